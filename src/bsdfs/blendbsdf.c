/* Mitsuba's `blendbsdf`: the mixture (1 - weight) f0 + weight f1 of its two
 * nested BSDFs, `weight` a float or texture (required) clamped to [0, 1].
 * Sampling picks the second with probability weight; a smooth sample is
 * then weighed against the whole mixture (pdf = (1 - w) p0 + w p1, weight
 * = mixture / pdf), as Mitsuba does, and a delta one keeps its own weight
 * with its probability scaled by the choice. */
#include "bsdfs/bsdf_impl.h"

typedef struct {
    bsdf_scalar weight;
    const bsdf_t *nested[2];
} blend_data;

static double blend_weight(const blend_data *d, texture_point uv)
{
    return fmin(fmax(scalar_eval(&d->weight, uv), 0.0), 1.0);
}

static rgb blend_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const blend_data *d = b->data;
    double w = blend_weight(d, bsdf_at(q));
    return rgb_add(rgb_scale(bsdf_eval(d->nested[0], q, wo), 1.0 - w), rgb_scale(bsdf_eval(d->nested[1], q, wo), w));
}

static double blend_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const blend_data *d = b->data;
    double w = blend_weight(d, bsdf_at(q));
    return (1.0 - w) * bsdf_pdf(d->nested[0], q, wo) + w * bsdf_pdf(d->nested[1], q, wo);
}

static int blend_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const blend_data *d = b->data;
    double w = blend_weight(d, bsdf_at(q));
    int second = u1 <= w && w > 0.0;
    double u = second ? u1 / w : (u1 - w) / (1.0 - w), choice = second ? w : 1.0 - w;
    if (!bsdf_sample(d->nested[second], q, fmin(u, 1.0 - 1e-16), u2, out))
        return 0;
    if (out->sampled_type & BSDF_DELTA) {
        out->pdf *= choice;
        return 1;
    }
    return bsdf_finish_sample(b, q, out);
}

static rgb blend_albedo(const bsdf_t *b, texture_point uv)
{
    const blend_data *d = b->data;
    double w = blend_weight(d, uv);
    return rgb_add(rgb_scale(bsdf_albedo_at(d->nested[0], uv), 1.0 - w), rgb_scale(bsdf_albedo_at(d->nested[1], uv), w));
}

static rgb blend_straight(const bsdf_t *b, const bsdf_query *q)
{
    const blend_data *d = b->data;
    double w = blend_weight(d, bsdf_at(q));
    return rgb_add(rgb_scale(bsdf_straight_transmittance(d->nested[0], q), 1.0 - w),
                   rgb_scale(bsdf_straight_transmittance(d->nested[1], q), w));
}

static const bsdf_ops blend_ops = {"blendbsdf", blend_sample, blend_eval, blend_pdf, blend_albedo, blend_straight, NULL};

static bsdf_t *blend_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    blend_data d;
    scene_obj *nested[2];
    scene_obj_children(o, SCENE_BSDF, nested, 2);
    if (bsdf_scalar_param(set, o, "weight", 0.5, &d.weight, err, errlen) != 0 ||
        !(d.nested[0] = bsdf_set_get(set, nested[0], err, errlen)) ||
        !(d.nested[1] = bsdf_set_get(set, nested[1], err, errlen)))
        return NULL;
    return bsdf_alloc(o, &blend_ops, bsdf_flags(d.nested[0]) | bsdf_flags(d.nested[1]), &d, sizeof d, err, errlen);
}

static const scene_param_decl blend_params[] = {{"weight", PARAM_FLOAT | PARAM_TEXTURE, PARAM_REQUIRED, NULL},
                                                BSDF_PARAMS_END};
static const scene_child_decl blend_children[] = {{SCENE_BSDF, 2, 2, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const bsdf_plugin bsdf_blendbsdf = {
    .decl = {.cls = SCENE_BSDF, .type = "blendbsdf", .params = blend_params, .children = blend_children},
    .create = blend_create,
};
