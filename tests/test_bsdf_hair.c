/* The `hair` BSDF (Chiang et al. 2016, as Mitsuba 3 and pbrt define it)
 * against independent truths: the white furnace (no absorption: eval
 * integrates to 1 over the sphere, its lobes' attenuations summing to 1),
 * pdf integrating to 1, sample() agreeing with eval() and pdf() and
 * following pdf() (chi-square), and eval at chosen configurations against
 * the model written from its definitions: Mp as the von Mises-Fisher lobe
 * integrated numerically around the fibre (not the Bessel closed form), Np
 * as the logistic normalised numerically over [-pi, pi], Ap from Fresnel's
 * equations and Beer-Lambert. Directions are in Mitsuba's fibre frame: y the
 * fibre's tangent, z the normal, x around the fibre (the query's dpdu is
 * zero, so the BSDF's frame is the query's). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "support/plugin_xml.h"
#include "support/test_build.h"
#include "test_bsdf_support.h"

enum { HAIR_CHI2_TESTS = 6 }; /* counted in CHI2_TESTS_IN_SUITE (test_bsdf_support.c) */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const bsdf_t *hair_bsdf(plugin_xml *fx, const char *params)
{
    char xml[1024], err[512];
    snprintf(xml, sizeof xml, "<bsdf type='hair'>%s</bsdf>", params);
    const bsdf_t *b = plugin_xml_bsdf(fx, xml, err, sizeof err);
    cr_assert_not_null(b, "%s: %s", params, err);
    return b;
}

/* wi at longitudinal angle theta to the cross-section and offset h across
 * the fibre (h = sin gamma, gamma the angle to the normal in the section;
 * Mitsuba's sign: h > 0 for x < 0). */
static bsdf_query fibre_query(double theta_deg, double h)
{
    double t = theta_deg * M_PI / 180.0, g = asin(h);
    bsdf_query q = {.uv = v2(0.5, 0.5), .mode = TRANSPORT_RADIANCE};
    q.wi = v3(-cos(t) * sin(g), sin(t), cos(t) * cos(g));
    return q;
}

/* The integrals over the sphere of eval (*f, which is 1 with no absorption)
 * and of pdf (*p, always 1), by the midpoint rule on n x 2n cells uniform in
 * (theta, phi), weighted by cos theta: fine enough near the poles, where a
 * lobe from light arriving at a grazing theta lies. */
static void sphere_integrals(const bsdf_t *b, const bsdf_query *q, int n, rgb *f, double *p)
{
    *f = rgb_gray(0.0), *p = 0.0;
    double d = M_PI / n;
    for (int i = 0; i < n; i++) {
        double theta = -M_PI / 2 + (i + 0.5) * d, c = cos(theta), y = sin(theta);
        for (int j = 0; j < 2 * n; j++) {
            double phi = (j + 0.5) * d;
            vec3 wo = v3(c * cos(phi), y, c * sin(phi));
            *f = rgb_add(*f, rgb_scale(bsdf_eval(b, q, wo), c * d * d));
            *p += bsdf_pdf(b, q, wo) * c * d * d;
        }
    }
}

static const char *const rough_fibres[] = {
    "<float name='longitudinal_roughness' value='0.3'/><float name='azimuthal_roughness' value='0.3'/>",
    "<float name='longitudinal_roughness' value='0.2'/><float name='azimuthal_roughness' value='0.8'/>"
    "<float name='scale_tilt' value='5'/>",
    "<float name='longitudinal_roughness' value='0.9'/><float name='azimuthal_roughness' value='0.25'/>"
    "<float name='int_ior' value='1.33'/>",
};

