/* Rough plastic (Mitsuba `roughplastic`): a rough dielectric coating (microfacet
 * reflection F D G / (4 cos_i)) over a diffuse base. Light reaching the base
 * passes the rough coating twice, so the diffuse term is
 *   T(cos_i) T(cos_o) / eta^2 * rho / (1 - k) * cos_o / pi,
 * where T(mu) is the energy the rough interface transmits at incidence mu and
 * k = R_int (linear) or rho * R_int (nonlinear), R_int the hemispherical
 * reflectance of the coating seen from inside. As in Mitsuba, both count
 * single scattering only: T(mu) = E[(1 - F) G1(refracted)] and R(mu) =
 * E[F G1(reflected)] over visible normals, R_int = 2 mean_i R_in(mu_i) mu_i
 * over the table's cosines with the inverse IOR (total internal reflection
 * included). The energy the rough interface loses to its own shadowing is
 * lost, not reflected back to the base: counting it as reflected (R_int =
 * 1 - transmitted) made Mitsuba's linear-mode test image 18% too bright. Both are
 * integrated at construction with stratified visible-normal samples. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"
#include "celadon/sampling.h"

#define TABLE_SIZE 64   /* T(mu) at mu = i / (TABLE_SIZE - 1) */
#define STRATA 24       /* STRATA^2 samples per integral of T */
#define STRATA_INT 64   /* and of R_in (finer: the edge of total internal reflection) */

typedef struct {
    bsdf_spectrum diffuse_reflectance, specular_reflectance;
    microfacet distr;
    double eta, inv_eta2;
    double internal_reflectance;
    double specular_sampling_weight;
    int nonlinear;
    double transmittance[TABLE_SIZE];
} roughplastic_data;

/* Energy fractions of single scattering at a rough interface of relative IOR
 * eta for light arriving from above at cosine mu, over strata^2 visible
 * normals m: transmitted, E[(1 - F(wi.m)) G1(refracted)] (the expected
 * weight of a rough dielectric's transmission samples in importance mode),
 * or reflected, E[F(wi.m) G1(reflected)]. */
static double rough_interface(const microfacet *visible, double eta, double mu, int reflected, int strata)
{
    mu = fmax(mu, 1e-6);
    vec3 wi = v3(sqrt(fmax(0.0, 1.0 - mu * mu)), 0.0, mu);
    double sum = 0.0;
    for (int i = 0; i < strata; i++)
        for (int j = 0; j < strata; j++) {
            vec2 u = v2((i + 0.5) / strata, (j + 0.5) / strata);
            vec3 m = microfacet_sample(visible, wi, u, NULL);
            double cos_t, eta_ti;
            double f = fresnel_dielectric(v3_dot(wi, m), eta, &cos_t, NULL, &eta_ti);
            if (reflected)
                sum += f * microfacet_G1(visible, reflect_about(wi, m), m);
            else if (f < 1.0)
                sum += (1.0 - f) * microfacet_G1(visible, v3_norm(refract_about(wi, m, cos_t, eta_ti)), m);
        }
    return sum / (strata * strata);
}

static double table_lookup(const double *table, double mu)
{
    double x = fmin(fmax(mu, 0.0), 1.0) * (TABLE_SIZE - 1);
    int i = (int)x;
    if (i >= TABLE_SIZE - 1)
        return table[TABLE_SIZE - 1];
    double t = x - i;
    return table[i] * (1.0 - t) + table[i + 1] * t;
}

static rgb roughplastic_diffuse(const roughplastic_data *d, texture_point uv)
{
    rgb rho = spectrum_eval(&d->diffuse_reflectance, uv);
    rgb k = d->nonlinear ? rgb_scale(rho, d->internal_reflectance) : rgb_gray(d->internal_reflectance);
    return rgb_make(rho.r / (1.0 - k.r), rho.g / (1.0 - k.g), rho.b / (1.0 - k.b));
}

static double roughplastic_prob_specular(const roughplastic_data *d, double t_i)
{
    double ps = (1.0 - t_i) * d->specular_sampling_weight, pd = t_i * (1.0 - d->specular_sampling_weight);
    return ps + pd > 0.0 ? ps / (ps + pd) : 0.0;
}

static rgb roughplastic_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughplastic_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return rgb_gray(0.0);
    vec3 m;
    double dg = microfacet_reflection_dg(&d->distr, wi, wo, &m);
    double f = fresnel_dielectric(v3_dot(wi, m), d->eta, NULL, NULL, NULL);
    rgb spec = rgb_scale(spectrum_eval(&d->specular_reflectance, bsdf_at(q)), f * dg / (4.0 * wi.z));
    double t = table_lookup(d->transmittance, wi.z) * table_lookup(d->transmittance, wo.z);
    rgb diff = rgb_scale(roughplastic_diffuse(d, bsdf_at(q)), d->inv_eta2 * t * wo.z / M_PI);
    return rgb_add(spec, diff);
}

