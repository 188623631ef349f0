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
    bsdf_perturbing base; /* first: the perturbing ops read it */
    const texture_t *height;
    double scale;
} bumpmap_data;

static void bumpmap_normal(const void *data, const bsdf_query *q, vec3 *n, vec3 *tangent)
{
    const bumpmap_data *d = data;
    vec2 g = v2_scale(texture_eval_1_gradient(d->height, q->uv), d->scale);
    vec3 du = q->dpdu, dv = q->dpdv;
    du.z = g.x, dv.z = g.y; /* dp/du + n (g_u - n.dp/du), n = +z */
    *n = v3_cross(du, dv);  /* zero without a parametrisation: the frame stays */
    vec3 ng = v3_len(q->ng) > 0.0 ? q->ng : v3(0.0, 0.0, 1.0);
    if (v3_dot(ng, *n) < 0.0)
        *n = v3_neg(*n);
    *tangent = v3_len(q->dpdu) > 0.0 ? q->dpdu : v3(1.0, 0.0, 0.0);
}

static const bsdf_ops bumpmap_ops = BSDF_PERTURBING_OPS("bumpmap");

static bsdf_t *bumpmap_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    bumpmap_data d = {.base.normal = bumpmap_normal};
    if (!(d.height = texture_set_get(set->textures, scene_obj_child(o, SCENE_TEXTURE), err, errlen)) ||
        bsdf_perturbing_param(set, o, &d.base, err, errlen) != 0)
        return NULL;
    d.scale = scene_obj_float(o, "scale", 1.0);
    return bsdf_alloc(o, &bumpmap_ops, bsdf_flags(d.base.nested), &d, sizeof d, err, errlen);
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
