/* The samplers: every number in [0, 1); each plugin's 2D projections
 * stratified as its method promises (exact cell counts, the (0,m,2)-net
 * property of the Sobol-based ones) and their star discrepancy within the
 * bound that follows from it; the independent sampler's discrepancy that of
 * uniform random points; sample counts rounded by Mitsuba's and pbrt-v4's
 * rules; the numbers a pure function of (seed, pixel, sample, dimension);
 * and the building blocks (permutations, bit reversal, the Sobol points, Owen scrambling). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "samplers/samplers.h"
#include "samplers/sequences.h"
#include "support/plugin_xml.h"

/* The sampler <sampler type="TYPE" PARAMS/>, prepared for a 64x64 film. */
static sampler_t make_sampler(const char *type, const char *params, long long count)
{
    plugin_xml f;
    plugin_xml_open(&f);
    char xml[512], err[512];
    snprintf(xml, sizeof xml,
             "<sensor type=\"perspective\"><sampler type=\"%s\"><integer name=\"sample_count\" value=\"%lld\"/>"
             "%s</sampler></sensor>",
             type, count, params);
    scene_obj *sensor;
    cr_assert_eq(plugin_xml_objects(&f, xml, SCENE_SENSOR, &sensor, 1, err, sizeof err), 1, "%s", err);
    scene_obj *o = scene_obj_child(sensor, SCENE_SAMPLER);
    sampler_t s;
    cr_assert_eq(sampler_plugin_find(type)->create(o, &s, err, sizeof err), 0, "%s", err);
    plugin_xml_close(&f);
    sampler_prepare(&s, 64, 64);
    return s;
}

/* The stream of sample k of a pixel, at dimension dim. */
static sampler_stream stream_at(const sampler_t *s, uint32_t px, uint32_t py, uint32_t k, uint32_t dim)
{
    sampler_stream st;
    sampler_start(s, &st, px, py, k);
    sampler_seek(&st, dim);
    return st;
}

/* The 2D points of dimensions (dim, dim + 1) of every sample of a pixel. */
static void pixel_points(const sampler_t *s, uint32_t px, uint32_t py, uint32_t dim, vec2 *pts)
{
    for (uint32_t k = 0; k < (uint32_t)s->sample_count; k++) {
        sampler_stream st = stream_at(s, px, py, k, dim);
        pts[k] = sampler_next_2d(&st);
    }
}

static void pixel_numbers(const sampler_t *s, uint32_t px, uint32_t py, uint32_t dim, double *x)
{
    for (uint32_t k = 0; k < (uint32_t)s->sample_count; k++) {
        sampler_stream st = stream_at(s, px, py, k, dim);
        x[k] = sampler_next_1d(&st);
    }
}

/* Each of the nx x ny cells holds `each` points. */
static bool grid_stratified(const vec2 *p, int n, int nx, int ny, int each)
{
    int *c = calloc((size_t)(nx * ny), sizeof *c);
    cr_assert_not_null(c);
    for (int i = 0; i < n; i++)
        c[(int)(p[i].y * ny) * nx + (int)(p[i].x * nx)]++;
    bool ok = true;
    for (int i = 0; i < nx * ny; i++)
        ok = ok && c[i] == each;
    free(c);
    return ok;
}

static bool strata_1d(const double *x, int n)
{
    int *c = calloc((size_t)n, sizeof *c);
    cr_assert_not_null(c);
    bool ok = true;
    for (int i = 0; i < n; i++)
        c[(int)(x[i] * n)]++;
    for (int i = 0; i < n; i++)
        ok = ok && c[i] == 1;
    free(c);
    return ok;
}

/* A (0,m,2)-net in base 2: every elementary interval 2^-k x 2^-(m-k)
 * holds one point. */
static bool is_net(const vec2 *p, int m)
{
    int n = 1 << m;
    for (int k = 0; k <= m; k++)
        if (!grid_stratified(p, n, 1 << k, 1 << (m - k), 1))
            return false;
    return true;
}

/* The exact star discrepancy of n points of [0,1)^2: the largest gap
 * between the share of points in an anchored box [0,x)x[0,y) (open or
 * closed at the far corner) and its area, over the boxes whose corners are
 * point coordinates or 1. */
