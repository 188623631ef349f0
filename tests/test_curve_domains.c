/* Curvature domains: knots kept, every domain within tolerance of its chord,
 * no needless split, denser where the curve bends harder. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "celadon/curve_domains.h"
#include "test_curve_shapes.h"

/* Brute-force sagitta of the curve on [a, b] about its chord. */
static double sagitta_ref(const bspline_t *c, double a, double b)
{
    vec2 p = bspline_eval(c, a), q = bspline_eval(c, b), d = v2_sub(q, p);
    double worst = 0;
    for (int i = 1; i < 400; i++) {
        vec2 x = v2_sub(bspline_eval(c, a + (b - a) * i / 400.0), p);
        double t = fmin(1, fmax(0, v2_dot(x, d) / v2_dot(d, d)));
        worst = fmax(worst, v2_len(v2_sub(x, v2_scale(d, t))));
    }
    return worst;
}

/* Brute-force departure (radians) of the tangent angle on [a, b] from its
 * linear interpolation in arc length (exact arc length by 2000 chords). */
static double normal_departure_ref(const bspline_t *c, double a, double b)
{
    enum { N = 2000 };
    static double ang[N + 1], s[N + 1];
    vec2 d0[2], d[2];
    bspline_eval_derivs(c, a, 1, d0);
    vec2 prev = d0[0];
    for (int i = 0; i <= N; i++) {
        bspline_eval_derivs(c, a + (b - a) * i / N, 1, d);
        ang[i] = atan2(d0[1].x * d[1].y - d0[1].y * d[1].x, v2_dot(d0[1], d[1]));
        s[i] = i ? s[i - 1] + v2_len(v2_sub(d[0], prev)) : 0;
        prev = d[0];
    }
    double worst = 0;
    for (int i = 0; i <= N; i++)
        worst = fmax(worst, fabs(ang[i] - ang[N] * s[i] / s[N]));
    return worst;
}

/* Mean chord length of the domains whose chord midpoint has x in (x0, x1);
 * asserts there is one. */
static double mean_domain_length(const bspline_t *c, const double *u, int n, double x0, double x1)
{
    double sum = 0;
    int cnt = 0;
    for (int i = 0; i + 1 < n; i++) {
        vec2 a = bspline_eval(c, u[i]), b = bspline_eval(c, u[i + 1]);
        double mid = 0.5 * (a.x + b.x);
        if (mid > x0 && mid < x1)
            sum += v2_len(v2_sub(b, a)), cnt++;
    }
    cr_assert_gt(cnt, 0, "a domain in x (%g, %g)", x0, x1);
    return sum / cnt;
}

/* A single cubic span: the parabola y = x^2 / 200 on [0, 200] (a degree-
 * elevated quadratic Bezier), curvature 1/100 at x = 0 down to ~1/1118. */
static bspline_t parabola(void)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 4), 0);
    const vec2 P[] = {{0, 0}, {200.0 / 3, 0}, {400.0 / 3, 200.0 / 3}, {200, 200}};
    for (int i = 0; i < 4; i++) {
        c.knots[i] = 0;
        c.knots[i + 4] = 1;
        c.ctrl[i] = P[i];
    }
    return c;
}

Test(curve_domains, knots_kept_and_every_domain_within_tolerance)
{
    bspline_t c = test_vase_curve();
    const double tol = 0.05;
    double *u;
    int n;
    cr_assert_eq(curve_domains_by_curvature(&c, tol, &u, &n), 0);
    cr_assert_eq(u[0], 0.0);
    cr_assert_eq(u[n - 1], 1.0);
    for (int i = 1; i < n; i++)
        cr_assert_lt(u[i - 1], u[i]);
    for (int k = 4; k < 8; k++) { /* interior knots 0.1, 0.35, 0.35, 0.7 */
        int found = 0;
        for (int i = 0; i < n; i++)
            found |= u[i] == c.knots[k];
        cr_assert(found, "knot %g is a boundary", c.knots[k]);
    }
    /* Within tolerance, and minimal: the aligned parent interval each domain
     * was bisected from (inside its knot span) is out of tolerance. */
    const double spans[] = {0, 0.1, 0.35, 0.7, 1};
    for (int i = 0; i + 1 < n; i++) {
        double a = u[i], b = u[i + 1], w = b - a;
        cr_assert_leq(sagitta_ref(&c, a, b), 1.05 * tol, "domain [%g, %g]", a, b);
        int s = 0;
        while (spans[s + 1] < b)
            s++;
        double k0 = spans[s], k1 = spans[s + 1];
        if (w < k1 - k0 - 1e-12) {
            double pa = k0 + floor((a - k0) / (2 * w) + 1e-9) * 2 * w;
            cr_assert_gt(sagitta_ref(&c, pa, pa + 2 * w), 0.95 * tol, "[%g, %g] need not be split", pa, pa + 2 * w);
        }
    }
    free(u);
    bspline_free(&c);
}

