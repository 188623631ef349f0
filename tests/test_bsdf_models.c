/* Individual BSDF models against closed forms: Lambert's albedo, Fresnel
 * branching of smooth dielectrics, the thin-sheet series, conductor Fresnel,
 * the plastic energy balance, limits of the rough models, two-sided mirroring,
 * and parameter handling. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "celadon/fresnel.h"
#include "test_bsdf_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char err[256];

/* Mean sample weight (the directional albedo), its standard error, and the
 * fraction of samples of the given lobe type. */
static rgb mean_weight(const bsdf_t *b, const bsdf_query *q, int n, unsigned type, double *fraction, double *se)
{
    rng_t rng;
    rng_seed(&rng, 99, 1);
    rgb sum = rgb_gray(0.0);
    double sum2 = 0.0;
    int hits = 0;
    for (int k = 0; k < n; k++) {
        bsdf_sample_rec s;
        double u1 = rng_next_double(&rng);
        vec2 u2 = v2(rng_next_double(&rng), rng_next_double(&rng));
        if (!bsdf_sample(b, q, u1, u2, &s))
            continue;
        sum = rgb_add(sum, s.weight);
        sum2 += s.weight.r * s.weight.r;
        hits += (s.sampled_type & type) != 0;
    }
    rgb m = rgb_scale(sum, 1.0 / n);
    if (fraction)
        *fraction = (double)hits / n;
    if (se)
        *se = sqrt(fmax(0.0, sum2 / n - m.r * m.r) / n);
    return m;
}

Test(bsdf_models, white_diffuse_reflects_everything)
{
    bsdf_diffuse_params p = bsdf_diffuse_defaults();
    cr_assert_float_eq(p.reflectance.value.g, 0.5, 0);
    p.reflectance = bsdf_spectrum_const(rgb_gray(1.0));
    bsdf_t *b = bsdf_create_diffuse(&p, err, sizeof err);
    bsdf_query q = query_at(37.0, 0.0, TRANSPORT_RADIANCE);
    /* Hemispherical integral of f cos by midpoint quadrature in (cos, phi). */
    double sum = 0.0;
    const int n = 400;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double z = (i + 0.5) / n, r = sqrt(1 - z * z), phi = 2 * M_PI * (j + 0.5) / n;
            sum += bsdf_eval(b, &q, v3(r * cos(phi), r * sin(phi), z)).g;
        }
    cr_assert_float_eq(sum * 2 * M_PI / (n * n), 1.0, 1e-5);
    /* Every sample carries exactly the reflectance. */
    rng_t rng;
    rng_seed(&rng, 1, 1);
    for (int k = 0; k < 1000; k++) {
        bsdf_sample_rec s;
        cr_assert(bsdf_sample(b, &q, rng_next_double(&rng), v2(rng_next_double(&rng), rng_next_double(&rng)), &s));
        cr_assert_eq(s.weight.r, 1.0);
        cr_assert_eq(s.sampled_type, BSDF_DIFFUSE_REFLECTION);
    }
    cr_assert_eq(bsdf_albedo(b, v2(0, 0)).b, 1.0);
    bsdf_free(b);
}

