/* Chi-square machinery shared by the material tests (see test_bsdf_support.h). */
#include "test_bsdf_support.h"

#include <criterion/criterion.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Number of chi-square tests in the suite (71 when this was written), for the
 * Sidak correction. */
#define CHI2_TESTS_IN_SUITE 72

double chi2_threshold(void)
{
    return 1.0 - pow(1.0 - 0.01, 1.0 / CHI2_TESTS_IN_SUITE);
}

double chi2_pvalue_counts(const double *observed, const double *expected, int n, int *dof)
{
    double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
    int terms = 0;
    for (int i = 0; i < n; i++) {
        if (expected[i] < 5.0) {
            pooled_o += observed[i];
            pooled_e += fmax(expected[i], 0.0);
            continue;
        }
        double d = observed[i] - expected[i];
        chi2 += d * d / expected[i];
        terms++;
    }
    if (pooled_e > 0.0) {
        double d = pooled_o - pooled_e;
        chi2 += d * d / pooled_e;
        terms++;
    } else if (pooled_o > 0.0) {
        /* Samples where the density claims there can be none. */
        if (dof)
            *dof = terms;
        return 0.0;
    }
    if (dof)
        *dof = terms - 1;
    return terms > 1 ? gsl_cdf_chisq_Q(chi2, terms - 1) : 1.0;
}

/* Integral of the pdf over one cell z0 <= cos theta <= z1, p0 <= phi <= p1,
 * computed in (theta, phi) with the sin(theta) Jacobian (smooth at the poles,
 * unlike cos theta) by composite 3-point Gauss-Legendre: 8 panels in theta, 4
 * in phi. Nodes are interior, so a density that jumps on a cell boundary is
 * integrated correctly. */