static double star_discrepancy(const vec2 *p, int n)
{
    double d = 0.0;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++) {
            double x = i < n ? p[i].x : 1.0, y = j < n ? p[j].y : 1.0;
            int open = 0, closed = 0;
            for (int k = 0; k < n; k++) {
                open += p[k].x < x && p[k].y < y;
                closed += p[k].x <= x && p[k].y <= y;
            }
            d = fmax(d, fmax(x * y - (double)open / n, (double)closed / n - x * y));
        }
    return d;
}

/* Warnock's formula: the squared L2 star discrepancy of n points. */
static double l2_star_discrepancy2(const vec2 *p, int n)
{
    double a = 0.0, b = 0.0;
    for (int i = 0; i < n; i++) {
        a += (1.0 - p[i].x * p[i].x) * (1.0 - p[i].y * p[i].y);
        for (int j = 0; j < n; j++)
            b += (1.0 - fmax(p[i].x, p[j].x)) * (1.0 - fmax(p[i].y, p[j].y));
    }
    return 1.0 / 9.0 - a / (2.0 * n) + b / ((double)n * n);
}

/* The dimensions the path integrator pairs (film, a vertex's light point
 * and BSDF direction) and some far ones. */
static const uint32_t pair_dims[] = {SAMPLER_DIM_FILM, SAMPLER_DIM_INTEGRATOR + 1, SAMPLER_DIM_INTEGRATOR + 4,
                                     SAMPLER_DIM_INTEGRATOR + 7 * 7 + 1, 301};
enum { NPAIRS = sizeof pair_dims / sizeof pair_dims[0] };

static const char *const all_samplers[] = {"independent", "stratified", "multijitter",
                                           "orthogonal",  "ldsampler",  "zsobol"};

Test(samplers, numbers_in_unit_interval)
{
    for (int t = 0; t < 6; t++)
        for (int jitter = 0; jitter < 2; jitter++) {
            bool jitters = strcmp(all_samplers[t], "ldsampler") && strcmp(all_samplers[t], "zsobol") &&
                           strcmp(all_samplers[t], "independent");
            if (!jitter && !jitters)
                continue;
            sampler_t s = make_sampler(all_samplers[t], jitter ? "" : "<boolean name=\"jitter\" value=\"false\"/>", 7);
            for (uint32_t py = 0; py < 9; py++)
                for (uint32_t px = 60000; px < 60009; px++)
                    for (uint32_t k = 0; k < (uint32_t)s.sample_count; k++) {
                        sampler_stream st;
                        sampler_start(&s, &st, px, py, k);
                        for (int d = 0; d < 40; d++) {
                            double x = sampler_next_1d(&st);
                            vec2 v = sampler_next_2d(&st);
                            cr_assert(x >= 0.0 && x < 1.0 && v.x >= 0.0 && v.x < 1.0 && v.y >= 0.0 && v.y < 1.0,
                                      "%s: %.17g %.17g %.17g", all_samplers[t], x, v.x, v.y);
                        }
                    }
        }
}

Test(samplers, sample_counts_rounded_as_mitsuba_and_pbrt_do)
{
    cr_expect_eq(make_sampler("independent", "", 10).sample_count, 10);
    cr_expect_eq(make_sampler("stratified", "", 10).sample_count, 16);   /* a square */
    cr_expect_eq(make_sampler("multijitter", "", 10).sample_count, 12);  /* 4 x 3 */
    cr_expect_eq(make_sampler("orthogonal", "", 10).sample_count, 25);   /* a prime's square */
    cr_expect_eq(make_sampler("orthogonal", "<integer name=\"strength\" value=\"3\"/>", 10).sample_count, 27);
    cr_expect_eq(make_sampler("ldsampler", "", 17).sample_count, 64);    /* a power of 4 */
    cr_expect_eq(make_sampler("zsobol", "", 17).sample_count, 32);       /* a power of 2 */
    cr_expect_eq(make_sampler("zsobol", "", 64).sample_count, 64);
}

/* Every pixel (of a few) and paired dimension: the grid or net the method
 * promises, each 1D dimension in sample_count strata, and the star
 * discrepancy within the bound that follows: an anchored box's far edges
 * cross at most nx + ny - 1 cells of a grid (each off by at most its
 * points), and a (0,m,2)-net in base 2 has n D* <= m/2 + 3/2 (Niederreiter
 * 1992, Theorem 4.10, b = 2, t = 0). */
