/* Mitsuba's `normalmap`: the nested BSDF in the shading frame whose normal
 * the `normalmap` texture gives, 2 rgb - 1 in Mitsuba's shading frame (x
 * along dp/du projected on the tangent plane, z the shading normal): a map
 * of (0.5, 0.5, 1) everywhere changes nothing. `flip_invalid_normals`
 * (true) mirrors a normal that wi sees from behind; `use_shadowing_function`
 * (true) applies Mitsuba's shadowing term for the bump terminator
 * (perturbed_frame.c does both). */
#include "bsdfs/bsdf_impl.h"

typedef struct {
    bsdf_perturbing base; /* first: the perturbing ops read it */
    bsdf_spectrum normals;
} normalmap_data;

static void normalmap_normal(const void *data, const bsdf_query *q, vec3 *n, vec3 *tangent)
{
    const normalmap_data *d = data;
    rgb c = spectrum_eval(&d->normals, bsdf_at(q));
    vec3 m = v3(2.0 * c.r - 1.0, 2.0 * c.g - 1.0, 2.0 * c.b - 1.0); /* in Mitsuba's frame */
    vec3 s = bsdf_query_tangent(q), t = v3(-s.y, s.x, 0.0);          /* its axes in the local one */
    *n = v3_add(v3_add(v3_scale(s, m.x), v3_scale(t, m.y)), v3(0.0, 0.0, m.z));
    *tangent = s;
}

static const bsdf_ops normalmap_ops = BSDF_PERTURBING_OPS("normalmap");

static bsdf_t *normalmap_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    normalmap_data d = {.base.normal = normalmap_normal};
    if (bsdf_spectrum_param(set, o, "normalmap", 0.0, &d.normals, err, errlen) != 0 ||
        bsdf_perturbing_param(set, o, &d.base, err, errlen) != 0)
        return NULL;
    return bsdf_alloc(o, &normalmap_ops, bsdf_flags(d.base.nested), &d, sizeof d, err, errlen);
}

static const scene_param_decl normalmap_params[] = {
    {"normalmap", PARAM_COLOR | PARAM_TEXTURE, PARAM_REQUIRED, NULL},
    {"flip_invalid_normals", PARAM_BOOL, 0, NULL},
    {"use_shadowing_function", PARAM_BOOL, 0, NULL},
    BSDF_PARAMS_END,
};
static const scene_child_decl normalmap_children[] = {{SCENE_BSDF, 1, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const bsdf_plugin bsdf_normalmap = {
    .decl = {.cls = SCENE_BSDF, .type = "normalmap", .params = normalmap_params, .children = normalmap_children},
    .create = normalmap_create,
};
