/* Hausdorff distances and foot points against cases computed by hand. */
#include <criterion/criterion.h>
#include <math.h>

#include "celadon/curve_distance.h"
#include "test_curve_shapes.h"

/* The segment (x0,y0)-(x1,y1) as a clamped cubic with evenly spaced control points. */
static bspline_t line_curve(double x0, double y0, double x1, double y1)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 4), 0);
    for (int i = 0; i < 4; i++) {
        c.knots[i] = 0.0;
        c.knots[i + 4] = 1.0;
        c.ctrl[i] = v2(x0 + (x1 - x0) * i / 3.0, y0 + (y1 - y0) * i / 3.0);
    }
    return c;
}

Test(curve_distance, line_against_shifted_polyline)
{
    bspline_t c = line_curve(0, 0, 0, 100);
    const vec2 poly[] = {{0.7, 0}, {0.7, 40}, {0.7, 100}};
    double c2p, p2c;
    curve_polyline_hausdorff(&c, poly, 3, &c2p, &p2c);
    cr_assert_float_eq(c2p, 0.7, 1e-9);
    cr_assert_float_eq(p2c, 0.7, 1e-9);
    bspline_free(&c);
}

Test(curve_distance, shorter_polyline_is_asymmetric)
{
    bspline_t c = line_curve(0, 0, 0, 100);
    const vec2 poly[] = {{0.5, 10}, {0.5, 90}};
    double c2p, p2c;
    curve_polyline_hausdorff(&c, poly, 2, &c2p, &p2c);
    cr_assert_float_eq(p2c, 0.5, 1e-9);
    cr_assert_float_eq(c2p, sqrt(0.25 + 100.0), 1e-9, "curve end (0,0) to (0.5,10): %.12g", c2p);
    bspline_free(&c);
}

Test(curve_distance, zigzag_maxima_lie_between_samples)
{
    /* Zig-zag between x = 0 and x = 1 with period 20: polyline -> curve is 1
     * (the vertices at x = 1); curve -> polyline is the distance from (0, 10)
     * to the segments through (1, 10), i.e. 10 / sqrt(101). */
    bspline_t c = line_curve(0, 0, 0, 100);
    vec2 poly[11];
    for (int i = 0; i <= 10; i++)
        poly[i] = v2(i % 2, 10.0 * i);
    double c2p, p2c;
    curve_polyline_hausdorff(&c, poly, 11, &c2p, &p2c);
    cr_assert_float_eq(p2c, 1.0, 1e-9);
    cr_assert_float_eq(c2p, 10.0 / sqrt(101.0), 1e-7, "got %.12g", c2p);
    bspline_free(&c);
}

static double seg_dist(vec2 q, vec2 a, vec2 b)
{
    vec2 ab = v2_sub(b, a);
    double t = v2_dot(v2_sub(q, a), ab) / v2_dot(ab, ab);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return v2_len(v2_sub(q, v2_add(a, v2_scale(ab, t))));
}

static double dist_to_polyline(vec2 q, const vec2 *p, int n)
{
    double best = INFINITY;
    for (int i = 0; i + 1 < n; i++)
        best = fmin(best, seg_dist(q, p[i], p[i + 1]));
    return best;
}

