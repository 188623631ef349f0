/* Sample warps and tabulated distributions: densities integrate to one, the
 * warps land where their densities say (chi-square), PCG32 matches its
 * reference stream. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "celadon/rng.h"
#include "celadon/sampling.h"
#include "test_bsdf_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

Test(rng, matches_pcg32_reference_stream)
{
    /* First outputs of O'Neill's pcg32-demo for pcg32_srandom(42, 54). */
    const uint32_t expect[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    rng_t r;
    rng_seed(&r, 42, 54);
    for (int i = 0; i < 6; i++)
        cr_assert_eq(rng_next_u32(&r), expect[i], "output %d", i);
}

Test(rng, sample_streams_are_deterministic_and_distinct)
{
    rng_t a = rng_for_sample(1, 10, 20, 3), b = rng_for_sample(1, 10, 20, 3);
    rng_t c = rng_for_sample(1, 10, 20, 4), d = rng_for_sample(1, 20, 10, 3), e = rng_for_sample(2, 10, 20, 3);
    int same_c = 0, same_d = 0, same_e = 0;
    double sum = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; i++) {
        uint32_t x = rng_next_u32(&a);
        cr_assert_eq(x, rng_next_u32(&b));
        same_c += x == rng_next_u32(&c);
        same_d += x == rng_next_u32(&d);
        same_e += x == rng_next_u32(&e);
        double u = rng_next_double(&b);
        rng_next_double(&a);
        cr_assert(u >= 0.0 && u < 1.0);
        sum += u;
    }
    cr_assert_lt(same_c + same_d + same_e, 3);
    /* Mean of n uniforms: sd = sqrt(1/12 / n). */
    cr_assert_lt(fabs(sum / n - 0.5), 5.0 * sqrt(1.0 / 12.0 / n));
}

Test(rng, bounded_is_uniform)
{
    rng_t r;
    rng_seed(&r, 9, 1);
    double obs[7] = {0}, exp_[7];
    for (int i = 0; i < 70000; i++)
        obs[rng_next_bounded(&r, 7)] += 1.0;
    for (int i = 0; i < 7; i++)
        exp_[i] = 10000.0;
    cr_assert_gt(chi2_pvalue_counts(obs, exp_, 7, NULL), chi2_threshold());
}

/* ---- sphere warps through the chi-square harness ---- */

typedef struct {
    int kind;
    double cos_max;
} warp_ctx;

static int warp_sample(void *ctx, rng_t *rng, vec3 *w)
{
    const warp_ctx *c = ctx;
    vec2 u = v2(rng_next_double(rng), rng_next_double(rng));
    switch (c->kind) {
    case 0: *w = warp_square_to_cosine_hemisphere(u); break;
    case 1: *w = warp_square_to_uniform_hemisphere(u); break;
    case 2: *w = warp_square_to_uniform_sphere(u); break;
    default: *w = warp_square_to_uniform_cone(u, c->cos_max); break;
    }
    return 1;
}

static double warp_pdf(void *ctx, vec3 w)
{
    const warp_ctx *c = ctx;
    switch (c->kind) {
    case 0: return warp_cosine_hemisphere_pdf(w);
    case 1: return warp_uniform_hemisphere_pdf(w);
    case 2: return warp_uniform_sphere_pdf();
    default: return warp_uniform_cone_pdf(w, c->cos_max);
    }
}

Test(sampling, sphere_warps_match_their_densities)
{
    const char *names[] = {"cosine hemisphere", "uniform hemisphere", "uniform sphere", "uniform cone"};
    for (int kind = 0; kind < 4; kind++) {
        /* The cone's edge (cos 0.5) is a cell boundary of the 16-cell cos grid. */
        warp_ctx c = {kind, 0.5};
        sphere_sampler s = {warp_sample, warp_pdf, &c};
        char msg[256];
        double p = chi2_sphere(&s, 16, 32, 100000, 100 + kind, msg, sizeof msg);
        cr_assert_gt(p, chi2_threshold(), "%s: %s", names[kind], msg);
        /* The density integrates to one: the extra cell expects nothing. */
        cr_assert(strstr(msg, "pdf integral 1.000") || strstr(msg, "pdf integral 0.999"), "%s: %s", names[kind], msg);
    }
}

Test(sampling, concentric_disk_and_triangle_are_uniform)
{
    rng_t r;
    rng_seed(&r, 5, 5);
    double obs_d[64] = {0}, obs_t[64] = {0}, exp_d[64], exp_t[64];
    const int n = 64000;
    int in_tri = 0;
    for (int i = 0; i < n; i++) {
        vec2 u = v2(rng_next_double(&r), rng_next_double(&r));
        vec2 p = warp_square_to_concentric_disk(u);
        cr_assert_leq(v2_dot(p, p), 1.0 + 1e-12);
        /* Equal-area annular sectors: 8 radii by sqrt, 8 angles. */
        double rr = v2_dot(p, p), a = atan2(p.y, p.x) + M_PI;
        int ir = (int)(rr * 8), ia = (int)(a / (2 * M_PI) * 8);
        obs_d[(ir > 7 ? 7 : ir) * 8 + (ia > 7 ? 7 : ia)] += 1.0;
        vec2 b = warp_square_to_uniform_triangle(u);
        in_tri += b.x >= 0 && b.y >= 0 && b.x + b.y <= 1.0;
        /* Bins: 8 strips in b1 of equal area: b1 < 1 - sqrt(1 - k/8). */
        int ib = (int)((1.0 - (1.0 - b.x) * (1.0 - b.x)) * 8), ic = (int)(b.y / (1.0 - b.x + 1e-300) * 8);
        obs_t[(ib > 7 ? 7 : ib) * 8 + (ic > 7 ? 7 : ic)] += 1.0;
    }
    for (int i = 0; i < 64; i++)
        exp_d[i] = exp_t[i] = n / 64.0;
    cr_assert_eq(in_tri, n);
    cr_assert_gt(chi2_pvalue_counts(obs_d, exp_d, 64, NULL), chi2_threshold(), "disk");
    cr_assert_gt(chi2_pvalue_counts(obs_t, exp_t, 64, NULL), chi2_threshold(), "triangle");
    cr_assert_float_eq(warp_concentric_disk_pdf(v2(0.5, 0.5)), 1.0 / M_PI, 1e-15);
}

