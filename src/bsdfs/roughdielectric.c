/* Rough dielectric interface (Mitsuba `roughdielectric`), after Walter et al.
 * 2007: microfacet reflection F D G / (4 |cos_i|) and transmission
 *   (1 - F) D G |wi.m| |wo.m| eta^2 / (|cos_i| (wi.m + eta wo.m)^2),
 * eta = n_o / n_i, scaled by 1 / eta^2 in radiance mode. Both sides scatter;
 * from the back the microfacet distribution is mirrored. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

typedef struct {
    double eta; /* int_ior / ext_ior */
    bsdf_roughness roughness;
    bsdf_spectrum specular_reflectance, specular_transmittance;
} roughdielectric_data;

/* The generalised half vector of (wi, wo), oriented to +z; 0 when degenerate. */
static int half_vector(const roughdielectric_data *d, vec3 wi, vec3 wo, vec3 *m, int *reflect, double *eta_rel)
{
    double ci = wi.z, co = wo.z;
    if (ci == 0.0 || co == 0.0)
        return 0;
    *reflect = ci * co > 0.0;
    *eta_rel = ci > 0.0 ? d->eta : 1.0 / d->eta;
    vec3 h = v3_add(wi, v3_scale(wo, *reflect ? 1.0 : *eta_rel));
    double len = v3_len(h);
    if (!(len > 1e-12))
        return 0;
    h = v3_scale(h, (h.z < 0.0 ? -1.0 : 1.0) / len);
    /* Both directions must see the facet from their own side. */
    if (v3_dot(wi, h) * ci <= 0.0 || v3_dot(wo, h) * co <= 0.0)
        return 0;
    *m = h;
    return 1;
}

static rgb roughdielectric_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughdielectric_data *d = b->data;
    vec3 wi = q->wi, m;
    int reflect;
    double eta;
    if (!half_vector(d, wi, wo, &m, &reflect, &eta))
        return rgb_gray(0.0);
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    double dg = microfacet_D(&distr, m) * microfacet_G(&distr, wi, wo, m);
    if (dg == 0.0)
        return rgb_gray(0.0);
    double wi_m = v3_dot(wi, m), wo_m = v3_dot(wo, m);
    double f = fresnel_dielectric(wi_m, d->eta, NULL, NULL, NULL);
    if (reflect)
        return rgb_scale(spectrum_eval(&d->specular_reflectance, bsdf_at(q)), f * dg / (4.0 * fabs(wi.z)));
    double denom = wi_m + eta * wo_m;
    double scale = q->mode == TRANSPORT_RADIANCE ? 1.0 / (eta * eta) : 1.0;
    double value = fabs(scale * (1.0 - f) * dg * eta * eta * wi_m * wo_m / (wi.z * denom * denom));
    return rgb_scale(spectrum_eval(&d->specular_transmittance, bsdf_at(q)), value);
}

static double roughdielectric_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughdielectric_data *d = b->data;
    vec3 wi = q->wi, m;
    int reflect;
    double eta;
    if (!half_vector(d, wi, wo, &m, &reflect, &eta))
        return 0.0;
    vec3 wi_up = wi.z > 0.0 ? wi : v3_neg(wi);
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    double pm = microfacet_pdf(&distr, wi_up, m);
    double wi_m = v3_dot(wi, m), wo_m = v3_dot(wo, m);
    double f = fresnel_dielectric(wi_m, d->eta, NULL, NULL, NULL);
    if (reflect)
        return f * pm / (4.0 * fabs(wo_m));
    double denom = wi_m + eta * wo_m;
    return (1.0 - f) * pm * eta * eta * fabs(wo_m) / (denom * denom);
}

static int roughdielectric_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const roughdielectric_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z == 0.0)
        return 0;
    vec3 wi_up = wi.z > 0.0 ? wi : v3_neg(wi);
    double pm;
    microfacet distr = bsdf_roughness_at(&d->roughness, bsdf_at(q));
    vec3 m = microfacet_sample(&distr, wi_up, u2, &pm);
    if (!(pm > 0.0))
        return 0;
    double cos_t, eta_it, eta_ti;
    double f = fresnel_dielectric(v3_dot(wi, m), d->eta, &cos_t, &eta_it, &eta_ti);
    if (u1 <= f) {
        out->wo = reflect_about(wi, m);
        out->eta = 1.0;
        out->sampled_type = BSDF_GLOSSY_REFLECTION;
        if (out->wo.z * wi.z <= 0.0)
            return 0;
    } else {
        out->wo = v3_norm(refract_about(wi, m, cos_t, eta_ti));
        out->eta = eta_it;
        out->sampled_type = BSDF_GLOSSY_TRANSMISSION;
        if (out->wo.z * wi.z >= 0.0)
            return 0;
    }
    return bsdf_finish_sample(b, q, out);
}

static rgb roughdielectric_albedo(const bsdf_t *b, texture_point uv)
{
    const roughdielectric_data *d = b->data;
    return spectrum_eval(&d->specular_transmittance, uv);
}

static const bsdf_ops roughdielectric_ops = {"roughdielectric",
                                             roughdielectric_sample, roughdielectric_eval, roughdielectric_pdf,
                                             roughdielectric_albedo, NULL, NULL};

static bsdf_t *roughdielectric_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    roughdielectric_data d;
    double int_ior, ext_ior;
    if (bsdf_dielectric_param(set, o, &int_ior, &ext_ior, &d.specular_reflectance, &d.specular_transmittance, err,
                              errlen) != 0 ||
        bsdf_roughness_param(set, o, &d.roughness, err, errlen) != 0)
        return NULL;
    if (bsdf_check_ior(o, int_ior, ext_ior, err, errlen) || bsdf_check_spectrum(o, "specular_reflectance", &d.specular_reflectance, err, errlen) ||
        bsdf_check_spectrum(o, "specular_transmittance", &d.specular_transmittance, err, errlen))
        return NULL;
    d.eta = int_ior / ext_ior;
    unsigned flags = BSDF_GLOSSY_REFLECTION | BSDF_GLOSSY_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE |
                     bsdf_roughness_flags(&d.roughness);
    return bsdf_alloc(o, &roughdielectric_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl roughdielectric_params[] = {BSDF_PARAMS_DIELECTRIC, BSDF_PARAMS_ROUGHNESS,
                                                          BSDF_PARAMS_END};

const bsdf_plugin bsdf_roughdielectric = {
    .decl = {.cls = SCENE_BSDF, .type = "roughdielectric", .params = roughdielectric_params,
             .exclusive = {"alpha", "alpha_u"}},
    .create = roughdielectric_create,
};
