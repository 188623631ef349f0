/* Mitsuba's `normalmap`: the nested BSDF in the shading frame whose normal
 * the `normalmap` texture gives, 2 rgb - 1 in Mitsuba's shading frame (x
 * along dp/du projected on the tangent plane, z the shading normal): a map
 * of (0.5, 0.5, 1) everywhere changes nothing. `flip_invalid_normals`
 * (true) mirrors a normal that wi sees from behind; `use_shadowing_function`
 * (true) applies Mitsuba's shadowing term for the bump terminator. */
#include "bsdfs/bsdf_impl.h"

typedef struct {
    const bsdf_t *nested;
    bsdf_spectrum normals;
    bool flip_invalid, shadowing;
} normalmap_data;

static bsdf_perturbed normalmap_frame(const normalmap_data *d, const bsdf_query *q)
{
    rgb c = spectrum_eval(&d->normals, q->uv);
    vec3 m = v3(2.0 * c.r - 1.0, 2.0 * c.g - 1.0, 2.0 * c.b - 1.0); /* in Mitsuba's frame */
    vec3 s = bsdf_query_tangent(q), t = v3(-s.y, s.x, 0.0);          /* its axes in the local one */
    vec3 n = v3_add(v3_add(v3_scale(s, m.x), v3_scale(t, m.y)), v3(0.0, 0.0, m.z));
    if (!(v3_len(n) > 0.0))
        n = v3(0.0, 0.0, 1.0);
    return (bsdf_perturbed){bsdf_perturbed_frame(n, s, q, d->flip_invalid), d->shadowing};
}

static int normalmap_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const normalmap_data *d = b->data;
    bsdf_perturbed p = normalmap_frame(d, q);
    return bsdf_perturbed_sample(d->nested, &p, q, u1, u2, out);
}

static rgb normalmap_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const normalmap_data *d = b->data;
    bsdf_perturbed p = normalmap_frame(d, q);
    return bsdf_perturbed_eval(d->nested, &p, q, wo);
}

static double normalmap_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const normalmap_data *d = b->data;
    bsdf_perturbed p = normalmap_frame(d, q);
    return bsdf_perturbed_pdf(d->nested, &p, q, wo);
}

static rgb normalmap_albedo(const bsdf_t *b, vec2 uv)
{
    const normalmap_data *d = b->data;
    return bsdf_albedo(d->nested, uv);
}

static vec3 normalmap_shading_normal(const bsdf_t *b, const bsdf_query *q)
{
    return normalmap_frame(b->data, q).f.n;
}

static const bsdf_ops normalmap_ops = {"normalmap",      normalmap_sample, normalmap_eval,          normalmap_pdf,
                                       normalmap_albedo, NULL,             normalmap_shading_normal};

static bsdf_t *normalmap_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    normalmap_data d;
    if (bsdf_spectrum_param(set, o, "normalmap", 0.0, &d.normals, err, errlen) != 0 ||
        !(d.nested = bsdf_set_get(set, scene_obj_child(o, SCENE_BSDF), err, errlen)))
        return NULL;
    d.flip_invalid = scene_obj_bool(o, "flip_invalid_normals", true);
    d.shadowing = scene_obj_bool(o, "use_shadowing_function", true);
    return bsdf_alloc(o, &normalmap_ops, bsdf_flags(d.nested), &d, sizeof d, err, errlen);
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