Test(bsdf_hair, white_furnace_and_pdf_integrate_to_one, .timeout = 120)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    for (int k = 0; k < 3; k++) {
        char params[512];
        snprintf(params, sizeof params, "<rgb name='sigma_a' value='0'/>%s", rough_fibres[k]);
        const bsdf_t *white = hair_bsdf(&fx, params);
        const double thetas[] = {0.0, 30.0, -60.0, 80.0}, hs[] = {0.5, -0.9};
        /* the sanitized build: every other angle, alternating by fibre */
        int step = test_build_case_step(2);
        for (int ti = step > 1 ? k % 2 : 0; ti < 4; ti += step)
            for (int hi = 0; hi < 2; hi++) {
                bsdf_query q = fibre_query(thetas[ti], hs[hi]);
                rgb f;
                double p;
                sphere_integrals(white, &q, 240, &f, &p);
                cr_expect(fabs(f.r - 1.0) < 2e-3 && fabs(f.g - 1.0) < 2e-3 && fabs(f.b - 1.0) < 2e-3,
                          "%s theta %g h %g: integral of eval %g %g %g, not 1", rough_fibres[k], thetas[ti], hs[hi],
                          f.r, f.g, f.b);
                cr_expect(fabs(p - 1.0) < 2e-3, "%s theta %g h %g: integral of pdf %g", rough_fibres[k], thetas[ti],
                          hs[hi], p);
            }
    }
    /* absorbing (the default brown pigments): less comes out, red the most */
    const bsdf_t *brown = hair_bsdf(&fx, "");
    bsdf_query q = fibre_query(20.0, 0.3);
    rgb f;
    double p;
    sphere_integrals(brown, &q, 120, &f, &p);
    cr_expect(f.r < 1.0 && f.b < f.g && f.g < f.r && f.b > 0.0, "brown hair's albedo %g %g %g", f.r, f.g, f.b);
    plugin_xml_close(&fx);
}

/* --------------------------------------------------------- the reference */

typedef struct {
    double beta_m, beta_n, alpha_deg, eta; /* eta relative to air (Mitsuba's 1.000277) */
    rgb sigma_a;
} fibre;

