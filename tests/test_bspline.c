/* B-spline evaluation against independent truths: the Bézier decomposition
 * evaluated by de Casteljau, finite differences, partition of unity. */
#include <criterion/criterion.h>
#include <stdlib.h>

#include "celadon/bspline.h"

/* A clamped cubic with uneven interior knots, one of them double. */
static bspline_t make_curve(void)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 8), 0);
    const double U[] = {0, 0, 0, 0, 0.1, 0.35, 0.35, 0.7, 1, 1, 1, 1};
    const vec2 P[] = {{30, 0}, {45, 10}, {60, 40}, {20, 70}, {15, 90}, {25, 110}, {35, 130}, {33, 140}};
    for (int i = 0; i < 12; i++)
        c.knots[i] = U[i];
    for (int i = 0; i < 8; i++)
        c.ctrl[i] = P[i];
    cr_assert_null(bspline_validate(&c));
    return c;
}

Test(bspline, interpolates_clamped_ends)
{
    bspline_t c = make_curve();
    vec2 a = bspline_eval(&c, 0.0), b = bspline_eval(&c, 1.0);
    cr_assert_float_eq(a.x, 30, 1e-12);
    cr_assert_float_eq(a.y, 0, 1e-12);
    cr_assert_float_eq(b.x, 33, 1e-12);
    cr_assert_float_eq(b.y, 140, 1e-12);
    bspline_free(&c);
}

Test(bspline, bezier_pieces_match_de_boor)
{
    bspline_t c = make_curve();
    bezier3_t *b;
    int n = bspline_to_bezier(&c, &b);
    cr_assert_eq(n, 4, "distinct spans: 4, got %d", n);
    for (int j = 0; j < n; j++) {
        cr_assert_lt(b[j].u0, b[j].u1);
        if (j > 0)
            cr_assert_eq(b[j].u0, b[j - 1].u1);
        for (int k = 0; k <= 20; k++) {
            double s = k / 20.0, u = b[j].u0 + s * (b[j].u1 - b[j].u0);
            vec2 p = bezier3_eval(&b[j], s), q = bspline_eval(&c, u);
            cr_assert_float_eq(p.x, q.x, 1e-10, "piece %d s=%g", j, s);
            cr_assert_float_eq(p.y, q.y, 1e-10, "piece %d s=%g", j, s);
            vec2 d[2];
            bspline_eval_derivs(&c, u, 1, d);
            vec2 db = v2_scale(bezier3_deriv(&b[j], s), 1.0 / (b[j].u1 - b[j].u0));
            cr_assert_float_eq(d[1].x, db.x, 1e-8 * (1 + fabs(db.x)));
            cr_assert_float_eq(d[1].y, db.y, 1e-8 * (1 + fabs(db.y)));
        }
    }
    free(b);
    bspline_free(&c);
}

Test(bspline, derivatives_match_finite_differences)
{
    bspline_t c = make_curve();
    const double h = 1e-6;
    for (double u = 0.02; u < 0.99; u += 0.037) {
        vec2 d[3], dp[3], dm[3];
        bspline_eval_derivs(&c, u, 2, d);
        bspline_eval_derivs(&c, u + h, 2, dp);
        bspline_eval_derivs(&c, u - h, 2, dm);
        cr_assert_float_eq(d[1].x, (dp[0].x - dm[0].x) / (2 * h), 1e-4 * (1 + fabs(d[1].x)));
        cr_assert_float_eq(d[1].y, (dp[0].y - dm[0].y) / (2 * h), 1e-4 * (1 + fabs(d[1].y)));
        /* The second derivative jumps at the double knot 0.35; skip its neighbourhood. */
        if (fabs(u - 0.35) > 2 * h && fabs(u - 0.1) > 2 * h && fabs(u - 0.7) > 2 * h) {
            cr_assert_float_eq(d[2].x, (dp[1].x - dm[1].x) / (2 * h), 1e-3 * (1 + fabs(d[2].x)));
            cr_assert_float_eq(d[2].y, (dp[1].y - dm[1].y) / (2 * h), 1e-3 * (1 + fabs(d[2].y)));
        }
    }
    bspline_free(&c);
}

Test(bspline, partition_of_unity)
{
    bspline_t c = make_curve();
    for (int i = 0; i < c.n_ctrl; i++)
        c.ctrl[i] = v2(7.5, -2.0);
    for (double u = 0; u <= 1.0; u += 0.01) {
        vec2 p = bspline_eval(&c, u);
        cr_assert_float_eq(p.x, 7.5, 1e-12);
        cr_assert_float_eq(p.y, -2.0, 1e-12);
    }
    bspline_free(&c);
}

Test(bspline, validate_rejects_bad_knots)
{
    bspline_t c = make_curve();
    c.knots[5] = 0.05; /* decreasing */
    cr_assert_not_null(bspline_validate(&c));
    c.knots[5] = 0.35;
    c.knots[0] = -0.5; /* not clamped */
    cr_assert_not_null(bspline_validate(&c));
    c.knots[0] = 0.0;
    cr_assert_null(bspline_validate(&c));
    double first_interior = c.knots[c.degree + 1];
    c.knots[c.degree + 1] = c.knots[0]; /* the start repeated p + 2 times */
    cr_assert_str_eq(bspline_validate(&c), "end knot multiplicity exceeds the degree + 1");
    c.knots[c.degree + 1] = first_interior;
    int nk = bspline_n_knots(&c);
    c.knots[nk - 2 - c.degree] = c.knots[nk - 1]; /* the end repeated p + 2 times */
    cr_assert_str_eq(bspline_validate(&c), "end knot multiplicity exceeds the degree + 1");
    bspline_free(&c);
}
