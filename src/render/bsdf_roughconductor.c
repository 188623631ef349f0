/* Rough conductor (Mitsuba `roughconductor`): Torrance-Sparrow microfacet
 * reflection f = F(wi.m) D(m) G(wi, wo) / (4 cos_i cos_o), front side only. */
#include "celadon/fresnel.h"
#include "render/bsdf_impl.h"

typedef struct {
    rgb eta, k;
    microfacet distr;
    bsdf_spectrum specular_reflectance;
} roughconductor_data;

static rgb roughconductor_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughconductor_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return rgb_gray(0.0);
    vec3 m;
    double dg = microfacet_reflection_dg(&d->distr, wi, wo, &m);
    if (dg == 0.0)
        return rgb_gray(0.0);
    rgb f = fresnel_conductor_rgb(v3_dot(wi, m), d->eta, d->k);
    return rgb_scale(rgb_mul(f, spectrum_eval(&d->specular_reflectance, q->uv)), dg / (4.0 * wi.z));
}

static double roughconductor_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughconductor_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return 0.0;
    return microfacet_reflection_pdf(&d->distr, wi, wo);
}

static int roughconductor_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u1;
    const roughconductor_data *d = b->data;
    if (q->wi.z <= 0.0)
        return 0;
    vec3 m = microfacet_sample(&d->distr, q->wi, u2, NULL);
    out->wo = reflect_about(q->wi, m);
    if (out->wo.z <= 0.0)
        return 0;
    out->eta = 1.0;
    out->sampled_type = BSDF_GLOSSY_REFLECTION;
    return bsdf_finish_sample(b, q, out);
}

static rgb roughconductor_albedo(const bsdf_t *b, vec2 uv)
{
    const roughconductor_data *d = b->data;
    return rgb_mul(spectrum_eval(&d->specular_reflectance, uv), fresnel_conductor_rgb(1.0, d->eta, d->k));
}

static const bsdf_ops roughconductor_ops = {roughconductor_sample, roughconductor_eval, roughconductor_pdf,
                                            roughconductor_albedo, NULL};

bsdf_roughconductor_params bsdf_roughconductor_defaults(void)
{
    bsdf_roughconductor_params p;
    bsdf_conductor_preset("none", &p.eta, &p.k);
    p.distribution = MICROFACET_BECKMANN;
    p.alpha_u = p.alpha_v = 0.1;
    p.sample_visible = 1;
    p.specular_reflectance = bsdf_spectrum_const(rgb_gray(1.0));
    return p;
}

bsdf_t *bsdf_create_roughconductor(const bsdf_roughconductor_params *p, char *err, size_t errlen)
{
    bsdf_spectrum eta = bsdf_spectrum_const(p->eta), k = bsdf_spectrum_const(p->k);
    if (bsdf_check_spectrum("eta", &eta, err, errlen) || bsdf_check_spectrum("k", &k, err, errlen) ||
        bsdf_check_spectrum("specular_reflectance", &p->specular_reflectance, err, errlen) ||
        bsdf_check_alpha("alpha_u", p->alpha_u, err, errlen) || bsdf_check_alpha("alpha_v", p->alpha_v, err, errlen))
        return NULL;
    bsdf_t *b = bsdf_alloc("roughconductor", &roughconductor_ops, BSDF_GLOSSY_REFLECTION | BSDF_FRONT_SIDE,
                           sizeof(roughconductor_data), err, errlen);
    if (b)
        *(roughconductor_data *)b->data = (roughconductor_data){
            p->eta, p->k, microfacet_make(p->distribution, p->alpha_u, p->alpha_v, p->sample_visible),
            p->specular_reflectance};
    return b;
}
