/* Mitsuba's `bumpmap`: the nested BSDF in the shading frame of the surface
 * displaced along its normal by `scale` (1) times the nested texture (of
 * any name; its luminance), the usual approximation that ignores the
 * normal's own variation: with g = scale grad h by (u, v),
 *   dp/du' = dp/du + n (g_u - n.dp/du),  dp/dv' = dp/dv + n (g_v - n.dp/dv),
 *   n' = normalize(dp/du' x dp/dv'), turned to the geometric normal's side,
 * the tangent dp/du made perpendicular to n'. `flip_invalid_normals` and
 * `use_shadowing_function` as for normalmap (true). Only variations of the
 * height change the frame: a constant offset does not. */
#include "bsdfs/bsdf_impl.h"

typedef struct {
    const bsdf_t *nested;
    const texture_t *height;
    double scale;
    bool flip_invalid, shadowing;
} bumpmap_data;

static bsdf_perturbed bumpmap_frame(const bumpmap_data *d, const bsdf_query *q)
{
    vec2 g = v2_scale(texture_eval_1_gradient(d->height, q->uv), d->scale);
    vec3 du = q->dpdu, dv = q->dpdv;
    du.z = g.x, dv.z = g.y; /* dp/du + n (g_u - n.dp/du), n = +z */
    vec3 n = v3_cross(du, dv);
    if (!(v3_len(n) > 1e-300)) /* no parametrisation: leave the frame */
        n = v3(0.0, 0.0, 1.0);
    n = v3_norm(n);
    vec3 ng = v3_len(q->ng) > 0.0 ? q->ng : v3(0.0, 0.0, 1.0);
    if (v3_dot(ng, n) < 0.0)
        n = v3_neg(n);
    return (bsdf_perturbed){bsdf_perturbed_frame(n, v3_len(q->dpdu) > 0.0 ? q->dpdu : v3(1.0, 0.0, 0.0), q,
                                                 d->flip_invalid),
                            d->shadowing};
}

static int bumpmap_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const bumpmap_data *d = b->data;
    bsdf_perturbed p = bumpmap_frame(d, q);
    return bsdf_perturbed_sample(d->nested, &p, q, u1, u2, out);
}

static rgb bumpmap_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const bumpmap_data *d = b->data;
    bsdf_perturbed p = bumpmap_frame(d, q);
    return bsdf_perturbed_eval(d->nested, &p, q, wo);
}

static double bumpmap_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const bumpmap_data *d = b->data;
    bsdf_perturbed p = bumpmap_frame(d, q);
    return bsdf_perturbed_pdf(d->nested, &p, q, wo);
}

static rgb bumpmap_albedo(const bsdf_t *b, vec2 uv)
{
    const bumpmap_data *d = b->data;
    return bsdf_albedo(d->nested, uv);
}

static vec3 bumpmap_shading_normal(const bsdf_t *b, const bsdf_query *q)
{
    return bumpmap_frame(b->data, q).f.n;
}

static const bsdf_ops bumpmap_ops = {"bumpmap",      bumpmap_sample, bumpmap_eval,          bumpmap_pdf,
                                     bumpmap_albedo, NULL,           bumpmap_shading_normal};

static bsdf_t *bumpmap_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    bumpmap_data d;
    if (!(d.height = texture_set_get(set->textures, scene_obj_child(o, SCENE_TEXTURE), err, errlen)) ||
        !(d.nested = bsdf_set_get(set, scene_obj_child(o, SCENE_BSDF), err, errlen)))
        return NULL;
    d.scale = scene_obj_float(o, "scale", 1.0);
    d.flip_invalid = scene_obj_bool(o, "flip_invalid_normals", true);
    d.shadowing = scene_obj_bool(o, "use_shadowing_function", true);
    return bsdf_alloc(o, &bumpmap_ops, bsdf_flags(d.nested), &d, sizeof d, err, errlen);
}

static const scene_param_decl bumpmap_params[] = {
    {"scale", PARAM_FLOAT, 0, NULL},
    {"flip_invalid_normals", PARAM_BOOL, 0, NULL},
    {"use_shadowing_function", PARAM_BOOL, 0, NULL},
    BSDF_PARAMS_END,
};
static const scene_child_decl bumpmap_children[] = {
    {SCENE_BSDF, 1, 1, NULL},
    {SCENE_TEXTURE, 1, 1, NULL},
    {SCENE_SCENE, 0, 0, NULL},
};

const bsdf_plugin bsdf_bumpmap = {
    .decl = {.cls = SCENE_BSDF, .type = "bumpmap", .params = bumpmap_params, .children = bumpmap_children},
    .create = bumpmap_create,
};
