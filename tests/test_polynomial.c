/* The first root of a cubic on an interval (celadon/polynomial.h) against
 * cubics built from their roots: random simple roots, double roots (a
 * touch), a triple root, degenerate leading coefficients, and roots at or
 * before the `after` bound. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "celadon/polynomial.h"
#include "celadon/rng.h"

/* c[] of s (t - r0)(t - r1)(t - r2). */
static void from_roots(double s, double r0, double r1, double r2, double c[4])
{
    c[3] = s;
    c[2] = -s * (r0 + r1 + r2);
    c[1] = s * (r0 * r1 + r0 * r2 + r1 * r2);
    c[0] = -s * r0 * r1 * r2;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Three random roots in [-1, 2], the interval [0, 1] and a random `after`:
 * the first root above after in [0, 1], to 1e-12, or none. */
Test(polynomial, the_first_root_of_a_cubic_on_an_interval)
{
    rng_t r;
    rng_seed(&r, 3, 0);
    for (int k = 0; k < 20000; k++) {
        double roots[3];
        for (int i = 0; i < 3; i++)
            roots[i] = -1.0 + 3.0 * rng_next_double(&r);
        qsort(roots, 3, sizeof *roots, cmp_double);
        if (roots[1] - roots[0] < 1e-6 || roots[2] - roots[1] < 1e-6)
            continue; /* the double roots are the next test's */
        double c[4], after = rng_next_double(&r) < 0.5 ? -1.0 : 0.5 * rng_next_double(&r);
        from_roots(rng_next_double(&r) < 0.5 ? -2.0 : 0.7, roots[0], roots[1], roots[2], c);
        double want = NAN, got;
        for (int i = 2; i >= 0; i--)
            if (roots[i] >= 0.0 && roots[i] <= 1.0 && roots[i] > after)
                want = roots[i];
        int found = poly_cubic_first_root(c, 0.0, 1.0, after, &got);
        cr_assert_eq(found, !isnan(want), "roots %g %g %g after %g: found %d (%g)", roots[0], roots[1], roots[2],
                     after, found, got);
        if (found)
            cr_assert(fabs(got - want) < 1e-12, "roots %g %g %g: %.17g, not %.17g", roots[0], roots[1], roots[2], got,
                      want);
    }
}

Test(polynomial, touches_degenerate_leading_terms_and_the_after_bound)
{
    double c[4], t;
    /* (t - 0.25)^2 (t - 0.75): a touch at 0.25 (exact zero there), a crossing at 0.75 */
    from_roots(1.0, 0.25, 0.25, 0.75, c);
    cr_assert(poly_cubic_first_root(c, 0.0, 1.0, -1.0, &t));
    cr_expect(fabs(t - 0.25) < 1e-12, "%.17g", t);
    cr_assert(poly_cubic_first_root(c, 0.0, 1.0, 0.25, &t));
    cr_expect(fabs(t - 0.75) < 1e-12, "%.17g", t);
    /* a triple root: one crossing */
    from_roots(1.0, 0.5, 0.5, 0.5, c);
    cr_assert(poly_cubic_first_root(c, 0.0, 1.0, -1.0, &t));
    cr_expect(fabs(t - 0.5) < 1e-5, "%.17g", t); /* cbrt of rounding: a triple root is ill-conditioned */
    /* a quadratic (c3 = 0) and a line */
    double q[4] = {0.06, -0.5, 1.0, 0.0}; /* (t - 0.2)(t - 0.3) */
    cr_assert(poly_cubic_first_root(q, 0.0, 1.0, -1.0, &t));
    cr_expect(fabs(t - 0.2) < 1e-12, "%.17g", t);
    cr_assert(poly_cubic_first_root(q, 0.0, 1.0, 0.2, &t));
    cr_expect(fabs(t - 0.3) < 1e-12, "%.17g", t);
    double line[4] = {-0.3, 1.0, 0.0, 0.0};
    cr_assert(poly_cubic_first_root(line, 0.0, 1.0, -1.0, &t));
    cr_expect(fabs(t - 0.3) < 1e-15, "%.17g", t);
    /* no root in the interval, and a constant */
    from_roots(1.0, -0.5, 1.5, 2.0, c);
    cr_expect(!poly_cubic_first_root(c, 0.0, 1.0, -1.0, &t));
    double flat[4] = {0.4, 0.0, 0.0, 0.0};
    cr_expect(!poly_cubic_first_root(flat, 0.0, 1.0, -1.0, &t));
    /* a root at the interval's start counts unless `after` excludes it */
    from_roots(1.0, 0.0, 2.0, 3.0, c);
    cr_expect(poly_cubic_first_root(c, 0.0, 1.0, -1.0, &t) && t == 0.0);
    cr_expect(!poly_cubic_first_root(c, 0.0, 1.0, 0.0, &t));
}