Test(curve_domains, denser_where_the_curve_bends_harder)
{
    bspline_t c = parabola();
    double *u;
    int n;
    cr_assert_eq(curve_domains_by_curvature(&c, 0.01, &u, &n), 0);
    cr_assert_gt(n, 10);
    /* Domain chord lengths grow as the curvature falls along the parabola,
     * roughly as 1/sqrt(kappa): compare the first and last quarter of x. */
    double ratio = mean_domain_length(&c, u, n, 150, INFINITY) / mean_domain_length(&c, u, n, -INFINITY, 50);
    cr_assert_gt(ratio, 2.0, "mean domain length ratio %g", ratio);
    free(u);
    bspline_free(&c);

    /* A straight line (travelled at uneven speed) needs no split at all. */
    cr_assert_eq(bspline_init(&c, 3, 4), 0);
    const double y[] = {0, 10, 150, 160};
    for (int i = 0; i < 4; i++) {
        c.knots[i] = 0;
        c.knots[i + 4] = 1;
        c.ctrl[i] = v2(10 + 0.5 * y[i], y[i]);
    }
    cr_assert_eq(curve_domains_by_curvature(&c, 0.01, &u, &n), 0);
    cr_assert_eq(n, 2);
    free(u);
    bspline_free(&c);
}

Test(curve_domains, curvature_variation_within_tolerance)
{
    bspline_t c = test_vase_curve();
    const double tol_deg = 0.25;
    double *u, *u_chord;
    int n, n_chord;
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 0.25, tol_deg, &u, &n), 0);
    cr_assert_eq(curve_domains_by_curvature(&c, 0.25, &u_chord, &n_chord), 0);
    cr_assert_gt(n, n_chord, "the normal criterion adds domains (%d vs %d)", n, n_chord);
    for (int i = 0; i + 1 < n; i++) {
        cr_assert_leq(sagitta_ref(&c, u[i], u[i + 1]), 1.05 * 0.25);
        double dep = normal_departure_ref(&c, u[i], u[i + 1]) * 180 / M_PI;
        cr_assert_leq(dep, 1.1 * tol_deg, "domain [%g, %g]: normal departs %g deg", u[i], u[i + 1], dep);
    }
    /* Every chord-only boundary stays a boundary (bisection only refines). */
    for (int k = 0, i = 0; k < n_chord; k++) {
        while (i < n && u[i] < u_chord[k])
            i++;
        cr_assert(i < n && u[i] == u_chord[k], "boundary %g kept", u_chord[k]);
    }
    free(u);
    free(u_chord);
    bspline_free(&c);
}

Test(curve_domains, denser_where_the_curvature_changes_faster)
{
    /* With the chord criterion out of play, the parabola's domains follow
     * |dk/ds|: about 7.7e-5 /px^2 near x = 50, 5e-6 near x = 200, so domain
     * lengths there differ by about sqrt(15). */
    bspline_t c = parabola();
    double *u;
    int n;
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 1e9, INFINITY, &u, &n), 0);
    cr_assert_eq(n, 2, "no split without a finite tolerance");
    free(u);
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 1e9, 0.05, &u, &n), 0);
    double ratio = mean_domain_length(&c, u, n, 150, INFINITY) / mean_domain_length(&c, u, n, 30, 70);
    cr_assert_gt(ratio, 2.0, "mean domain length ratio %g", ratio);
    free(u);
    /* A circular arc has constant curvature: its cubic approximation (radius
     * 100, a quarter turn) needs no split at a tolerance its 0.03 %
     * curvature ripple cannot reach. */
    const double k = 4.0 / 3.0 * tan(M_PI / 8) * 100;
    const vec2 P[] = {{100, 0}, {100, k}, {k, 100}, {0, 100}};
    for (int i = 0; i < 4; i++)
        c.ctrl[i] = P[i];
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 1e9, 1.0, &u, &n), 0);
    cr_assert_eq(n, 2, "a circular arc is one domain, got %d", n - 1);
    free(u);
    bspline_free(&c);
}

Test(curve_domains, finer_tolerance_more_domains)
{
    bspline_t c = test_vase_curve();
    int prev = 0;
    for (double tol = 1.0; tol > 0.002; tol /= 4) {
        double *u;
        int n;
        cr_assert_eq(curve_domains_by_curvature(&c, tol, &u, &n), 0);
        cr_assert_gt(n, prev);
        prev = n;
        free(u);
    }
    bspline_free(&c);
}

Test(curve_domains, bad_input)
{
    bspline_t c = test_vase_curve();
    double *u = (double *)&c;
    int n = 7;
    cr_assert_eq(curve_domains_by_curvature(&c, 0.0, &u, &n), -1);
    cr_assert_null(u);
    cr_assert_eq(n, 0);
    cr_assert_eq(curve_domains_by_curvature(&c, NAN, &u, &n), -1);
    cr_assert_eq(curve_domains_by_curvature(&c, -1, &u, &n), -1);
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 0.1, 0.0, &u, &n), -1);
    cr_assert_eq(curve_domains_by_curvature_variation(&c, 0.1, NAN, &u, &n), -1);
    c.knots[0] = 0.5; /* not clamped */
    cr_assert_eq(curve_domains_by_curvature(&c, 0.1, &u, &n), -1);
    bspline_free(&c);
}
