/* The Dierckx-style fit: known curves with noise, the nested knot sequence,
 * interpolation, an independent dense least-squares solution, the profile
 * tolerance, degenerate input. */
#include <criterion/criterion.h>
#include <gsl/gsl_multifit.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "celadon/curve_distance.h"
#include "celadon/curve_fit.h"
#include "test_curve_shapes.h"

/* Deterministic standard normal deviates (xorshift64 + Box-Muller). */
static double gauss(uint64_t *s)
{
    double u[2];
    for (int k = 0; k < 2; k++) {
        *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
        u[k] = ((*s >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2 * log(u[0])) * cos(2 * M_PI * u[1]);
}

/* Chord-length parameters, as the fit documents them. */
static void chord_params(const vec2 *p, int n, double *u)
{
    u[0] = 0;
    for (int i = 1; i < n; i++)
        u[i] = u[i - 1] + v2_len(v2_sub(p[i], p[i - 1]));
    for (int i = 1; i < n; i++)
        u[i] /= u[n - 1];
}

static double ssr_at_chord_params(const bspline_t *c, const vec2 *p, int n)
{
    double *u = malloc((size_t)n * sizeof *u), s = 0;
    chord_params(p, n, u);
    for (int i = 0; i < n; i++) {
        vec2 d = v2_sub(bspline_eval(c, u[i]), p[i]);
        s += v2_dot(d, d);
    }
    free(u);
    return s;
}

static vec2 *noisy_vase(int n, double sigma, uint64_t seed)
{
    bspline_t c = test_vase_curve();
    vec2 *p = malloc((size_t)n * sizeof *p);
    for (int i = 0; i < n; i++) {
        p[i] = bspline_eval(&c, (double)i / (n - 1));
        if (i > 0 && i < n - 1)
            p[i] = v2_add(p[i], v2(sigma * gauss(&seed), sigma * gauss(&seed)));
    }
    bspline_free(&c);
    return p;
}

Test(curve_fit, noisy_spline_is_recovered)
{
    enum { N = 1000 };
    const double sigma = 0.3;
    vec2 *p = noisy_vase(N, sigma, 42);
    bspline_t fit;
    bspline_fit_info info;
    double s = 2.0 * N * sigma * sigma; /* the expected sum of squared noise */
    cr_assert_eq(bspline_fit_smoothing(p, N, s, &fit, &info), 0);
    cr_assert_null(bspline_validate(&fit));
    cr_assert_leq(info.ssr, s);
    cr_assert_eq(info.n_ctrl, fit.n_ctrl);
    cr_assert_float_eq(info.ssr, ssr_at_chord_params(&fit, p, N), 1e-9 * s);
    /* The ends are interpolated exactly. */
    vec2 a = bspline_eval(&fit, 0), b = bspline_eval(&fit, 1);
    cr_assert(a.x == p[0].x && a.y == p[0].y && b.x == p[N - 1].x && b.y == p[N - 1].y);
    /* Against the noise-free curve the fit is much closer than the noise. */
    bspline_t truth = test_vase_curve();
    vec2 *clean = malloc(2001 * sizeof *clean);
    for (int i = 0; i <= 2000; i++)
        clean[i] = bspline_eval(&truth, i / 2000.0);
    double c2p, p2c;
    curve_polyline_hausdorff(&fit, clean, 2001, &c2p, &p2c);
    cr_assert_lt(c2p, 0.3, "fit to truth %g px", c2p);
    cr_assert_lt(p2c, 0.3, "truth to fit %g px", p2c);
    cr_assert_lt(fit.n_ctrl, 40);
    free(clean);
    bspline_free(&truth);
    bspline_free(&fit);
    free(p);
}

Test(curve_fit, knot_insertion_reduces_the_residual_monotonically)
{
    enum { N = 600 };
    vec2 *p = noisy_vase(N, 0.2, 7);
    bspline_t poly;
    bspline_fit_info info;
    cr_assert_eq(bspline_fit_smoothing(p, N, 1e30, &poly, &info), 0);
    cr_assert_eq(info.n_ctrl, 4, "s huge: the cubic polynomial");
    cr_assert_eq(info.iterations, 1);
    double prev_ssr = info.ssr;
    int prev_n = 4, grew = 0;
    for (double s = info.ssr * 0.7; s > 30.0; s *= 0.7) {
        bspline_t f;
        bspline_fit_info fi;
        cr_assert_eq(bspline_fit_smoothing(p, N, s, &f, &fi), 0);
        cr_assert_leq(fi.ssr, s);
        cr_assert_leq(fi.ssr, prev_ssr * (1 + 1e-9), "s=%g: ssr %g after %g", s, fi.ssr, prev_ssr);
        cr_assert_geq(fi.n_ctrl, prev_n);
        cr_assert_eq(fi.iterations, fi.n_ctrl - 3, "one knot per iteration");
        cr_assert_float_eq(fi.ssr, ssr_at_chord_params(&f, p, N), 1e-9 * (1 + fi.ssr));
        grew += fi.n_ctrl > prev_n;
        prev_ssr = fi.ssr;
        prev_n = fi.n_ctrl;
        bspline_free(&f);
    }
    cr_assert_gt(grew, 5);
    bspline_free(&poly);
    free(p);
}

Test(curve_fit, zero_smoothing_interpolates)
{
    enum { N = 12 };
    vec2 p[N];
    for (int i = 0; i < N; i++) /* an uneven arc */
        p[i] = v2(50 * cos(0.2 * i + 0.01 * i * i), 50 * sin(0.2 * i + 0.01 * i * i));
    bspline_t f;
    bspline_fit_info info;
    cr_assert_eq(bspline_fit_smoothing(p, N, 0.0, &f, &info), 0);
    cr_assert_eq(f.n_ctrl, N);
    cr_assert_lt(info.ssr, 1e-12);
    double u[N];
    chord_params(p, N, u);
    for (int i = 0; i < N; i++) {
        vec2 q = bspline_eval(&f, u[i]);
        cr_assert_float_eq(q.x, p[i].x, 1e-6);
        cr_assert_float_eq(q.y, p[i].y, 1e-6);
    }
    bspline_free(&f);
}

Test(curve_fit, polynomial_matches_dense_least_squares)
{
    /* With no interior knots the fit is the cubic Bezier through the end
     * points that minimises the residual: solved here independently with
     * GSL's dense SVD least squares on the Bernstein basis. */
    enum { N = 200 };
    vec2 *p = noisy_vase(N, 0.5, 3);
    double u[N];
    chord_params(p, N, u);
    gsl_matrix *X = gsl_matrix_alloc(N, 2), *cov = gsl_matrix_alloc(2, 2);
    gsl_vector *yx = gsl_vector_alloc(N), *yy = gsl_vector_alloc(N), *cx = gsl_vector_alloc(2),
               *cy = gsl_vector_alloc(2);
    for (int i = 0; i < N; i++) {
        double t = u[i], s = 1 - t, b0 = s * s * s, b1 = 3 * t * s * s, b2 = 3 * t * t * s, b3 = t * t * t;
        gsl_matrix_set(X, i, 0, b1);
        gsl_matrix_set(X, i, 1, b2);
        gsl_vector_set(yx, i, p[i].x - b0 * p[0].x - b3 * p[N - 1].x);
        gsl_vector_set(yy, i, p[i].y - b0 * p[0].y - b3 * p[N - 1].y);
    }
    gsl_multifit_linear_workspace *w = gsl_multifit_linear_alloc(N, 2);
    double chi;
    gsl_multifit_linear(X, yx, cx, cov, &chi, w);
    gsl_multifit_linear(X, yy, cy, cov, &chi, w);
    bspline_t f;
    cr_assert_eq(bspline_fit_smoothing(p, N, 1e30, &f, NULL), 0);
    cr_assert_eq(f.n_ctrl, 4);
    for (int k = 0; k < 2; k++) {
        cr_assert_float_eq(f.ctrl[k + 1].x, gsl_vector_get(cx, k), 1e-6);
        cr_assert_float_eq(f.ctrl[k + 1].y, gsl_vector_get(cy, k), 1e-6);
    }
    gsl_multifit_linear_free(w);
    gsl_matrix_free(X);
    gsl_matrix_free(cov);
    gsl_vector_free(yx);
    gsl_vector_free(yy);
    gsl_vector_free(cx);
    gsl_vector_free(cy);
    bspline_free(&f);
    free(p);
}

/* A smooth analytic vase outline traced as a pixel contour: points every
 * 0.6 px of height, both coordinates rounded to whole pixels. */
static vec2 *pixel_vase(int n)
{
    vec2 *p = malloc((size_t)n * sizeof *p);
    for (int i = 0; i < n; i++) {
        double h = 600.0 * i / (n - 1);
        double r = 90 + 35 * sin(h / 95.0) - 20 * cos(h / 47.0) + 0.00004 * (h - 300) * (h - 300);
        p[i] = v2(round(r), round(h));
    }
    return p;
}

Test(curve_fit, profile_fit_meets_the_tolerance_with_few_control_points)
{
    enum { N = 1000 };
    vec2 *p = pixel_vase(N);
    bspline_t f;
    bspline_fit_info info;
    cr_assert_eq(bspline_fit_profile(p, N, 1.0, &f, &info), 0);
    cr_assert_null(bspline_validate(&f));
    cr_assert_leq(f.n_ctrl, 20, "control points: %d", f.n_ctrl);
    cr_assert_float_eq(info.s, info.ssr, 0);
    double c2p, p2c;
    curve_polyline_hausdorff(&f, p, N, &c2p, &p2c);
    cr_assert_leq(p2c, 1.0 + 1e-6, "polyline to curve %g px", p2c);
    cr_assert_lt(c2p, 1.0);
    /* Fewest control points: every spline earlier in the knot sequence
     * (reached through bspline_fit_smoothing with a larger s) misses the
     * tolerance somewhere. */
    int earlier = 0, last_n = 0;
    for (double s = 1e6;; s *= 0.9) {
        bspline_t g;
        bspline_fit_info gi;
        cr_assert_eq(bspline_fit_smoothing(p, N, s, &g, &gi), 0);
        int done = gi.n_ctrl >= f.n_ctrl;
        if (!done && gi.n_ctrl != last_n) {
            last_n = gi.n_ctrl;
            double g_c2p, g_p2c;
            curve_polyline_hausdorff(&g, p, N, &g_c2p, &g_p2c);
            cr_assert_gt(g_p2c, 1.0, "%d control points already meet the tolerance", gi.n_ctrl);
            earlier++;
        }
        bspline_free(&g);
        if (done)
            break;
    }
    cr_assert_gt(earlier, 3);
    bspline_free(&f);
    free(p);
}

Test(curve_fit, degenerate_input_is_refused)
{
    vec2 same[10], nan_pts[10], ok[10];
    for (int i = 0; i < 10; i++) {
        same[i] = v2(3, 4);
        ok[i] = nan_pts[i] = v2(i, i * i);
    }
    nan_pts[4].y = NAN;
    bspline_t f;
    cr_assert_eq(bspline_fit_smoothing(ok, 3, 1.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_smoothing(NULL, 10, 1.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_smoothing(same, 10, 1.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_smoothing(nan_pts, 10, 1.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_smoothing(ok, 10, -1.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_smoothing(ok, 10, NAN, &f, NULL), -1);
    cr_assert_eq(bspline_fit_profile(ok, 10, 0.0, &f, NULL), -1);
    cr_assert_eq(bspline_fit_profile(ok, 10, INFINITY, &f, NULL), -1);
    cr_assert_eq(bspline_fit_profile(same, 10, 1.0, &f, NULL), -1);
    nan_pts[4].y = INFINITY;
    cr_assert_eq(bspline_fit_profile(nan_pts, 10, 1.0, &f, NULL), -1);
    cr_assert_null(f.ctrl);
    /* Only three distinct points after dropping repeats. */
    vec2 three[6] = {{0, 0}, {0, 0}, {1, 1}, {1, 1}, {2, 0}, {2, 0}};
    cr_assert_eq(bspline_fit_smoothing(three, 6, 0.0, &f, NULL), -1);
}

Test(curve_fit, repeated_points_change_nothing)
{
    enum { N = 300 };
    vec2 *p = noisy_vase(N, 0.3, 11), *twice = malloc(2 * N * sizeof *twice);
    for (int i = 0; i < N; i++)
        twice[2 * i] = twice[2 * i + 1] = p[i];
    bspline_t a, b;
    cr_assert_eq(bspline_fit_profile(p, N, 1.0, &a, NULL), 0);
    cr_assert_eq(bspline_fit_profile(twice, 2 * N, 1.0, &b, NULL), 0);
    cr_assert_eq(a.n_ctrl, b.n_ctrl);
    for (int i = 0; i < a.n_ctrl; i++)
        cr_assert(a.ctrl[i].x == b.ctrl[i].x && a.ctrl[i].y == b.ctrl[i].y);
    bspline_free(&a);
    bspline_free(&b);
    free(twice);
    free(p);
}

Test(curve_fit, hostile_input_never_crashes)
{
    /* Small polylines from a palette of awkward values (repeats, huge, tiny,
     * nearly equal); every result is either a refusal or a valid, finite
     * curve. */
    const double palette[] = {0, 1, -1, 1e-300, 1e300, -1e300, 3.5, 1e8, 1e8 + 1e-8, 2e-9, 42, 1e154};
    const int np = sizeof palette / sizeof palette[0];
    uint64_t seed = 99;
    for (int trial = 0; trial < 300; trial++) {
        vec2 p[14];
        seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
        int n = (int)(seed % 15);
        for (int i = 0; i < n; i++) {
            seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
            p[i] = v2(palette[seed % np], palette[(seed >> 8) % np]);
        }
        bspline_t f;
        bspline_fit_info info;
        int rc = trial % 2 ? bspline_fit_profile(p, n, 1.0, &f, &info) : bspline_fit_smoothing(p, n, 0.5, &f, &info);
        cr_assert(rc == 0 || rc == -1);
        if (rc != 0) {
            cr_assert_null(f.ctrl);
            continue;
        }
        cr_assert_null(bspline_validate(&f), "trial %d", trial);
        for (int i = 0; i < f.n_ctrl; i++)
            cr_assert(isfinite(f.ctrl[i].x) && isfinite(f.ctrl[i].y));
        bspline_free(&f);
    }
}