Test(curve_distance, chords_of_a_curve_match_brute_force)
{
    /* A polyline through 41 curve points: both distances are chord sagittas.
     * Reference: brute force against 4000 dense curve samples. */
    bspline_t c = test_vase_curve();
    enum { N = 41, DENSE = 4001 };
    vec2 poly[N];
    for (int i = 0; i < N; i++)
        poly[i] = bspline_eval(&c, (double)i / (N - 1));
    static vec2 dense[DENSE];
    for (int i = 0; i < DENSE; i++)
        dense[i] = bspline_eval(&c, (double)i / (DENSE - 1));
    double ref_c2p = 0, ref_p2c = 0;
    for (int i = 0; i < DENSE; i++)
        ref_c2p = fmax(ref_c2p, dist_to_polyline(dense[i], poly, N));
    for (int s = 0; s + 1 < N; s++)
        for (int k = 0; k <= 50; k++)
            ref_p2c = fmax(ref_p2c, dist_to_polyline(v2_lerp(poly[s], poly[s + 1], k / 50.0), dense, DENSE));
    double c2p, p2c;
    curve_polyline_hausdorff(&c, poly, N, &c2p, &p2c);
    cr_assert_gt(ref_c2p, 0.05, "the test needs visible sagittas");
    cr_assert_float_eq(c2p, ref_c2p, 1e-4, "%.9g vs brute force %.9g", c2p, ref_c2p);
    cr_assert_float_eq(p2c, ref_p2c, 1e-3, "%.9g vs brute force %.9g", p2c, ref_p2c);
    cr_assert_geq(p2c, ref_p2c - 1e-6, "the polished maximum is at least the sampled one");
    bspline_free(&c);
}

Test(curve_distance, newton_finds_the_foot_point)
{
    bspline_t c = test_vase_curve();
    for (double u = 0.05; u < 1.0; u += 0.1) {
        vec2 d[2];
        bspline_eval_derivs(&c, u, 1, d);
        vec2 nrm = v2_norm(v2(d[1].y, -d[1].x));
        vec2 p = v2_add(d[0], v2_scale(nrm, 0.8)); /* 0.8 px off the curve along its normal */
        double uf, dist = curve_point_distance_near(&c, p, u + 0.02, &uf);
        cr_assert_float_eq(dist, 0.8, 1e-9, "u=%g", u);
        cr_assert_float_eq(uf, u, 1e-7);
    }
    bspline_free(&c);
}

Test(curve_distance, degenerate_input)
{
    bspline_t c = line_curve(0, 0, 0, 100);
    double c2p, p2c;
    /* A single point: both sides measure to it. */
    const vec2 one[] = {{3, 50}};
    curve_polyline_hausdorff(&c, one, 1, &c2p, &p2c);
    cr_assert_float_eq(p2c, 3.0, 1e-9);
    cr_assert_float_eq(c2p, sqrt(9.0 + 2500.0), 1e-9);
    /* Repeated points are a point too. */
    const vec2 same[] = {{3, 50}, {3, 50}, {3, 50}};
    curve_polyline_hausdorff(&c, same, 3, &c2p, &p2c);
    cr_assert_float_eq(p2c, 3.0, 1e-9);
    /* Refusals: NaN out. */
    const vec2 bad[] = {{0, 0}, {NAN, 1}}, huge[] = {{0, 0}, {1e200, 1}};
    curve_polyline_hausdorff(&c, bad, 2, &c2p, &p2c);
    cr_assert(isnan(c2p) && isnan(p2c));
    curve_polyline_hausdorff(&c, huge, 2, &c2p, &p2c);
    cr_assert(isnan(c2p) && isnan(p2c));
    curve_polyline_hausdorff(&c, one, 0, &c2p, &p2c);
    cr_assert(isnan(c2p) && isnan(p2c));
    c.knots[0] = 0.5; /* invalid curve */
    curve_polyline_hausdorff(&c, one, 1, &c2p, &p2c);
    cr_assert(isnan(c2p) && isnan(p2c));
    bspline_free(&c);
}

Test(curve_distance, many_scales_at_once)
{
    /* A polyline with one vertex ten thousand pixels away: the far side is
     * measured exactly and the near part stays fast. */
    bspline_t c = line_curve(0, 0, 0, 100);
    vec2 poly[202];
    for (int i = 0; i <= 200; i++)
        poly[i] = v2(0.5, i * 0.5);
    poly[201] = v2(1e4, 100);
    double c2p, p2c;
    curve_polyline_hausdorff(&c, poly, 202, &c2p, &p2c);
    cr_assert_float_eq(p2c, 1e4, 1e-6);
    cr_assert_float_eq(c2p, 0.5, 1e-9);
    bspline_free(&c);
}