static double cell_integral(const sphere_sampler *s, double z0, double z1, double p0, double p1)
{
    static const double node[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static const double weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    const int mt = 8, mp = 4;
    double t0 = acos(fmin(z1, 1.0)), t1 = acos(fmax(z0, -1.0));
    double ht = (t1 - t0) / mt, hp = (p1 - p0) / mp, sum = 0.0;
    for (int i = 0; i < mt; i++)
        for (int a = 0; a < 3; a++) {
            double th = t0 + ht * (i + 0.5 + 0.5 * node[a]), st = sin(th), z = cos(th);
            for (int j = 0; j < mp; j++)
                for (int b = 0; b < 3; b++) {
                    double phi = p0 + hp * (j + 0.5 + 0.5 * node[b]);
                    sum += weight[a] * weight[b] * st * s->pdf(s->ctx, v3(st * cos(phi), st * sin(phi), z));
                }
        }
    return sum * ht * hp / 4.0;
}

double chi2_sphere(const sphere_sampler *s, int n_cos, int n_phi, long n_samples, uint64_t seed, char *msg,
                   size_t msglen)
{
    int n = n_cos * n_phi;
    double *obs = calloc((size_t)n + 1, sizeof *obs), *exp_ = calloc((size_t)n + 1, sizeof *exp_);
    rng_t rng;
    rng_seed(&rng, seed, 7);
    for (long k = 0; k < n_samples; k++) {
        vec3 w;
        if (!s->sample(s->ctx, &rng, &w)) {
            obs[n] += 1.0;
            continue;
        }
        double z = fmin(fmax(w.z, -1.0), 1.0);
        double phi = atan2(w.y, w.x);
        if (phi < 0.0)
            phi += 2.0 * M_PI;
        int iz = (int)((z + 1.0) * 0.5 * n_cos), ip = (int)(phi / (2.0 * M_PI) * n_phi);
        iz = iz < 0 ? 0 : (iz >= n_cos ? n_cos - 1 : iz);
        ip = ip < 0 ? 0 : (ip >= n_phi ? n_phi - 1 : ip);
        obs[iz * n_phi + ip] += 1.0;
    }
    double total = 0.0;
    for (int iz = 0; iz < n_cos; iz++)
        for (int ip = 0; ip < n_phi; ip++) {
            double z0 = -1.0 + 2.0 * iz / n_cos, z1 = -1.0 + 2.0 * (iz + 1) / n_cos;
            double p0 = 2.0 * M_PI * ip / n_phi, p1 = 2.0 * M_PI * (ip + 1) / n_phi;
            double integral = cell_integral(s, z0, z1, p0, p1);
            exp_[iz * n_phi + ip] = integral * n_samples;
            total += integral;
        }
    exp_[n] = fmax(0.0, 1.0 - total) * n_samples;
    int dof;
    double p = chi2_pvalue_counts(obs, exp_, n + 1, &dof);
    snprintf(msg, msglen, "p = %.3g (dof %d, pdf integral %.5f, non-density samples %.0f, expected %.1f)", p, dof,
             total, obs[n], exp_[n]);
    free(obs);
    free(exp_);
    return p;
}

bsdf_query query_at(double theta_deg, double phi_deg, transport_mode mode)
{
    double t = theta_deg * M_PI / 180.0, p = phi_deg * M_PI / 180.0;
    bsdf_query q = {v3(sin(t) * cos(p), sin(t) * sin(p), cos(t)), v2(0.3, 0.6), mode};
    return q;
}

/* Textures the cases borrow; created once per test process. */
static texture_t *case_checker;

static bsdf_t *checked(bsdf_t *b, const char *err)
{
    cr_assert_not_null(b, "creating a test BSDF: %s", err);
    return b;
}

int bsdf_cases_make(bsdf_case *c)
{
    char err[256];
    int n = 0;
    rgb au_eta, au_k, cu_eta, cu_k;
    cr_assert_eq(bsdf_conductor_preset("Au", &au_eta, &au_k), 0);
    cr_assert_eq(bsdf_conductor_preset("Cu", &cu_eta, &cu_k), 0);
    texture_checkerboard_params cp = texture_checkerboard_defaults();
    cp.color0 = rgb_make(0.9, 0.6, 0.3);
    case_checker = texture_create_checkerboard(&cp);

    bsdf_diffuse_params dp = bsdf_diffuse_defaults();
    dp.reflectance = bsdf_spectrum_tex(case_checker);
    c[n++] = (bsdf_case){"diffuse (checkerboard)", checked(bsdf_create_diffuse(&dp, err, sizeof err), err), 0, 1};

    bsdf_conductor_params cd = bsdf_conductor_defaults();
    cd.eta = au_eta;
    cd.k = au_k;
    c[n++] = (bsdf_case){"conductor Au", checked(bsdf_create_conductor(&cd, err, sizeof err), err), 0, 1};

    bsdf_roughconductor_params rc = bsdf_roughconductor_defaults();
    rc.eta = au_eta;
    rc.k = au_k;
    rc.alpha_u = rc.alpha_v = 0.3;
    c[n++] = (bsdf_case){"roughconductor beckmann 0.3 Au", checked(bsdf_create_roughconductor(&rc, err, sizeof err), err), 0, 1};
    rc.eta = cu_eta;
    rc.k = cu_k;
    rc.distribution = MICROFACET_GGX;
    rc.alpha_u = 0.15;
    rc.alpha_v = 0.5;
    c[n++] = (bsdf_case){"roughconductor ggx 0.15x0.5 Cu", checked(bsdf_create_roughconductor(&rc, err, sizeof err), err), 0, 1};
    rc.sample_visible = 0;
    rc.alpha_u = rc.alpha_v = 0.3;
    c[n++] = (bsdf_case){"roughconductor ggx 0.3 all normals", checked(bsdf_create_roughconductor(&rc, err, sizeof err), err), 0, 1};
    rc.distribution = MICROFACET_BECKMANN;
    rc.alpha_u = 0.25;
    rc.alpha_v = 0.4;
    c[n++] = (bsdf_case){"roughconductor beckmann 0.25x0.4 all normals", checked(bsdf_create_roughconductor(&rc, err, sizeof err), err), 0, 1};

    bsdf_dielectric_params de = bsdf_dielectric_defaults();
    c[n++] = (bsdf_case){"dielectric", checked(bsdf_create_dielectric(&de, err, sizeof err), err), 1, 0};
    c[n++] = (bsdf_case){"thindielectric", checked(bsdf_create_thindielectric(&de, err, sizeof err), err), 1, 0};

    bsdf_roughdielectric_params rd = bsdf_roughdielectric_defaults();
    rd.alpha_u = rd.alpha_v = 0.3;
    c[n++] = (bsdf_case){"roughdielectric beckmann 0.3", checked(bsdf_create_roughdielectric(&rd, err, sizeof err), err), 1, 0};
    rd.distribution = MICROFACET_GGX;
    rd.alpha_u = 0.2;
    rd.alpha_v = 0.35;
    rd.int_ior = 1.333;
    c[n++] = (bsdf_case){"roughdielectric ggx 0.2x0.35 water", checked(bsdf_create_roughdielectric(&rd, err, sizeof err), err), 1, 0};
    rd.distribution = MICROFACET_BECKMANN;
    rd.sample_visible = 0;
    rd.alpha_u = rd.alpha_v = 0.3;
    c[n++] = (bsdf_case){"roughdielectric beckmann 0.3 all normals", checked(bsdf_create_roughdielectric(&rd, err, sizeof err), err), 1, 0};

    bsdf_plastic_params pl = bsdf_plastic_defaults();
    c[n++] = (bsdf_case){"plastic", checked(bsdf_create_plastic(&pl, err, sizeof err), err), 0, 1};
    pl.nonlinear = 1;
    pl.diffuse_reflectance = bsdf_spectrum_const(rgb_make(0.9, 0.2, 0.05));
    c[n++] = (bsdf_case){"plastic nonlinear", checked(bsdf_create_plastic(&pl, err, sizeof err), err), 0, 1};

    bsdf_roughplastic_params rp = bsdf_roughplastic_defaults();
    rp.alpha = 0.2;
    c[n++] = (bsdf_case){"roughplastic beckmann 0.2", checked(bsdf_create_roughplastic(&rp, err, sizeof err), err), 0, 1};
    rp.distribution = MICROFACET_GGX;
    rp.alpha = 0.3;
    rp.nonlinear = 1;
    rp.diffuse_reflectance = bsdf_spectrum_const(rgb_make(0.95, 0.5, 0.1));
    c[n++] = (bsdf_case){"roughplastic ggx 0.3 nonlinear", checked(bsdf_create_roughplastic(&rp, err, sizeof err), err), 0, 1};

    /* Two-sided wrappers borrow the BSDFs above. */
    c[n++] = (bsdf_case){"twosided roughconductor", checked(bsdf_create_twosided(c[2].bsdf, NULL, err, sizeof err), err), 1, 1};
    c[n++] = (bsdf_case){"twosided diffuse | roughplastic", checked(bsdf_create_twosided(c[0].bsdf, c[13].bsdf, err, sizeof err), err), 1, 1};
    cr_assert_leq(n, BSDF_CASES_MAX);
    return n;
}

void bsdf_cases_free(bsdf_case *cases, int n)
{
    for (int i = 0; i < n; i++)
        bsdf_free(cases[i].bsdf);
    texture_free(case_checker);
    case_checker = NULL;
}