static double roughplastic_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const roughplastic_data *d = b->data;
    vec3 wi = q->wi;
    if (wi.z <= 0.0 || wo.z <= 0.0)
        return 0.0;
    double p_spec = roughplastic_prob_specular(d, table_lookup(d->transmittance, wi.z));
    double spec = microfacet_reflection_pdf(&d->distr, wi, wo);
    return p_spec * spec + (1.0 - p_spec) * warp_cosine_hemisphere_pdf(wo);
}

static int roughplastic_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const roughplastic_data *d = b->data;
    if (q->wi.z <= 0.0)
        return 0;
    double p_spec = roughplastic_prob_specular(d, table_lookup(d->transmittance, q->wi.z));
    out->eta = 1.0;
    if (u1 < p_spec) {
        vec3 m = microfacet_sample(&d->distr, q->wi, u2, NULL);
        out->wo = reflect_about(q->wi, m);
        out->sampled_type = BSDF_GLOSSY_REFLECTION;
    } else {
        out->wo = warp_square_to_cosine_hemisphere(u2);
        out->sampled_type = BSDF_DIFFUSE_REFLECTION;
    }
    if (out->wo.z <= 0.0)
        return 0;
    return bsdf_finish_sample(b, q, out);
}

static rgb roughplastic_albedo(const bsdf_t *b, texture_point uv)
{
    const roughplastic_data *d = b->data;
    return spectrum_eval(&d->diffuse_reflectance, uv);
}

static const bsdf_ops roughplastic_ops = {"roughplastic",
                                          roughplastic_sample, roughplastic_eval, roughplastic_pdf, roughplastic_albedo,
                                          NULL, NULL};

/* The coating's energy tables: T(mu) and the internal reflectance. */
static void roughplastic_tables(roughplastic_data *d)
{
    microfacet visible = d->distr;
    visible.sample_visible = 1;
    double r_int = 0.0;
    for (int i = 0; i < TABLE_SIZE; i++) {
        double mu = (double)i / (TABLE_SIZE - 1);
        d->transmittance[i] = rough_interface(&visible, d->eta, mu, 0, STRATA);
        r_int += rough_interface(&visible, 1.0 / d->eta, mu, 1, STRATA_INT) * fmax(mu, 1e-6);
    }
    d->internal_reflectance = 2.0 * r_int / TABLE_SIZE;
}

static bsdf_t *roughplastic_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    roughplastic_data d;
    double int_ior, ext_ior;
    microfacet_type distribution;
    if (bsdf_plastic_param(set, o, &int_ior, &ext_ior, &d.diffuse_reflectance, &d.specular_reflectance, &d.nonlinear,
                           err, errlen) != 0)
        return NULL;
    if (microfacet_type_parse(scene_obj_string(o, "distribution", "beckmann"), &distribution) != 0) {
        scene_obj_error(o, err, errlen, "unknown distribution");
        return NULL;
    }
    double alpha = scene_obj_float(o, "alpha", 0.1);
    int visible = scene_obj_bool(o, "sample_visible", true);
    if (bsdf_check_ior(o, int_ior, ext_ior, err, errlen) || bsdf_check_alpha(o, "alpha", alpha, err, errlen) ||
        bsdf_check_spectrum(o, "diffuse_reflectance", &d.diffuse_reflectance, err, errlen) ||
        bsdf_check_spectrum(o, "specular_reflectance", &d.specular_reflectance, err, errlen))
        return NULL;
    d.distr = microfacet_make(distribution, alpha, alpha, visible);
    d.eta = int_ior / ext_ior;
    d.inv_eta2 = 1.0 / (d.eta * d.eta);
    d.specular_sampling_weight = bsdf_specular_sampling_weight(&d.diffuse_reflectance, &d.specular_reflectance);
    roughplastic_tables(&d);
    return bsdf_alloc(o, &roughplastic_ops, BSDF_GLOSSY_REFLECTION | BSDF_DIFFUSE_REFLECTION | BSDF_FRONT_SIDE, &d,
                      sizeof d, err, errlen);
}

static const scene_param_decl roughplastic_params[] = {
    BSDF_PARAMS_PLASTIC,
    {"distribution", PARAM_STRING, 0, "beckmann|ggx"},
    {"alpha", PARAM_FLOAT, 0, NULL},
    {"sample_visible", PARAM_BOOL, 0, NULL},
    BSDF_PARAMS_END,
};

const bsdf_plugin bsdf_roughplastic = {
    .decl = {.cls = SCENE_BSDF, .type = "roughplastic", .params = roughplastic_params},
    .create = roughplastic_create,
};