Test(bsdf_models, dielectric_splits_by_fresnel_and_conserves_energy)
{
    bsdf_dielectric_params p = bsdf_dielectric_defaults();
    cr_assert_float_eq(p.int_ior, 1.5046, 1e-12);
    cr_assert_float_eq(p.ext_ior, 1.000277, 1e-12);
    bsdf_t *b = bsdf_create_dielectric(&p, err, sizeof err);
    double eta = 1.5046 / 1.000277;
    const double thetas[] = {0.0, 45.0, 80.0, 135.0, 150.0};
    for (int i = 0; i < 5; i++) {
        bsdf_query q = query_at(thetas[i], 30.0, TRANSPORT_IMPORTANCE);
        double f = fresnel_dielectric(q.wi.z, eta, NULL, NULL, NULL), frac, se;
        const int n = 40000;
        rgb m = mean_weight(b, &q, n, BSDF_DELTA_REFLECTION, &frac, &se);
        /* Importance (flux) is conserved exactly: each sample weighs 1. */
        cr_assert_float_eq(m.g, 1.0, 1e-12, "theta %g", thetas[i]);
        cr_assert_float_eq(frac, f, 5.0 * sqrt(f * (1 - f) / n) + 1e-12, "theta %g: %g vs F %g", thetas[i], frac, f);

        /* Directions: mirror, and Snell's law with the azimuth flipped. */
        bsdf_sample_rec s;
        cr_assert(bsdf_sample(b, &q, 0.0, v2(0.5, 0.5), &s));
        cr_assert_float_eq(s.wo.z, q.wi.z, 1e-15);
        cr_assert_float_eq(s.wo.x, -q.wi.x, 1e-15);
        if (f < 1.0) {
            q.mode = TRANSPORT_RADIANCE;
            cr_assert(bsdf_sample(b, &q, 1.0 - 1e-12, v2(0.5, 0.5), &s));
            cr_assert_eq(s.sampled_type, BSDF_DELTA_TRANSMISSION);
            double n_i = q.wi.z > 0 ? 1.0 : eta, n_t = q.wi.z > 0 ? eta : 1.0;
            double sin_i = sqrt(1 - q.wi.z * q.wi.z), sin_t = sqrt(1 - s.wo.z * s.wo.z);
            cr_assert_float_eq(n_i * sin_i, n_t * sin_t, 1e-12);
            cr_assert(s.wo.z * q.wi.z < 0);
            cr_assert_float_eq(s.eta, n_t / n_i, 1e-12);
            /* Radiance is compressed by (n_i / n_t)^2 crossing the interface. */
            cr_assert_float_eq(s.weight.r, (n_i / n_t) * (n_i / n_t), 1e-12);
        }
    }
    /* Beyond the critical angle inside the glass: total internal reflection. */
    bsdf_query q = query_at(180.0 - 50.0, 0.0, TRANSPORT_RADIANCE);
    double frac;
    mean_weight(b, &q, 2000, BSDF_DELTA_REFLECTION, &frac, NULL);
    cr_assert_eq(frac, 1.0);
    cr_assert(rgb_is_black(bsdf_eval(b, &q, v3(0, 0, 1))));
    cr_assert_eq(bsdf_pdf(b, &q, v3(0, 0, 1)), 0.0);
    bsdf_free(b);
}

Test(bsdf_models, thindielectric_sums_internal_bounces)
{
    bsdf_dielectric_params p = bsdf_dielectric_defaults();
    p.int_ior = 1.5;
    p.ext_ior = 1.0;
    bsdf_t *b = bsdf_create_thindielectric(&p, err, sizeof err);
    bsdf_query q = query_at(60.0, 10.0, TRANSPORT_RADIANCE);
    double r = fresnel_dielectric(q.wi.z, 1.5, NULL, NULL, NULL), t = 1 - r;
    /* R + T R T + T R^3 T + ... = R + T^2 R / (1 - R^2) */
    double r_sheet = r + t * t * r / (1 - r * r);
    const int n = 40000;
    double frac;
    rgb m = mean_weight(b, &q, n, BSDF_DELTA_REFLECTION, &frac, NULL);
    cr_assert_float_eq(m.r, 1.0, 1e-12);
    cr_assert_float_eq(frac, r_sheet, 5.0 * sqrt(r_sheet * (1 - r_sheet) / n));
    bsdf_sample_rec s;
    cr_assert(bsdf_sample(b, &q, 0.999999, v2(0, 0), &s));
    cr_assert_eq(s.sampled_type, BSDF_DELTA_TRANSMISSION);
    cr_assert(s.wo.x == -q.wi.x && s.wo.y == -q.wi.y && s.wo.z == -q.wi.z, "passes straight through");
    cr_assert_eq(s.eta, 1.0);
    bsdf_free(b);
}

