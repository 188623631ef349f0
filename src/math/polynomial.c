/* Real roots of quadratics and cubics (celadon/polynomial.h). */
#include <float.h>
#include <math.h>

#include "celadon/polynomial.h"

int poly_quadratic_roots(double a, double b, double c, double *t0, double *t1)
{
    if (a == 0.0)
        return 0;
    double disc = b * b - a * c;
    if (disc < 0.0)
        return 0;
    double q = -(b + copysign(sqrt(disc), b));
    double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
    *t0 = fmin(r0, r1);
    *t1 = fmax(r0, r1);
    return 2;
}

static double cubic(const double c[4], double t) { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }
static double cubic_slope(const double c[4], double t) { return (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1]; }

/* The root of the cubic in [a, b], where fa and fb have opposite signs:
 * Newton steps, replaced by bisection whenever one would leave the bracket,
 * which shrinks at every step. */
static double polish(const double c[4], double a, double b, double fa)
{
    double x = 0.5 * (a + b), tol = 4.0 * DBL_EPSILON * fmax(fabs(a), fabs(b));
    for (int it = 0; it < 200 && b - a > tol; it++) {
        double f = cubic(c, x);
        if (f == 0.0)
            return x;
        if ((f < 0.0) == (fa < 0.0))
            a = x, fa = f;
        else
            b = x;
        double fp = cubic_slope(c, x), next = fp != 0.0 ? x - f / fp : a;
        x = next > a && next < b ? next : 0.5 * (a + b);
    }
    return x;
}

int poly_cubic_first_root(const double c[4], double lo, double hi, double after, double *root)
{
    /* The pieces' ends: lo, the critical points inside (lo, hi), hi. The
     * derivative 3 c3 t^2 + 2 c2 t + c1 is a quadratic in the form above;
     * with c3 = 0 it is linear. */
    double ends[4] = {lo, 0, 0, 0}, r0, r1;
    int n = 1;
    if (poly_quadratic_roots(3.0 * c[3], c[2], c[1], &r0, &r1) == 2) {
        if (r0 > lo && r0 < hi)
            ends[n++] = r0;
        if (r1 > lo && r1 < hi && r1 != r0)
            ends[n++] = r1;
    } else if (c[3] == 0.0 && c[2] != 0.0) {
        double r = -c[1] / (2.0 * c[2]);
        if (r > lo && r < hi)
            ends[n++] = r;
    }
    ends[n++] = hi;
    double fa = cubic(c, ends[0]);
    for (int i = 0; i + 1 < n; i++) {
        double a = ends[i], b = ends[i + 1], fb = cubic(c, b);
        double r = NAN;
        if (fa == 0.0)
            r = a;
        else if (fb == 0.0)
            r = b;
        else if ((fa < 0.0) != (fb < 0.0))
            r = polish(c, a, b, fa);
        /* a monotone piece holds one root: past one too early, try the next */
        if (r > after) {
            *root = r;
            return 1;
        }
        fa = fb;
    }
    return 0;
}