static double fresnel_ref(double cos_i, double eta)
{
    double sin_t = sqrt(fmax(0.0, 1.0 - cos_i * cos_i)) / eta;
    if (sin_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin_t * sin_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* The vMF lobe of concentration 1/v around the mirror direction of the
 * cone at theta_i, integrated over the azimuth by the midpoint rule: the
 * density per unit solid angle averaged over a turn around the fibre. */
static double mp_ref(double theta_i, double theta_o, double v)
{
    double kappa = 1.0 / v, theta_r = -theta_i, sum = 0.0;
    const int n = 20000;
    for (int j = 0; j < n; j++) {
        double phi = (j + 0.5) * 2.0 * M_PI / n;
        double dot = sin(theta_r) * sin(theta_o) + cos(theta_r) * cos(theta_o) * cos(phi);
        sum += exp(kappa * (dot - 1.0));
    }
    double c = kappa / (4.0 * M_PI * (1.0 - exp(-2.0 * kappa))) * 2.0; /* kappa / (4 pi sinh kappa) e^kappa */
    return c * sum / n;
}

static double logistic_ref(double x, double s) { return exp(-fabs(x) / s) / (s * pow(1.0 + exp(-fabs(x) / s), 2)); }

static double np_ref(double x, double s)
{
    x = atan2(sin(x), cos(x));
    double z = 0.0;
    const int n = 20000;
    for (int j = 0; j < n; j++)
        z += logistic_ref(-M_PI + (j + 0.5) * 2.0 * M_PI / n, s) * 2.0 * M_PI / n;
    return logistic_ref(x, s) / z;
}

/* The model from its definitions: sum over p of Mp Ap Np (+ the residual). */
static rgb hair_ref(const fibre *m, vec3 wi, vec3 wo)
{
    double theta_i = asin(wi.y), theta_o = asin(wo.y);
    double phi_i = atan2(wi.z, wi.x), phi_o = atan2(wo.z, wo.x);
    double gamma_i = atan2(-wi.x, wi.z), h = sin(gamma_i);
    double v0 = pow(0.726 * m->beta_m + 0.812 * m->beta_m * m->beta_m + 3.7 * pow(m->beta_m, 20), 2);
    double v[4] = {v0, v0 / 4.0, 4.0 * v0, 4.0 * v0};
    double s = sqrt(M_PI / 8.0) * (0.265 * m->beta_n + 1.194 * pow(m->beta_n, 2) + 5.372 * pow(m->beta_n, 22));
    double a = m->alpha_deg * M_PI / 180.0, tilt[4] = {-2.0 * a, a, 4.0 * a, 0.0};
    /* Snell longitudinally, Bravais' index in the cross-section */
    double theta_t = asin(sin(theta_i) / m->eta);
    double eta_p = sqrt(m->eta * m->eta - sin(theta_i) * sin(theta_i)) / cos(theta_i);
    double gamma_t = asin(h / eta_p);
    double len = 2.0 * cos(gamma_t) / cos(theta_t);
    double f = fresnel_ref(cos(theta_i) * cos(gamma_i), m->eta);
    double sa[3] = {m->sigma_a.r, m->sigma_a.g, m->sigma_a.b}, out[3];
    for (int c = 0; c < 3; c++) {
        double t = exp(-sa[c] * len);
        double ap[4] = {f, (1 - f) * (1 - f) * t, (1 - f) * (1 - f) * t * t * f, 0.0};
        ap[3] = ap[2] * f * t / (1.0 - f * t);
        double sum = 0.0;
        for (int p = 0; p < 4; p++) {
            double mp = mp_ref(theta_i + tilt[p], theta_o, v[p]);
            double np = p < 3 ? np_ref(phi_o - phi_i - (2 * p * gamma_t - 2 * gamma_i + p * M_PI), s) : 1.0 / (2 * M_PI);
            sum += mp * ap[p] * 2.0 * M_PI * np;
        }
        out[c] = sum;
    }
    return rgb_make(out[0], out[1], out[2]);
}

static vec3 uniform_direction(rng_t *rng)
{
    double y = 2.0 * rng_next_double(rng) - 1.0, phi = 2.0 * M_PI * rng_next_double(rng), c = sqrt(1.0 - y * y);
    return v3(c * cos(phi), y, c * sin(phi));
}

Test(bsdf_hair, eval_matches_the_model_integrated_from_its_definitions, .timeout = 60)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    const fibre fibres[] = {
        {0.3, 0.3, 2.0, 1.55 / 1.000277, {0.419 * 1.3 + 0.187 * 0.2, 0.697 * 1.3 + 0.4 * 0.2, 1.37 * 1.3 + 1.05 * 0.2}},
        {0.1, 0.5, 3.0, 1.55 / 1.000277, {0.2, 0.25, 0.7}},   /* smooth: kappa in the hundreds */
        {0.8, 0.15, 0.0, 1.33 / 1.000277, {0.05, 0.5, 2.0}},
    };
    const char *xml[] = {"",
                         "<float name='longitudinal_roughness' value='0.1'/><float name='azimuthal_roughness' "
                         "value='0.5'/><float name='scale_tilt' value='3'/><rgb name='sigma_a' value='0.2, 0.25, 0.7'/>",
                         "<float name='longitudinal_roughness' value='0.8'/><float name='azimuthal_roughness' "
                         "value='0.15'/><float name='scale_tilt' value='0'/><float name='int_ior' value='1.33'/>"
                         "<rgb name='sigma_a' value='0.025, 0.25, 1'/><float name='scale' value='2'/>"};
    rng_t rng;
    rng_seed(&rng, 42, 7);
    for (int k = 0; k < 3; k++) {
        const bsdf_t *b = hair_bsdf(&fx, xml[k]);
        for (int i = 0; i < 12; i++) {
            vec3 wi = uniform_direction(&rng), wo = uniform_direction(&rng);
            if (wi.z < 0.05)
                wi.z = -wi.z + 0.05, wi = v3_norm(wi); /* light arrives on the outside */
            if (i == 0) /* the R lobe's peak: the mirror direction about the normal, tilted */
                wo = v3(-wi.x, -wi.y, wi.z);
            bsdf_query q = {.wi = wi, .uv = v2(0.5, 0.5), .mode = TRANSPORT_RADIANCE};
            rgb f = bsdf_eval(b, &q, wo), r = hair_ref(&fibres[k], wi, wo);
            double err = fmax(fabs(f.r - r.r), fmax(fabs(f.g - r.g), fabs(f.b - r.b)));
            cr_expect(err <= 1e-6 * (1.0 + rgb_max(r)), "fibre %d, wi %g %g %g, wo %g %g %g: eval %g %g %g, model %g %g %g",
                      k, wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, f.r, f.g, f.b, r.r, r.g, r.b);
        }
    }
    plugin_xml_close(&fx);
}

/* ------------------------------------------------------------- sampling */

/* sample() returns eval / pdf at the direction it draws, with pdf(); and it
 * draws by that density (chi-square over the sphere, 16 x 32 cells). */
Test(bsdf_hair, sample_follows_pdf_and_agrees_with_eval, .timeout = 120)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    const double thetas[] = {10.0, -50.0}, hs[] = {0.2, -0.7};
    int tests = 0;
    for (int k = 0; k < 3; k++) {
        const bsdf_t *b = hair_bsdf(&fx, rough_fibres[k]);
        for (int t = 0; t < 2; t++) {
            bsdf_density_ctx ctx = {b, fibre_query(thetas[t], hs[t])};
            rng_t rng;
            rng_seed(&rng, 77 + k, t);
            for (int i = 0; i < 2000; i++) {
                bsdf_sample_rec s;
                double u1 = rng_next_double(&rng);
                vec2 u2 = v2(rng_next_double(&rng), rng_next_double(&rng));
                cr_assert(bsdf_sample(b, &ctx.q, u1, u2, &s), "%s: no sample", rough_fibres[k]);
                double pdf = bsdf_pdf(b, &ctx.q, s.wo);
                rgb f = bsdf_eval(b, &ctx.q, s.wo);
                cr_assert(fabs(v3_len(s.wo) - 1.0) < 1e-9 && fabs(s.pdf - pdf) <= 1e-9 * pdf && s.eta == 1.0);
                cr_assert(fabs(s.weight.r * pdf - f.r) <= 1e-9 * (f.r + 1e-300) &&
                              fabs(s.weight.b * pdf - f.b) <= 1e-9 * (f.b + 1e-300),
                          "%s: weight %g, eval / pdf %g", rough_fibres[k], s.weight.r, f.r / pdf);
            }
            sphere_sampler sp = bsdf_sphere_sampler(&ctx);
            char msg[256];
            double p = chi2_sphere(&sp, 16, 32, 100000, 500 + 7 * k + t, msg, sizeof msg);
            cr_expect_gt(p, chi2_threshold(), "%s, theta %g h %g: %s", rough_fibres[k], thetas[t], hs[t], msg);
            tests++;
        }
    }
    cr_assert_eq(tests, HAIR_CHI2_TESTS);
    plugin_xml_close(&fx);
}

