/* Lambertian reflector (Mitsuba `diffuse`): f = reflectance / pi, front side only. */
#include "celadon/sampling.h"
#include "bsdfs/bsdf_impl.h"

typedef struct {
    bsdf_spectrum reflectance;
} diffuse_data;

static int diffuse_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u1;
    const diffuse_data *d = b->data;
    if (q->wi.z <= 0.0)
        return 0;
    out->wo = warp_square_to_cosine_hemisphere(u2);
    out->pdf = warp_cosine_hemisphere_pdf(out->wo);
    if (!(out->pdf > 0.0))
        return 0;
    out->weight = spectrum_eval(&d->reflectance, bsdf_at(q));
    out->eta = 1.0;
    out->sampled_type = BSDF_DIFFUSE_REFLECTION;
    return 1;
}

static rgb diffuse_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const diffuse_data *d = b->data;
    if (q->wi.z <= 0.0 || wo.z <= 0.0)
        return rgb_gray(0.0);
    return rgb_scale(spectrum_eval(&d->reflectance, bsdf_at(q)), wo.z / M_PI);
}

static double diffuse_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    (void)b;
    return q->wi.z > 0.0 ? warp_cosine_hemisphere_pdf(wo) : 0.0;
}

static rgb diffuse_albedo(const bsdf_t *b, texture_point uv)
{
    const diffuse_data *d = b->data;
    return spectrum_eval(&d->reflectance, uv);
}

static const bsdf_ops diffuse_ops = {"diffuse", diffuse_sample, diffuse_eval, diffuse_pdf, diffuse_albedo, NULL, NULL};

static bsdf_t *diffuse_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    diffuse_data d;
    if (bsdf_spectrum_param(set, o, "reflectance", 0.5, &d.reflectance, err, errlen) != 0 ||
        bsdf_check_spectrum(o, "reflectance", &d.reflectance, err, errlen) != 0)
        return NULL;
    return bsdf_alloc(o, &diffuse_ops, BSDF_DIFFUSE_REFLECTION | BSDF_FRONT_SIDE, &d, sizeof d, err, errlen);
}

static const scene_param_decl diffuse_params[] = {
    {"reflectance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
    BSDF_PARAMS_END,
};

const bsdf_plugin bsdf_diffuse = {
    .decl = {.cls = SCENE_BSDF, .type = "diffuse", .params = diffuse_params},
    .create = diffuse_create,
};