static void check_stratified(const char *type, const char *params, long long count, int nx, int ny, int per_cell,
                             int net_m)
{
    sampler_t s = make_sampler(type, params, count);
    int n = (int)s.sample_count;
    vec2 *p = malloc(sizeof *p * (size_t)n);
    double *x = malloc(sizeof *x * (size_t)n);
    cr_assert(p && x);
    for (uint32_t pix = 0; pix < 5; pix++)
        for (int d = 0; d < NPAIRS; d++) {
            uint32_t px = 3 + 7 * pix, py = 11 * pix;
            pixel_points(&s, px, py, pair_dims[d], p);
            double disc = star_discrepancy(p, n), bound;
            if (net_m > 0) {
                cr_assert(is_net(p, net_m), "%s: pixel (%u,%u) dims %u-%u: not a (0,%d,2)-net", type, px, py,
                          pair_dims[d], pair_dims[d] + 1, net_m);
                bound = (net_m / 2.0 + 1.5) / n;
            } else {
                cr_assert(grid_stratified(p, n, nx, ny, per_cell), "%s: pixel (%u,%u) dims %u-%u: not %dx%d strata",
                          type, px, py, pair_dims[d], pair_dims[d] + 1, nx, ny);
                bound = (double)(nx + ny - 1) * per_cell / n;
            }
            cr_assert_leq(disc, bound, "%s dims %u-%u: star discrepancy %g above the bound %g", type, pair_dims[d],
                          pair_dims[d] + 1, disc, bound);
            pixel_numbers(&s, px, py, pair_dims[d] + 2, x);
            cr_assert(strata_1d(x, n), "%s: dimension %u not in %d strata", type, pair_dims[d] + 2, n);
        }
    free(p), free(x);
}

Test(samplers, stratified_grid) { check_stratified("stratified", "", 16, 4, 4, 1, 0); }
Test(samplers, stratified_grid_unjittered)
{
    check_stratified("stratified", "<boolean name=\"jitter\" value=\"false\"/>", 49, 7, 7, 1, 0);
}
Test(samplers, multijitter_grid) { check_stratified("multijitter", "", 12, 4, 3, 1, 0); }
Test(samplers, orthogonal_grid) { check_stratified("orthogonal", "", 49, 7, 7, 1, 0); }
Test(samplers, orthogonal_strength_3_grid)
{
    check_stratified("orthogonal", "<integer name=\"strength\" value=\"3\"/>", 27, 3, 3, 3, 0);
}
Test(samplers, ldsampler_net) { check_stratified("ldsampler", "", 64, 0, 0, 0, 6); }
Test(samplers, zsobol_net) { check_stratified("zsobol", "", 64, 0, 0, 0, 6); }
Test(samplers, zsobol_net_odd_power) { check_stratified("zsobol", "", 32, 0, 0, 0, 5); }

/* The 1D projections of multijitter's 2D points are stratified too
 * (n-rooks), and so are those of orthogonal arrays in every pair of the
 * p + 1 dimensions their columns serve. */
Test(samplers, multijitter_and_orthogonal_projections)
{
    sampler_t mj = make_sampler("multijitter", "", 20); /* 5 x 4 */
    vec2 p[49];
    double x[49], y[49];
    pixel_points(&mj, 5, 9, SAMPLER_DIM_INTEGRATOR + 1, p);
    for (int i = 0; i < 20; i++)
        x[i] = p[i].x, y[i] = p[i].y;
    cr_expect(strata_1d(x, 20) && strata_1d(y, 20), "multijitter: 1D projections not stratified");
    sampler_t oa = make_sampler("orthogonal", "", 49); /* p = 7: 8 columns */
    for (uint32_t a = 0; a < 8; a++)
        for (uint32_t b = a + 1; b < 8; b++) {
            double xa[49], xb[49];
            pixel_numbers(&oa, 2, 3, 40 + a, xa);
            pixel_numbers(&oa, 2, 3, 40 + b, xb);
            for (int i = 0; i < 49; i++)
                p[i] = v2(xa[i], xb[i]);
            cr_expect(grid_stratified(p, 49, 7, 7, 1), "orthogonal: dimensions %u and %u not 7x7", 40 + a, 40 + b);
        }
}