/* Mitsuba's refusals: roughness outside [0, 1], equal IORs, pigments and
 * sigma_a together; and the pigments' colours: pheomelanin is red (it
 * absorbs blue most, red least). */
Test(bsdf_hair, parameters)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    const char *bad[] = {
        "<bsdf type='hair'><float name='longitudinal_roughness' value='1.5'/></bsdf>",
        "<bsdf type='hair'><float name='azimuthal_roughness' value='-0.1'/></bsdf>",
        "<bsdf type='hair'><float name='int_ior' value='1.0'/><float name='ext_ior' value='1.0'/></bsdf>",
        "<bsdf type='hair'><rgb name='sigma_a' value='1'/><float name='pheomelanin' value='1'/></bsdf>",
        "<bsdf type='hair'><rgb name='sigma_a' value='1'/><float name='eumelanin' value='1'/></bsdf>",
        "<bsdf type='hair'><rgb name='sigma_a' value='-1, 0, 0'/></bsdf>",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char err[512] = "";
        cr_expect_null(plugin_xml_bsdf(&fx, bad[i], err, sizeof err), "accepted %s", bad[i]);
    }
    const bsdf_t *red = hair_bsdf(&fx, "<float name='eumelanin' value='0'/><float name='pheomelanin' value='2'/>");
    rgb a = bsdf_albedo(red, v2(0.5, 0.5));
    cr_expect(a.r > a.g && a.g > a.b, "pheomelanin's albedo %g %g %g", a.r, a.g, a.b);
    /* sigma_a above 1 is an absorption, not a reflectance: not clamped */
    const bsdf_t *dark = hair_bsdf(&fx, "<rgb name='sigma_a' value='5'/>");
    const bsdf_t *one = hair_bsdf(&fx, "<rgb name='sigma_a' value='1'/>");
    cr_expect_lt(bsdf_albedo(dark, v2(0.5, 0.5)).g, bsdf_albedo(one, v2(0.5, 0.5)).g);
    plugin_xml_close(&fx);
}
