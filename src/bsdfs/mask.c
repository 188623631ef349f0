/* Mitsuba's `mask` BSDF: the nested BSDF where the surface is there, with
 * probability `opacity` (a float or texture, 0.5 by default, clamped to
 * [0, 1]), and a null lobe elsewhere: light goes on straight through with
 * probability 1 - opacity. eval and pdf are opacity times the nested ones;
 * a shadow ray crosses the surface with the transmittance
 * 1 - opacity (1 - the nested one's). */
#include "bsdfs/bsdf_impl.h"

typedef struct {
    bsdf_scalar opacity;
    const bsdf_t *nested;
} mask_data;

static double mask_opacity(const mask_data *d, texture_point uv)
{
    return fmin(fmax(scalar_eval(&d->opacity, uv), 0.0), 1.0);
}

static int mask_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const mask_data *d = b->data;
    double opacity = mask_opacity(d, bsdf_at(q));
    if (u1 < opacity) {
        if (!bsdf_sample(d->nested, q, u1 / opacity, u2, out))
            return 0;
        out->pdf *= opacity; /* the weight stays: opacity f / (opacity pdf) */
        return 1;
    }
    out->wo = v3_neg(q->wi);
    out->pdf = 1.0 - opacity;
    out->eta = 1.0;
    out->sampled_type = BSDF_NULL | BSDF_STRAIGHT_TRANSMISSION;
    out->weight = rgb_gray(1.0);
    return 1;
}

static rgb mask_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const mask_data *d = b->data;
    return rgb_scale(bsdf_eval(d->nested, q, wo), mask_opacity(d, bsdf_at(q)));
}

static double mask_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const mask_data *d = b->data;
    return bsdf_pdf(d->nested, q, wo) * mask_opacity(d, bsdf_at(q));
}

static rgb mask_albedo(const bsdf_t *b, texture_point uv)
{
    const mask_data *d = b->data;
    return bsdf_albedo_at(d->nested, uv);
}

static rgb mask_straight(const bsdf_t *b, const bsdf_query *q)
{
    const mask_data *d = b->data;
    rgb nested = bsdf_straight_transmittance(d->nested, q);
    double opacity = mask_opacity(d, bsdf_at(q));
    return rgb_make(1.0 - opacity * (1.0 - nested.r), 1.0 - opacity * (1.0 - nested.g),
                    1.0 - opacity * (1.0 - nested.b));
}

static const bsdf_ops mask_ops = {"mask", mask_sample, mask_eval, mask_pdf, mask_albedo, mask_straight, NULL};

static bsdf_t *mask_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    mask_data d;
    if (bsdf_scalar_param(set, o, "opacity", 0.5, &d.opacity, err, errlen) != 0 ||
        !(d.nested = bsdf_set_get(set, scene_obj_child(o, SCENE_BSDF), err, errlen)))
        return NULL;
    unsigned flags = bsdf_flags(d.nested) | BSDF_NULL | BSDF_STRAIGHT_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE;
    return bsdf_alloc(o, &mask_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl mask_params[] = {{"opacity", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}, BSDF_PARAMS_END};
static const scene_child_decl mask_children[] = {{SCENE_BSDF, 1, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const bsdf_plugin bsdf_mask = {
    .decl = {.cls = SCENE_BSDF, .type = "mask", .params = mask_params, .children = mask_children},
    .create = mask_create,
};
