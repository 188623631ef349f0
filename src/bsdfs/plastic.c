/* Smooth plastic (Mitsuba `plastic`): a specular dielectric coating over a
 * diffuse base, with internal scattering between base and coating folded
 * into the diffuse term (Weidlich & Wilkie 2007, as Mitsuba does):
 *   delta lobe:  F(cos_i) * specular_reflectance;
 *   diffuse:     (1 - F(cos_i)) (1 - F(cos_o)) / eta^2 * rho / (1 - k) * cos_o / pi,
 * with k = fdr_int (linear) or rho * fdr_int (nonlinear), fdr_int the diffuse
 * Fresnel reflectance of the coating seen from inside. Front side only. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"
#include "celadon/sampling.h"

typedef struct {
    bsdf_spectrum diffuse_reflectance, specular_reflectance;
    double eta, inv_eta2, fdr_int;
    double specular_sampling_weight;
    int nonlinear;
} plastic_data;

/* The diffuse albedo after internal scattering, rho / (1 - k). */
static rgb plastic_diffuse(const plastic_data *d, texture_point uv)
{
    rgb rho = spectrum_eval(&d->diffuse_reflectance, uv);
    rgb k = d->nonlinear ? rgb_scale(rho, d->fdr_int) : rgb_gray(d->fdr_int);
    return rgb_make(rho.r / (1.0 - k.r), rho.g / (1.0 - k.g), rho.b / (1.0 - k.b));
}

/* Probability of choosing the specular lobe given the Fresnel term at wi. */
static double plastic_prob_specular(const plastic_data *d, double f_i)
{
    double ps = f_i * d->specular_sampling_weight, pd = (1.0 - f_i) * (1.0 - d->specular_sampling_weight);
    return ps + pd > 0.0 ? ps / (ps + pd) : 0.0;
}

static int plastic_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const plastic_data *d = b->data;
    double ci = q->wi.z;
    if (ci <= 0.0)
        return 0;
    double f_i = fresnel_dielectric(ci, d->eta, NULL, NULL, NULL);
    double p_spec = plastic_prob_specular(d, f_i);
    out->eta = 1.0;
    if (u1 < p_spec) {
        out->wo = reflect_local(q->wi);
        out->pdf = p_spec;
        out->sampled_type = BSDF_DELTA_REFLECTION;
        out->weight = rgb_scale(spectrum_eval(&d->specular_reflectance, bsdf_at(q)), f_i / p_spec);
        return 1;
    }
    out->wo = warp_square_to_cosine_hemisphere(u2);
    if (out->wo.z <= 0.0)
        return 0;
    double f_o = fresnel_dielectric(out->wo.z, d->eta, NULL, NULL, NULL);
    double p_diff = 1.0 - p_spec;
    out->pdf = p_diff * warp_cosine_hemisphere_pdf(out->wo);
    out->sampled_type = BSDF_DIFFUSE_REFLECTION;
    out->weight = rgb_scale(plastic_diffuse(d, bsdf_at(q)), d->inv_eta2 * (1.0 - f_i) * (1.0 - f_o) / p_diff);
    return 1;
}

static rgb plastic_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const plastic_data *d = b->data;
    if (q->wi.z <= 0.0 || wo.z <= 0.0)
        return rgb_gray(0.0);
    double f_i = fresnel_dielectric(q->wi.z, d->eta, NULL, NULL, NULL);
    double f_o = fresnel_dielectric(wo.z, d->eta, NULL, NULL, NULL);
    return rgb_scale(plastic_diffuse(d, bsdf_at(q)), d->inv_eta2 * (1.0 - f_i) * (1.0 - f_o) * wo.z / M_PI);
}

static double plastic_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const plastic_data *d = b->data;
    if (q->wi.z <= 0.0 || wo.z <= 0.0)
        return 0.0;
    double f_i = fresnel_dielectric(q->wi.z, d->eta, NULL, NULL, NULL);
    return (1.0 - plastic_prob_specular(d, f_i)) * warp_cosine_hemisphere_pdf(wo);
}

static rgb plastic_albedo(const bsdf_t *b, texture_point uv)
{
    const plastic_data *d = b->data;
    return spectrum_eval(&d->diffuse_reflectance, uv);
}

static const bsdf_ops plastic_ops = {"plastic", plastic_sample, plastic_eval, plastic_pdf, plastic_albedo, NULL, NULL};

static bsdf_t *plastic_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    plastic_data d;
    double int_ior, ext_ior;
    if (bsdf_plastic_param(set, o, &int_ior, &ext_ior, &d.diffuse_reflectance, &d.specular_reflectance, &d.nonlinear,
                           err, errlen) != 0 ||
        bsdf_check_ior(o, int_ior, ext_ior, err, errlen) ||
        bsdf_check_spectrum(o, "diffuse_reflectance", &d.diffuse_reflectance, err, errlen) ||
        bsdf_check_spectrum(o, "specular_reflectance", &d.specular_reflectance, err, errlen))
        return NULL;
    d.eta = int_ior / ext_ior;
    d.inv_eta2 = 1.0 / (d.eta * d.eta);
    d.fdr_int = fresnel_diffuse_reflectance(1.0 / d.eta);
    d.specular_sampling_weight = bsdf_specular_sampling_weight(&d.diffuse_reflectance, &d.specular_reflectance);
    return bsdf_alloc(o, &plastic_ops, BSDF_DELTA_REFLECTION | BSDF_DIFFUSE_REFLECTION | BSDF_FRONT_SIDE, &d,
                      sizeof d, err, errlen);
}

static const scene_param_decl plastic_params[] = {BSDF_PARAMS_PLASTIC, BSDF_PARAMS_END};

const bsdf_plugin bsdf_plastic = {
    .decl = {.cls = SCENE_BSDF, .type = "plastic", .params = plastic_params},
    .create = plastic_create,
};