Test(bsdf_models, conductor_presets_and_fresnel)
{
    rgb eta, k;
    cr_assert_eq(bsdf_conductor_preset("Unobtainium", &eta, &k), -1);
    const char *metals[] = {"Ag", "Al", "Au", "Cu"};
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(bsdf_conductor_preset(metals[i], &eta, &k), 0);
        bsdf_conductor_params p = bsdf_conductor_defaults();
        p.eta = eta;
        p.k = k;
        bsdf_t *b = bsdf_create_conductor(&p, err, sizeof err);
        for (int th = 0; th < 90; th += 20) {
            bsdf_query q = query_at(th, 0.0, TRANSPORT_RADIANCE);
            bsdf_sample_rec s;
            cr_assert(bsdf_sample(b, &q, 0.5, v2(0.5, 0.5), &s));
            rgb f = fresnel_conductor_rgb(q.wi.z, eta, k);
            cr_assert_float_eq(s.weight.g, f.g, 1e-15);
            cr_assert_eq(s.sampled_type, BSDF_DELTA_REFLECTION);
        }
        rgb a = bsdf_albedo(b, v2(0, 0));
        /* Every metal here reflects most visible light at normal incidence. */
        cr_assert(rgb_max(a) > 0.9 && rgb_max(a) <= 1.0, "%s: %g %g %g", metals[i], a.r, a.g, a.b);
        if (strcmp(metals[i], "Au") == 0 || strcmp(metals[i], "Cu") == 0)
            cr_assert(a.r > a.g && a.g > a.b, "%s is reddish-yellow", metals[i]);
        if (strcmp(metals[i], "Ag") == 0)
            cr_assert(a.b > 0.9, "silver is white");
        bsdf_free(b);
    }
    /* Default material "none": a perfect mirror. */
    bsdf_conductor_params p = bsdf_conductor_defaults();
    bsdf_t *b = bsdf_create_conductor(&p, err, sizeof err);
    bsdf_query q = query_at(70.0, 0.0, TRANSPORT_RADIANCE);
    bsdf_sample_rec s;
    cr_assert(bsdf_sample(b, &q, 0.5, v2(0.5, 0.5), &s));
    cr_assert_float_eq(s.weight.r, 1.0, 1e-12);
    bsdf_free(b);
}

/* Smooth plastic's energy balance: with the linear model the diffuse lobe
 * returns rho of the light that the coating transmits, so the albedo is
 * F(cos_i) + (1 - F(cos_i)) rho; the nonlinear model replaces rho by
 * rho (1 - Fdr_int) / (1 - rho Fdr_int) (Fdr_int: internal diffuse reflectance). */
Test(bsdf_models, plastic_albedo_closed_form)
{
    for (int nonlinear = 0; nonlinear < 2; nonlinear++) {
        bsdf_plastic_params p = bsdf_plastic_defaults();
        cr_assert_float_eq(p.int_ior, 1.49, 1e-12);
        p.nonlinear = nonlinear;
        p.diffuse_reflectance = bsdf_spectrum_const(rgb_make(0.8, 0.8, 0.8));
        bsdf_t *b = bsdf_create_plastic(&p, err, sizeof err);
        double eta = 1.49 / 1.000277, fdr = fresnel_diffuse_reflectance(1.0 / eta), rho = 0.8;
        double rho_eff = nonlinear ? rho * (1 - fdr) / (1 - rho * fdr) : rho;
        const double thetas[] = {0.0, 50.0, 80.0};
        for (int i = 0; i < 3; i++) {
            bsdf_query q = query_at(thetas[i], 0.0, TRANSPORT_RADIANCE);
            double f = fresnel_dielectric(q.wi.z, eta, NULL, NULL, NULL), se;
            rgb m = mean_weight(b, &q, 100000, BSDF_DELTA_REFLECTION, NULL, &se);
            double expect = f + (1 - f) * rho_eff;
            cr_assert_float_eq(m.r, expect, 4.0 * se + 2e-4, "nonlinear %d theta %g: %g vs %g (se %g)", nonlinear,
                               thetas[i], m.r, expect, se);
        }
        bsdf_free(b);
    }
}

/* Small roughness approaches the smooth models. */
Test(bsdf_models, rough_models_tend_to_smooth_ones)
{
    bsdf_query q = query_at(40.0, 0.0, TRANSPORT_IMPORTANCE);
    double se, frac;

    bsdf_roughdielectric_params rd = bsdf_roughdielectric_defaults();
    cr_assert_float_eq(rd.alpha_u, 0.1, 0);
    rd.alpha_u = rd.alpha_v = 0.01;
    bsdf_t *b = bsdf_create_roughdielectric(&rd, err, sizeof err);
    double f = fresnel_dielectric(q.wi.z, rd.int_ior / rd.ext_ior, NULL, NULL, NULL);
    rgb m = mean_weight(b, &q, 40000, BSDF_GLOSSY_REFLECTION, &frac, &se);
    cr_assert_float_eq(m.r, 1.0, 2e-3, "R + T = %g", m.r);
    cr_assert_float_eq(frac, f, 5.0 * sqrt(f * (1 - f) / 40000) + 1e-3);
    bsdf_free(b);

    bsdf_roughconductor_params rc = bsdf_roughconductor_defaults();
    rc.alpha_u = rc.alpha_v = 0.01;
    b = bsdf_create_roughconductor(&rc, err, sizeof err);
    m = mean_weight(b, &q, 20000, BSDF_GLOSSY_REFLECTION, NULL, NULL);
    cr_assert_float_eq(m.r, 1.0, 2e-3);
    bsdf_free(b);

    bsdf_roughplastic_params rp = bsdf_roughplastic_defaults();
    rp.alpha = 0.01;
    rp.diffuse_reflectance = bsdf_spectrum_const(rgb_gray(0.8));
    b = bsdf_create_roughplastic(&rp, err, sizeof err);
    f = fresnel_dielectric(q.wi.z, rp.int_ior / rp.ext_ior, NULL, NULL, NULL);
    m = mean_weight(b, &q, 100000, BSDF_GLOSSY_REFLECTION, NULL, &se);
    cr_assert_float_eq(m.r, f + (1 - f) * 0.8, 4.0 * se + 3e-3, "%g vs %g", m.r, f + (1 - f) * 0.8);
    bsdf_free(b);
}

