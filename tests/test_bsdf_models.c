/* Individual BSDF models against closed forms: Lambert's albedo, Fresnel
 * branching of smooth dielectrics, the thin-sheet series, conductor Fresnel,
 * the plastic energy balance, limits of the rough models, two-sided mirroring,
 * and parameter handling. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"
#include "scene_xml/spectrum.h"
#include "support/plugin_xml.h"
#include "test_bsdf_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static char err[512];
static plugin_xml fx;

/* The BSDF of an XML snippet, which must build. */
static const bsdf_t *bsdf_of(const char *xml)
{
    const bsdf_t *b = plugin_xml_bsdf(&fx, xml, err, sizeof err);
    cr_assert_not_null(b, "%s: %s", xml, err);
    return b;
}

static void open_fixture(void) { plugin_xml_open(&fx); }
static void close_fixture(void) { plugin_xml_close(&fx); }
TestSuite(bsdf_models, .init = open_fixture, .fini = close_fixture);

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
    cr_assert_float_eq(bsdf_albedo(bsdf_of("<bsdf type='diffuse'/>"), v2(0, 0)).g, 0.5, 0, "Mitsuba's default");
    const bsdf_t *b = bsdf_of("<bsdf type='diffuse'><rgb name='reflectance' value='1'/></bsdf>");
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
}

Test(bsdf_models, dielectric_splits_by_fresnel_and_conserves_energy)
{
    /* Mitsuba's defaults: bk7 inside, air outside. */
    const bsdf_t *b = bsdf_of("<bsdf type='dielectric'/>");
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
}

Test(bsdf_models, thindielectric_sums_internal_bounces)
{
    const bsdf_t *b = bsdf_of("<bsdf type='thindielectric'><float name='int_ior' value='1.5'/>"
                              "<float name='ext_ior' value='1'/></bsdf>");
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
    cr_assert_eq(s.sampled_type, BSDF_DELTA_TRANSMISSION | BSDF_STRAIGHT_TRANSMISSION, "a straight sample says so");
    cr_assert(s.wo.x == -q.wi.x && s.wo.y == -q.wi.y && s.wo.z == -q.wi.z, "passes straight through");
    cr_assert_eq(s.eta, 1.0);
}

Test(bsdf_models, conductor_presets_and_fresnel)
{
    rgb eta, k;
    cr_assert_eq(bsdf_conductor_preset("Unobtainium", &eta, &k), -1);
    const char *metals[] = {"Ag", "Al", "Au", "Cu"};
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(bsdf_conductor_preset(metals[i], &eta, &k), 0);
        char xml[160];
        snprintf(xml, sizeof xml, "<bsdf type='conductor'><string name='material' value='%s'/></bsdf>", metals[i]);
        const bsdf_t *b = bsdf_of(xml);
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
    }
    /* Amorphous carbon from its tabulated complex IOR (Palik's n ~ 1.8-2.4,
     * k ~ 0.7-0.9, mitsuba-data's ior/a-C.{eta,k}.spd), taken to RGB as
     * Mitsuba's RGB variants take a preset: CIE 1931 integration without
     * D65, then XYZ -> linear sRGB. Nearly flat spectra come out warm: red
     * reflects more than blue at normal incidence. */
    static const double wl[] = {309.950012, 326.263, 344.389008, 364.647003, 387.437988, 413.266998, 442.78598,
                                476.846008, 516.583008, 563.545044, 619.900024, 688.778015, 774.875, 885.570984};
    static const double n_ac[] = {1.84, 1.90, 1.94, 2.00, 2.06, 2.11, 2.17, 2.24, 2.30, 2.38, 2.43, 2.43, 2.33, 2.24};
    static const double k_ac[] = {0.808, 0.91, 0.92, 0.92, 0.91, 0.90, 0.89, 0.88, 0.87, 0.82, 0.75, 0.70, 0.71, 0.80};
    double xyz[3];
    spectrum_list_xyz(wl, n_ac, 14, false, xyz);
    scene_rgb want_eta = spectrum_xyz_to_rgb(xyz);
    spectrum_list_xyz(wl, k_ac, 14, false, xyz);
    scene_rgb want_k = spectrum_xyz_to_rgb(xyz);
    cr_assert_eq(bsdf_conductor_preset("a-C", &eta, &k), 0);
    cr_assert_float_eq(eta.r, want_eta.r, 1e-5, "a-C eta.r %g, table %g", eta.r, want_eta.r);
    cr_assert_float_eq(eta.g, want_eta.g, 1e-5);
    cr_assert_float_eq(eta.b, want_eta.b, 1e-5, "a-C eta.b %g, table %g", eta.b, want_eta.b);
    cr_assert_float_eq(k.r, want_k.r, 1e-5, "a-C k.r %g, table %g", k.r, want_k.r);
    cr_assert_float_eq(k.g, want_k.g, 1e-5);
    cr_assert_float_eq(k.b, want_k.b, 1e-5);
    rgb carbon = bsdf_albedo(bsdf_of("<bsdf type='conductor'><string name='material' value='a-C'/></bsdf>"), v2(0, 0));
    cr_assert(carbon.r > carbon.g && carbon.g > carbon.b && carbon.b > 0.15 && carbon.r < 0.3,
              "a-C: %g %g %g", carbon.r, carbon.g, carbon.b);
    /* Default material "none": a perfect mirror. */
    const bsdf_t *b = bsdf_of("<bsdf type='conductor'/>");
    bsdf_query q = query_at(70.0, 0.0, TRANSPORT_RADIANCE);
    bsdf_sample_rec s;
    cr_assert(bsdf_sample(b, &q, 0.5, v2(0.5, 0.5), &s));
    cr_assert_float_eq(s.weight.r, 1.0, 1e-12);
}