/* Independent points: the mean squared L2 star discrepancy of uniform
 * random points is (1/4 - 1/9) / n; the stratifying samplers' is below. */
Test(samplers, independent_discrepancy_is_random_others_lower)
{
    const int pixels = 3000;
    vec2 p[64];
    for (int t = 0; t < 6; t++) {
        sampler_t s = make_sampler(all_samplers[t], "", 16);
        int n = (int)s.sample_count; /* orthogonal: 25 */
        double mean = 0.0;
        for (uint32_t i = 0; i < (uint32_t)pixels; i++) {
            pixel_points(&s, i % 64, i / 64, SAMPLER_DIM_INTEGRATOR + 4, p);
            mean += l2_star_discrepancy2(p, n) / pixels;
        }
        double random = (0.25 - 1.0 / 9.0) / n;
        /* T^2 of n random points has a standard deviation of about its mean. */
        if (t == 0)
            cr_expect_lt(fabs(mean - random), 4.0 * random / sqrt(pixels), "independent: %g, expected %g", mean,
                         random);
        else
            cr_expect_lt(mean, 0.5 * random, "%s: mean T^2 %g, random points %g", all_samplers[t], mean, random);
    }
}

/* The numbers of (seed, pixel, sample, dimension) do not depend on what
 * was drawn before or elsewhere, the pixels' patterns differ, and so do
 * seeds. */
Test(samplers, numbers_are_a_function_of_seed_pixel_sample_dimension)
{
    for (int t = 1; t < 6; t++) {
        sampler_t s = make_sampler(all_samplers[t], "", 16), s2 = s;
        s2.seed = 99;
        sampler_stream a, b, c, e;
        sampler_start(&s, &a, 17, 4, 5);
        sampler_next_2d(&a);
        sampler_next_1d(&a);
        sampler_seek(&a, 9);
        vec2 va = sampler_next_2d(&a);
        sampler_start(&s, &c, 18, 4, 5); /* a neighbour in between */
        sampler_seek(&c, 9);
        vec2 vc = sampler_next_2d(&c);
        sampler_start(&s, &b, 17, 4, 5);
        sampler_seek(&b, 9);
        vec2 vb = sampler_next_2d(&b);
        cr_expect(va.x == vb.x && va.y == vb.y, "%s: the same sample draws differently", all_samplers[t]);
        cr_expect(va.x != vc.x || va.y != vc.y, "%s: neighbouring pixels draw the same", all_samplers[t]);
        sampler_start(&s2, &e, 17, 4, 5);
        sampler_seek(&e, 9);
        vec2 ve = sampler_next_2d(&e);
        cr_expect(va.x != ve.x || va.y != ve.y, "%s: seeds 0 and 99 draw the same", all_samplers[t]);
    }
}

/* Different dimensions of one pixel are not correlated: over many pixels,
 * the correlation of dimension pairs the integrator treats as independent
 * (a light pick and a BSDF lobe of one vertex) stays near 0. */
Test(samplers, dimensions_are_not_correlated)
{
    for (int t = 1; t < 6; t++) {
        sampler_t s = make_sampler(all_samplers[t], "", 16);
        double sxy = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0;
        int n = 0;
        double a[64], b[64];
        for (uint32_t i = 0; i < 1024; i++) {
            pixel_numbers(&s, i % 32, i / 32, SAMPLER_DIM_INTEGRATOR, a);
            pixel_numbers(&s, i % 32, i / 32, SAMPLER_DIM_INTEGRATOR + 3, b);
            for (int k = 0; k < s.sample_count; k++, n++)
                sx += a[k], sy += b[k], sxy += a[k] * b[k], sxx += a[k] * a[k], syy += b[k] * b[k];
        }
        double cov = sxy / n - sx / n * sy / n, r = cov / sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
        /* 16384 (orthogonal: 25600) pairs: sd of r under 0.008. */
        cr_expect_lt(fabs(r), 0.04, "%s: correlation %g", all_samplers[t], r);
    }
}

/* Every method is unbiased: each coordinate of every paired dimension,
 * 1D or 2D, averages 1/2 over many pixels (a randomised net's points are
 * uniform one by one; an unshifted net's sit on the lower corners of its
 * cells, 15/32 on average for 16). 1024 pixels of 16 samples: the sd of a
 * mean of independent numbers is 0.0023, stratified ones' is less. */
