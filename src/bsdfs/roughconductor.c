/* Rough conductor (Mitsuba `roughconductor`): Torrance-Sparrow microfacet
 * reflection f = F(wi.m) D(m) G(wi, wo) / (4 cos_i cos_o), front side only. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

typedef struct {
    rgb eta, k;
    bsdf_roughness roughness;
    bsdf_spectrum specular_reflectance;
} roughconductor_data;

static rgb roughconductor_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughconductor_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return rgb_gray(0.0);
    vec3 m;
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    double dg = microfacet_reflection_dg(&distr, wi, wo, &m);
    if (dg == 0.0)
        return rgb_gray(0.0);
    rgb f = fresnel_conductor_rgb(v3_dot(wi, m), d->eta, d->k);
    return rgb_scale(rgb_mul(f, spectrum_eval(&d->specular_reflectance, bsdf_at(q))), dg / (4.0 * wi.z));
}

static double roughconductor_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughconductor_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return 0.0;
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    return microfacet_reflection_pdf(&distr, wi, wo);
}

static int roughconductor_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u1;
    const roughconductor_data *d = b->data;
    if (q->wi.z <= 0.0)
        return 0;
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    vec3 m = microfacet_sample(&distr, q->wi, u2, NULL);
    out->wo = reflect_about(q->wi, m);
    if (out->wo.z <= 0.0)
        return 0;
    out->eta = 1.0;
    out->sampled_type = BSDF_GLOSSY_REFLECTION;
    return bsdf_finish_sample(b, q, out);
}

static rgb roughconductor_albedo(const bsdf_t *b, texture_point uv)
{
    const roughconductor_data *d = b->data;
    return rgb_mul(spectrum_eval(&d->specular_reflectance, uv), fresnel_conductor_rgb(1.0, d->eta, d->k));
}

static const bsdf_ops roughconductor_ops = {"roughconductor",
                                            roughconductor_sample, roughconductor_eval, roughconductor_pdf,
                                            roughconductor_albedo, NULL, NULL};

static bsdf_t *roughconductor_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    roughconductor_data d;
    if (bsdf_conductor_param(o, &d.eta, &d.k, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "specular_reflectance", 1.0, &d.specular_reflectance, err, errlen) != 0 ||
        bsdf_roughness_param(set, o, &d.roughness, err, errlen) != 0)
        return NULL;
    bsdf_spectrum eta = {d.eta, NULL}, k = {d.k, NULL};
    if (bsdf_check_spectrum(o, "eta", &eta, err, errlen) || bsdf_check_spectrum(o, "k", &k, err, errlen) ||
        bsdf_check_spectrum(o, "specular_reflectance", &d.specular_reflectance, err, errlen))
        return NULL;
    return bsdf_alloc(o, &roughconductor_ops,
                      BSDF_GLOSSY_REFLECTION | BSDF_FRONT_SIDE | bsdf_roughness_flags(&d.roughness), &d, sizeof d, err,
                      errlen);
}

static const scene_param_decl roughconductor_params[] = {BSDF_PARAMS_CONDUCTOR, BSDF_PARAMS_ROUGHNESS, BSDF_PARAMS_END};

const bsdf_plugin bsdf_roughconductor = {
    .decl = {.cls = SCENE_BSDF, .type = "roughconductor", .params = roughconductor_params,
             .exclusive = {"alpha", "alpha_u"}},
    .create = roughconductor_create,
};