/* Smooth plastic's energy balance: with the linear model the diffuse lobe
 * returns rho of the light that the coating transmits, so the albedo is
 * F(cos_i) + (1 - F(cos_i)) rho; the nonlinear model replaces rho by
 * rho (1 - Fdr_int) / (1 - rho Fdr_int) (Fdr_int: internal diffuse reflectance). */
Test(bsdf_models, plastic_albedo_closed_form)
{
    for (int nonlinear = 0; nonlinear < 2; nonlinear++) {
        /* Mitsuba's default int_ior: polypropylene, 1.49. */
        char xml[200];
        snprintf(xml, sizeof xml,
                 "<bsdf type='plastic'><boolean name='nonlinear' value='%s'/>"
                 "<rgb name='diffuse_reflectance' value='0.8'/></bsdf>",
                 nonlinear ? "true" : "false");
        const bsdf_t *b = bsdf_of(xml);
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
    }
}

/* Small roughness approaches the smooth models. */
Test(bsdf_models, rough_models_tend_to_smooth_ones)
{
    bsdf_query q = query_at(40.0, 0.0, TRANSPORT_IMPORTANCE);
    double se, frac;

    const bsdf_t *b = bsdf_of("<bsdf type='roughdielectric'><float name='alpha' value='0.01'/></bsdf>");
    double f = fresnel_dielectric(q.wi.z, 1.5046 / 1.000277, NULL, NULL, NULL);
    rgb m = mean_weight(b, &q, 40000, BSDF_GLOSSY_REFLECTION, &frac, &se);
    cr_assert_float_eq(m.r, 1.0, 2e-3, "R + T = %g", m.r);
    cr_assert_float_eq(frac, f, 5.0 * sqrt(f * (1 - f) / 40000) + 1e-3);

    b = bsdf_of("<bsdf type='roughconductor'><float name='alpha' value='0.01'/></bsdf>");
    m = mean_weight(b, &q, 20000, BSDF_GLOSSY_REFLECTION, NULL, NULL);
    cr_assert_float_eq(m.r, 1.0, 2e-3);

    /* Smooth plastic's linear model returns F + (1 - F) rho; Mitsuba's rough
     * one takes R_int as a 64-point mean 2 / 64 sum F_in(mu_i) mu_i (mu_i =
     * i / 63), a little below the integral, so rho is scaled by
     * (1 - R_int exact) / (1 - R_int Mitsuba). */
    b = bsdf_of("<bsdf type='roughplastic'><float name='alpha' value='0.01'/>"
                "<rgb name='diffuse_reflectance' value='0.8'/></bsdf>");
    double eta = 1.49 / 1.000277, r_mean = 0.0;
    for (int i = 0; i < 64; i++)
        r_mean += 2.0 / 64 * fresnel_dielectric(fmax(i / 63.0, 1e-6), 1.0 / eta, NULL, NULL, NULL) * (i / 63.0);
    double rho = 0.8 * (1.0 - fresnel_diffuse_reflectance(1.0 / eta)) / (1.0 - r_mean);
    f = fresnel_dielectric(q.wi.z, eta, NULL, NULL, NULL);
    m = mean_weight(b, &q, 100000, BSDF_GLOSSY_REFLECTION, NULL, &se);
    cr_assert_float_eq(m.r, f + (1 - f) * rho, 4.0 * se + 3e-3, "%g vs %g", m.r, f + (1 - f) * rho);
}