Test(samplers, every_coordinate_averages_one_half)
{
    for (int t = 0; t < 6; t++) {
        sampler_t s = make_sampler(all_samplers[t], "", 16);
        for (int d = 0; d < NPAIRS; d++) {
            double sx = 0.0, sy = 0.0, s1 = 0.0;
            int n = 0;
            vec2 pts[64];
            double x[64];
            for (uint32_t i = 0; i < 1024; i++) {
                pixel_points(&s, i % 32, i / 32, pair_dims[d], pts);
                pixel_numbers(&s, i % 32, i / 32, pair_dims[d] + 2, x);
                for (int k = 0; k < s.sample_count; k++, n++)
                    sx += pts[k].x, sy += pts[k].y, s1 += x[k];
            }
            double tol = 5.0 * sqrt(1.0 / 12.0 / n);
            cr_expect_lt(fabs(sx / n - 0.5), tol, "%s dim %u: x averages %g", all_samplers[t], pair_dims[d], sx / n);
            cr_expect_lt(fabs(sy / n - 0.5), tol, "%s dim %u: y averages %g", all_samplers[t], pair_dims[d], sy / n);
            cr_expect_lt(fabs(s1 / n - 0.5), tol, "%s dim %u: 1D averages %g", all_samplers[t], pair_dims[d] + 2,
                         s1 / n);
        }
    }
}

Test(sequences, permutations_are_bijections)
{
    for (uint32_t n = 1; n <= 130; n++)
        for (uint32_t seed = 0; seed < 40; seed++) {
            uint8_t seen[130] = {0};
            for (uint32_t i = 0; i < n; i++) {
                uint32_t j = seq_permute(i, n, seed * 0x9e3779b9u);
                cr_assert_lt(j, n);
                cr_assert_eq(seen[j], 0, "n %u seed %u: %u hit twice", n, seed, j);
                seen[j] = 1;
            }
        }
    /* Different seeds give different permutations of 16. */
    int differ = 0;
    for (uint32_t i = 0; i < 16; i++)
        differ += seq_permute(i, 16, 1) != seq_permute(i, 16, 2);
    cr_expect_gt(differ, 4);
}

Test(sequences, sobol_second_dimension_matches_the_direction_numbers)
{
    uint32_t v[32];
    v[0] = 1u << 31;
    for (int k = 1; k < 32; k++)
        v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    uint32_t i = 0x9e3779b9u;
    for (int trial = 0; trial < 1000; trial++, i = i * 1664525u + 1013904223u) {
        uint32_t r = 0;
        for (int k = 0; k < 32; k++)
            if (i & (1u << k))
                r ^= v[k];
        cr_assert_eq(seq_sobol1(i), r);
    }
    cr_expect_eq(seq_sobol0(1), 1u << 31);
    cr_expect_eq(seq_sobol1(3), (1u << 31) ^ (3u << 30));
}

/* seq_reverse_bits mirrors the 32 bits, checked bit by bit. */
Test(sequences, bit_reversal_mirrors_every_bit)
{
    uint32_t v = 0x9e3779b9u;
    for (int trial = 0; trial < 1000; trial++, v = v * 1664525u + 1013904223u) {
        uint32_t r = seq_reverse_bits(v);
        for (int k = 0; k < 32; k++)
            cr_assert_eq((r >> k) & 1u, (v >> (31 - k)) & 1u, "%08x bit %d", v, k);
    }
}

/* The first 2^m Sobol points form a (0,m,2)-net, and Owen scrambling
 * keeps it one, scrambling each coordinate differently per seed. */
Test(sequences, owen_scrambled_sobol_stays_a_net)
{
    enum { M = 8, N = 1 << M };
    vec2 p[N];
    for (uint32_t seed = 0; seed < 20; seed++) {
        for (uint32_t i = 0; i < N; i++)
            p[i] = v2(seq_unit(seq_owen_scramble(seq_sobol0(i), seed * 77u + 1u)),
                      seq_unit(seq_owen_scramble(seq_sobol1(i), seed * 77u + 2u)));
        cr_assert(is_net(p, M), "seed %u", seed);
        cr_expect(seed == 0 || seq_owen_scramble(seq_sobol0(5), 1u) != seq_owen_scramble(seq_sobol0(5), seed * 77u + 1u));
    }
}