Test(sampling, power_heuristic)
{
    cr_assert_float_eq(mis_power_heuristic(1.0, 1.0), 0.5, 1e-15);
    cr_assert_float_eq(mis_power_heuristic(3.0, 1.0), 0.9, 1e-15);
    cr_assert_float_eq(mis_power_heuristic(3.0, 1.0) + mis_power_heuristic(1.0, 3.0), 1.0, 1e-15);
    cr_assert_eq(mis_power_heuristic(0.0, 0.0), 0.0);
    cr_assert_eq(mis_power_heuristic(INFINITY, 2.0), 1.0);
}

Test(sampling, distribution1d_discrete_and_continuous)
{
    const double f[5] = {1.0, 0.0, 3.0, 0.0, 4.0};
    distribution1d d;
    cr_assert_eq(distribution1d_init(&d, f, 5), 0);
    cr_assert_float_eq(d.integral, 8.0 / 5.0, 1e-15);
    cr_assert_float_eq(distribution1d_pmf(&d, 2), 3.0 / 8.0, 1e-15);
    /* Zero cells are never picked, even at their cdf boundary. */
    double pmf, reuse;
    cr_assert_eq(distribution1d_sample_discrete(&d, 1.0 / 8.0, &pmf, &reuse), 2);
    cr_assert_float_eq(reuse, 0.0, 1e-15);
    cr_assert_eq(distribution1d_sample_discrete(&d, 0.3, &pmf, &reuse), 2);
    cr_assert_float_eq(reuse, (0.3 - 0.125) / 0.375, 1e-12);
    cr_assert_eq(distribution1d_sample_discrete(&d, 0.5, &pmf, &reuse), 4);
    double pdf;
    int cell;
    double x = distribution1d_sample_continuous(&d, 0.9, &pdf, &cell);
    cr_assert_eq(cell, 4);
    cr_assert_float_eq(x, 0.8 + 0.2 * (0.9 - 0.5) / 0.5, 1e-12);
    cr_assert_float_eq(pdf, distribution1d_pdf(&d, x), 1e-12);
    cr_assert_float_eq(pdf, 4.0 / 8.0 * 5.0, 1e-12);
    cr_assert_eq(distribution1d_pdf(&d, 0.3), 0.0);
    distribution1d_free(&d);

    const double zero[3] = {0, 0, 0};
    cr_assert_eq(distribution1d_init(&d, zero, 3), 0);
    cr_assert_float_eq(distribution1d_pdf(&d, 0.5), 1.0, 1e-15);
    distribution1d_free(&d);
    cr_assert_eq(distribution1d_init(&d, f, 0), -1);
}

Test(sampling, distribution2d_chi_square_and_pdf)
{
    enum { NU = 8, NV = 6, R = 4 };
    double f[NU * NV];
    rng_t r;
    rng_seed(&r, 77, 3);
    for (int i = 0; i < NU * NV; i++)
        f[i] = (i % 7 == 3) ? 0.0 : 0.1 + rng_next_double(&r) * (i % 5 + 1);
    for (int u = 0; u < NU; u++)
        f[2 * NU + u] = 0.0; /* an empty row */
    distribution2d d;
    cr_assert_eq(distribution2d_init(&d, f, NU, NV), 0);

    /* Density integrates to one (it is constant on each cell). */
    double total = 0.0, fsum = 0.0;
    for (int v = 0; v < NV; v++)
        for (int u = 0; u < NU; u++) {
            total += distribution2d_pdf(&d, v2((u + 0.5) / NU, (v + 0.5) / NV)) / (NU * NV);
            fsum += f[v * NU + u];
        }
    cr_assert_float_eq(total, 1.0, 1e-12);
    /* ... and is proportional to f. */
    cr_assert_float_eq(distribution2d_pdf(&d, v2(5.5 / NU, 4.5 / NV)), f[4 * NU + 5] / (fsum / (NU * NV)), 1e-12);

    /* Histogram on a grid R times finer than the cells. */
    const int n = 200000, cells = NU * NV * R * R;
    double obs[NU * NV * R * R] = {0}, exp_[NU * NV * R * R];
    for (int i = 0; i < n; i++) {
        double pdf;
        vec2 p = distribution2d_sample(&d, v2(rng_next_double(&r), rng_next_double(&r)), &pdf);
        cr_assert(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
        cr_assert_float_eq(pdf, distribution2d_pdf(&d, p), 1e-9);
        int iu = (int)(p.x * NU * R), iv = (int)(p.y * NV * R);
        obs[iv * NU * R + iu] += 1.0;
    }
    for (int iv = 0; iv < NV * R; iv++)
        for (int iu = 0; iu < NU * R; iu++)
            exp_[iv * NU * R + iu] =
                n * distribution2d_pdf(&d, v2((iu + 0.5) / (NU * R), (iv + 0.5) / (NV * R))) / cells;
    int dof;
    double p = chi2_pvalue_counts(obs, exp_, cells, &dof);
    cr_assert_gt(p, chi2_threshold(), "p = %g, dof %d", p, dof);
    distribution2d_free(&d);
}