/* Rough plastic's internal reflectance R_int, read off its public eval: at
 * normal incidence the diffuse term is rho / (1 - R_int) C in the linear mode
 * and rho / (1 - rho R_int) C in the nonlinear one, so their ratio r gives
 * R_int = (1 - r) / (rho - r). Against it, the coating's single-scattering
 * reflection seen from inside, integrated numerically from the
 * roughdielectric plugin's own eval (wi below the surface, wo over the lower
 * hemisphere; total internal reflection included): 2 int R_in(mu) mu dmu.
 * Mitsuba's R_int is that integral as a 64-point mean, hence 0.01. */
Test(bsdf_models, roughplastic_internal_reflectance_is_single_scattering)
{
    const double rho = 0.5;
    const char *fmt = "<bsdf type='roughplastic'><string name='distribution' value='ggx'/>"
                      "<float name='alpha' value='1'/><string name='int_ior' value='bk7'/>"
                      "<rgb name='diffuse_reflectance' value='%g'/><rgb name='specular_reflectance' value='0'/>"
                      "<boolean name='nonlinear' value='%s'/></bsdf>";
    char xml[512];
    snprintf(xml, sizeof xml, fmt, rho, "false");
    const bsdf_t *lin = bsdf_of(xml);
    snprintf(xml, sizeof xml, fmt, rho, "true");
    const bsdf_t *nonlin = bsdf_of(xml);
    bsdf_query q = query_at(0.0, 0.0, TRANSPORT_RADIANCE);
    double r = bsdf_eval(lin, &q, v3(0, 0, 1)).g / bsdf_eval(nonlin, &q, v3(0, 0, 1)).g;
    double r_int = (1.0 - r) / (rho - r);

    const bsdf_t *coat = bsdf_of("<bsdf type='roughdielectric'><string name='distribution' value='ggx'/>"
                                 "<float name='alpha' value='1'/><string name='int_ior' value='bk7'/></bsdf>");
    enum { NMU = 48, NCOS = 96, NPHI = 96 };
    double want = 0.0;
    for (int k = 0; k < NMU; k++) {
        double mu = (k + 0.5) / NMU, r_in = 0.0;
        bsdf_query qi = {.wi = v3(sqrt(1.0 - mu * mu), 0.0, -mu), .uv = v2(0, 0), .mode = TRANSPORT_RADIANCE};
        for (int i = 0; i < NCOS; i++)
            for (int j = 0; j < NPHI; j++) {
                double c = (i + 0.5) / NCOS, sn = sqrt(1.0 - c * c), phi = 2.0 * M_PI * (j + 0.5) / NPHI;
                r_in += bsdf_eval(coat, &qi, v3(sn * cos(phi), sn * sin(phi), -c)).g * 2.0 * M_PI / (NCOS * NPHI);
            }
        want += 2.0 * r_in * mu / NMU;
    }
    cr_assert_float_eq(r_int, want, 0.01, "R_int %g, numerical integration %g", r_int, want);
}

Test(bsdf_models, twosided_mirrors_the_back)
{
    scene_obj *o[2];
    cr_assert_eq(plugin_xml_objects(&fx,
                                    "<bsdf type='roughconductor' id='front'><float name='alpha_u' value='0.2'/>"
                                    "<float name='alpha_v' value='0.4'/></bsdf>"
                                    "<bsdf type='twosided'><ref id='front'/></bsdf>",
                                    SCENE_BSDF, o, 2, err, sizeof err),
                 2, "%s", err);
    const bsdf_t *front = bsdf_set_get(&fx.bsdfs, o[0], err, sizeof err);
    const bsdf_t *b = bsdf_set_get(&fx.bsdfs, o[1], err, sizeof err);
    cr_assert(front && b, "%s", err);
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

    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='twosided'><bsdf type='dielectric'/></bsdf>", err, sizeof err));
    cr_assert(strstr(err, "must not transmit light (got dielectric)"), "%s", err);
}