Test(bsdf_models, twosided_mirrors_the_back)
{
    bsdf_roughconductor_params rc = bsdf_roughconductor_defaults();
    rc.alpha_u = 0.2;
    rc.alpha_v = 0.4;
    bsdf_t *front = bsdf_create_roughconductor(&rc, err, sizeof err);
    bsdf_t *b = bsdf_create_twosided(front, NULL, err, sizeof err);
    cr_assert_eq(bsdf_flags(b) & (BSDF_FRONT_SIDE | BSDF_BACK_SIDE), BSDF_FRONT_SIDE | BSDF_BACK_SIDE);
    bsdf_query qf = query_at(35.0, 20.0, TRANSPORT_RADIANCE), qb = qf;
    qb.wi.z = -qb.wi.z;
    vec3 wo = v3_norm(v3(-0.3, 0.1, 0.8)), wo_b = v3(wo.x, wo.y, -wo.z);
    cr_assert_float_eq(bsdf_eval(b, &qb, wo_b).r, bsdf_eval(front, &qf, wo).r, 1e-15);
    cr_assert_float_eq(bsdf_pdf(b, &qb, wo_b), bsdf_pdf(front, &qf, wo), 1e-15);
    cr_assert(rgb_is_black(bsdf_eval(b, &qb, wo)), "no coupling across the surface");
    bsdf_sample_rec s;
    cr_assert(bsdf_sample(b, &qb, 0.5, v2(0.3, 0.7), &s));
    cr_assert_lt(s.wo.z, 0.0);
    bsdf_free(b);

    bsdf_dielectric_params dp = bsdf_dielectric_defaults();
    bsdf_t *glass = bsdf_create_dielectric(&dp, err, sizeof err);
    cr_assert_null(bsdf_create_twosided(glass, NULL, err, sizeof err));
    cr_assert(strstr(err, "dielectric"), "%s", err);
    bsdf_free(glass);
    bsdf_free(front);
}

Test(bsdf_models, parameters_names_and_errors)
{
    const char *const *names = bsdf_plugin_params("roughconductor");
    cr_assert_not_null(names);
    int has_alpha_u = 0, n = 0;
    for (; names[n]; n++)
        has_alpha_u |= strcmp(names[n], "alpha_u") == 0;
    cr_assert(has_alpha_u);
    cr_assert_null(bsdf_plugin_params("velvet"));
    cr_assert_not_null(bsdf_plugin_params("twosided"));
    cr_assert_null(bsdf_plugin_params("twosided")[0]);
    cr_assert_not_null(texture_plugin_params("bitmap"));

    double ior;
    cr_assert_eq(bsdf_ior_lookup("BK7", &ior), 0);
    cr_assert_float_eq(ior, 1.5046, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("acrylic glass", &ior), 0);
    cr_assert_float_eq(ior, 1.49, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("diamond", &ior), 0);
    cr_assert_float_eq(ior, 2.419, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("glass?", &ior), -1);
    /* Every listed name resolves (the lists feed "valid choices are" messages). */
    int n_ior = 0;
    for (const char *const *nm = bsdf_ior_names(); *nm; nm++, n_ior++)
        cr_assert_eq(bsdf_ior_lookup(*nm, &ior), 0, "%s", *nm);
    cr_assert_eq(n_ior, 23);
    int n_metal = 0;
    rgb eta, k;
    for (const char *const *nm = bsdf_conductor_names(); *nm; nm++, n_metal++)
        cr_assert_eq(bsdf_conductor_preset(*nm, &eta, &k), 0, "%s", *nm);
    cr_assert_eq(n_metal, 5);

    bsdf_dielectric_params dp = bsdf_dielectric_defaults();
    dp.int_ior = -1.0;
    cr_assert_null(bsdf_create_dielectric(&dp, err, sizeof err));
    cr_assert(strstr(err, "int_ior"), "%s", err);
    bsdf_roughdielectric_params rd = bsdf_roughdielectric_defaults();
    rd.alpha_v = NAN;
    cr_assert_null(bsdf_create_roughdielectric(&rd, err, sizeof err));
    cr_assert(strstr(err, "alpha_v"), "%s", err);
    bsdf_diffuse_params df = bsdf_diffuse_defaults();
    df.reflectance = bsdf_spectrum_const(rgb_make(0.5, -0.1, 0.2));
    cr_assert_null(bsdf_create_diffuse(&df, err, sizeof err));
    cr_assert(strstr(err, "reflectance"), "%s", err);
    cr_assert_null(bsdf_create_twosided(NULL, NULL, err, sizeof err));

    microfacet_type t;
    cr_assert_eq(microfacet_type_parse("ggx", &t), 0);
    cr_assert_eq(t, MICROFACET_GGX);
    cr_assert_eq(microfacet_type_parse("phong", &t), -1);
}

