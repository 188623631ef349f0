/* Mitsuba's render z-test (include/celadon/ztest.h): p-values against
 * erfc, the Sidak level, the 0.9975 pass rule at its boundary, and its
 * verdict on synthetic renders drawn from a known mean and variance
 * (unbiased: passes; biased by 10%: fails). */
#include <criterion/criterion.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>

#include "celadon/ztest.h"

/* Grey pixels: the Y row of sRGB -> XYZ sums to 1, so a grey mean g over a
 * grey variance v has Y = g and var_Y = v exactly. */
static void fill_grey(float *img, int n, float g)
{
    for (int i = 0; i < 3 * n; i++)
        img[i] = g;
}

Test(ztest, p_value_is_two_sided_normal_tail)
{
    float mean[3], ref[3], var[3], p[3];
    fill_grey(ref, 1, 0.0f);
    fill_grey(var, 1, 1.0f);
    fill_grey(mean, 1, 1.0f);
    /* spp 4: z_Y = 1 * sqrt(4 / 1) = 2, p = erfc(2 / sqrt 2) */
    ztest_result r = ztest_run(mean, ref, var, 1, 4, p);
    cr_assert_float_eq(p[1], erfc(2.0 / sqrt(2.0)), 2e-6, "p_Y %g", p[1]);
    cr_assert_float_eq(r.alpha, 0.01, 1e-12);
    cr_assert(r.pass, "z = 2 is not significant at 1%%");
    /* the variance floor: var 0 counts as 1e-4 */
    fill_grey(var, 1, 0.0f);
    fill_grey(mean, 1, 0.01f);
    ztest_run(mean, ref, var, 1, 4, p);
    cr_assert_float_eq(p[1], erfc(2.0 / sqrt(2.0)), 2e-6, "p_Y %g with var 0", p[1]);
}

Test(ztest, sidak_level)
{
    float px[3 * 1000] = {0};
    ztest_result r = ztest_run(px, px, px, 1000, 1, NULL);
    cr_assert_float_eq(r.alpha, 1.0 - pow(0.99, 1e-3), 1e-15);
    cr_assert(r.alpha < 0.01 / 1000 * 1.01 && r.alpha > 0.01 / 1000 * 0.99, "alpha %g ~ 0.01 / n", r.alpha);
    cr_assert(r.pass && r.failed_pixels == 0 && r.passed_channels == 3000);
}

/* 400 pixels: 0.9975 * 400 = 399, so one bad pixel (3 channels) passes and
 * two fail. */
Test(ztest, pass_rule_boundary)
{
    enum { N = 400 };
    static float mean[3 * N], ref[3 * N], var[3 * N];
    fill_grey(ref, N, 0.5f);
    fill_grey(var, N, 0.01f);
    fill_grey(mean, N, 0.5f);
    fill_grey(mean, 1, 5.0f);
    ztest_result r = ztest_run(mean, ref, var, N, 100, NULL);
    cr_assert(r.pass && r.failed_pixels == 1 && r.passed_channels == 3 * N - 3);
    cr_assert_eq(r.min_p, 0.0f);
    fill_grey(mean, 2, 5.0f);
    r = ztest_run(mean, ref, var, N, 100, NULL);
    cr_assert(!r.pass && r.failed_pixels == 2);
    mean[3 * 7] = NAN; /* a NaN in R fails X, Y and Z of its pixel */
    fill_grey(mean, 2, 0.5f);
    r = ztest_run(mean, ref, var, N, 100, NULL);
    cr_assert(r.pass && r.failed_pixels == 1 && r.passed_channels == 3 * N - 3);
}

/* A render drawn from the reference's own distribution: each pixel the mean
 * of spp samples of per-sample variance var, i.e. ref + N(0, var / spp). */
static ztest_result synthetic(double bias, unsigned long seed)
{
    enum { N = 64 * 64, SPP = 488 };
    float *mean = malloc(sizeof(float) * 3 * N), *ref = malloc(sizeof(float) * 3 * N),
          *var = malloc(sizeof(float) * 3 * N);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, seed);
    for (int i = 0; i < N; i++) {
        double g = 0.05 + gsl_rng_uniform(rng), v = 0.05 * g * g + 1e-4 * gsl_rng_uniform(rng);
        double m = g * (1.0 + bias) + gsl_ran_gaussian(rng, sqrt(v / SPP));
        for (int c = 0; c < 3; c++)
            ref[3 * i + c] = (float)g, var[3 * i + c] = (float)v, mean[3 * i + c] = (float)m;
    }
    ztest_result r = ztest_run(mean, ref, var, N, SPP, NULL);
    gsl_rng_free(rng);
    free(mean), free(ref), free(var);
    return r;
}

Test(ztest, unbiased_synthetic_render_passes)
{
    for (unsigned long seed = 1; seed <= 5; seed++) {
        ztest_result r = synthetic(0.0, seed);
        cr_assert(r.pass, "seed %lu: %ld pixels failed", seed, r.failed_pixels);
        cr_assert(r.failed_pixels <= 2, "seed %lu: %ld pixels failed", seed, r.failed_pixels);
    }
}

Test(ztest, biased_synthetic_render_fails)
{
    ztest_result r = synthetic(0.1, 1);
    cr_assert(!r.pass, "a 10%% bias passed (%ld pixels failed)", r.failed_pixels);
    /* and a 1% bias, one sigma of 488 samples at this variance, passes */
    r = synthetic(0.01, 1);
    cr_assert(r.pass, "a 1%% bias failed (%ld pixels)", r.failed_pixels);
}