Test(bsdf_models, parameters_names_and_errors)
{
    const bsdf_plugin *rough = bsdf_plugin_find("roughconductor");
    cr_assert_not_null(rough);
    int has_alpha_u = 0;
    for (const scene_param_decl *q = rough->decl.params; q->name; q++)
        has_alpha_u |= strcmp(q->name, "alpha_u") == 0;
    cr_assert(has_alpha_u);
    cr_assert_null(bsdf_plugin_find("velvet"));
    cr_assert_not_null(bsdf_plugin_find("twosided"));
    cr_assert_null(bsdf_plugin_find("twosided")->decl.params);
    cr_assert_not_null(texture_plugin_find("bitmap"));

    double ior;
    cr_assert_eq(bsdf_ior_lookup("BK7", &ior), 0);
    cr_assert_float_eq(ior, 1.5046, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("acrylic glass", &ior), 0);
    cr_assert_float_eq(ior, 1.49, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("diamond", &ior), 0);
    cr_assert_float_eq(ior, 2.419, 1e-12);
    cr_assert_eq(bsdf_ior_lookup("glass?", &ior), -1);
    /* Every name the reader accepts (the choices of int_ior) resolves. */
    int n_ior = 0;
    for (const char *nm = bsdf_ior_names; *nm; n_ior++) {
        char word[64];
        size_t len = strcspn(nm, "|");
        snprintf(word, sizeof word, "%.*s", (int)len, nm);
        cr_assert_eq(bsdf_ior_lookup(word, &ior), 0, "%s", word);
        nm += len + (nm[len] == '|');
    }
    cr_assert_eq(n_ior, 23);
    const char *metals[] = {"none", "Ag", "Al", "Au", "Cu", "a-C"};
    rgb eta, k;
    for (int i = 0; i < 6; i++)
        cr_assert_eq(bsdf_conductor_preset(metals[i], &eta, &k), 0, "%s", metals[i]);

    /* Bad values are refused when the BSDF is built, naming the parameter. */
    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='dielectric'><float name='int_ior' value='-1'/></bsdf>", err,
                                   sizeof err));
    cr_assert(strstr(err, "snippet.xml:1: <bsdf type='dielectric'>: int_ior must be a positive number"), "%s", err);
    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='roughdielectric'><float name='alpha_v' value='-0.5'/></bsdf>",
                                   err, sizeof err));
    cr_assert(strstr(err, "alpha_v"), "%s", err);
    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='diffuse'><rgb name='reflectance' value='0.5, -0.1, 0.2'/></bsdf>",
                                   err, sizeof err));
    cr_assert(strstr(err, "reflectance"), "%s", err);
    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='twosided'/>", err, sizeof err));
    cr_assert(strstr(err, "needs at least 1 nested <bsdf>"), "%s", err);
    cr_assert_null(plugin_xml_bsdf(&fx, "<bsdf type='conductor'><string name='material' value='Unobtainium'/></bsdf>",
                                   err, sizeof err));
    cr_assert(strstr(err, "unknown conductor material 'Unobtainium'"), "%s", err);

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
            for (int dist = 0; dist < 2; dist++) {
                const char *t = dist ? "ggx" : "beckmann";
                char xml[300];
                if (kind == 0)
                    snprintf(xml, sizeof xml, "<bsdf type='roughconductor'><float name='alpha' value='%g'/>"
                             "<string name='distribution' value='%s'/></bsdf>", alphas[a], t);
                else if (kind == 1)
                    snprintf(xml, sizeof xml, "<bsdf type='roughdielectric'><float name='alpha_u' value='%g'/>"
                             "<float name='alpha_v' value='0.3'/><string name='distribution' value='%s'/></bsdf>",
                             alphas[a], t);
                else if (kind == 2)
                    snprintf(xml, sizeof xml, "<bsdf type='roughplastic'><float name='alpha' value='%g'/>"
                             "<string name='distribution' value='%s'/></bsdf>", alphas[a], t);
                else
                    snprintf(xml, sizeof xml, "<bsdf type='roughdielectric'><float name='alpha' value='%g'/>"
                             "<boolean name='sample_visible' value='false'/>"
                             "<string name='distribution' value='%s'/></bsdf>", alphas[a], t);
                plugin_xml_close(&fx);
                plugin_xml_open(&fx);
                const bsdf_t *b = bsdf_of(xml);
                for (int w = 0; w < 6; w++) {
                    bsdf_query q = {.wi = v3_norm(wis[w]), .uv = v2(0, 0), .mode = TRANSPORT_RADIANCE};
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
            }
        }
}