/* Extreme roughness and directions produce finite values or clean rejections. */
Test(bsdf_models, extreme_inputs_stay_finite)
{
    const double alphas[] = {0.0, 1e-3, 2.0};
    const vec3 wis[] = {{0, 0, 1}, {1, 0, 0}, {0.6, 0.8, 1e-9}, {0, 0, -1}, {1e-9, 0, -1}, {0.8, -0.6, -1e-7}};
    rng_t rng;
    rng_seed(&rng, 3, 3);
    for (int a = 0; a < 3; a++)
        for (int kind = 0; kind < 4; kind++) {
            bsdf_t *b = NULL;
            for (int dist = 0; dist < 2; dist++) {
                microfacet_type t = dist ? MICROFACET_GGX : MICROFACET_BECKMANN;
                if (kind == 0) {
                    bsdf_roughconductor_params p = bsdf_roughconductor_defaults();
                    p.alpha_u = p.alpha_v = alphas[a];
                    p.distribution = t;
                    b = bsdf_create_roughconductor(&p, err, sizeof err);
                } else if (kind == 1) {
                    bsdf_roughdielectric_params p = bsdf_roughdielectric_defaults();
                    p.alpha_u = alphas[a];
                    p.alpha_v = 0.3;
                    p.distribution = t;
                    b = bsdf_create_roughdielectric(&p, err, sizeof err);
                } else if (kind == 2) {
                    bsdf_roughplastic_params p = bsdf_roughplastic_defaults();
                    p.alpha = alphas[a];
                    p.distribution = t;
                    b = bsdf_create_roughplastic(&p, err, sizeof err);
                } else {
                    bsdf_roughdielectric_params p = bsdf_roughdielectric_defaults();
                    p.alpha_u = p.alpha_v = alphas[a];
                    p.sample_visible = 0;
                    p.distribution = t;
                    b = bsdf_create_roughdielectric(&p, err, sizeof err);
                }
                cr_assert_not_null(b, "%s", err);
                for (int w = 0; w < 6; w++) {
                    bsdf_query q = {v3_norm(wis[w]), v2(0, 0), TRANSPORT_RADIANCE};
                    for (int k = 0; k < 200; k++) {
                        bsdf_sample_rec s;
                        double u1 = k == 0 ? 0.0 : rng_next_double(&rng);
                        vec2 u2 = k == 0 ? v2(0.0, 0.0) : k == 1 ? v2(1.0 - 1e-16, 1.0 - 1e-16)
                                                                 : v2(rng_next_double(&rng), rng_next_double(&rng));
                        if (!bsdf_sample(b, &q, u1, u2, &s))
                            continue;
                        cr_assert(isfinite(s.weight.r) && isfinite(s.pdf) && isfinite(s.wo.x + s.wo.y + s.wo.z),
                                  "kind %d alpha %g wi %d", kind, alphas[a], w);
                        rgb f = bsdf_eval(b, &q, s.wo);
                        cr_assert(isfinite(f.r) && isfinite(bsdf_pdf(b, &q, s.wo)));
                    }
                }
                bsdf_free(b);
            }
        }
}
