/* profile_radius: where the profile's shape crosses a height. On each cubic
 * Bezier piece h(s) is a cubic in s, solved by GSL; the radius is the
 * piece's r at each root in [0, 1]. See include/celadon/profile.h. */
#include "celadon/profile.h"

#include <gsl/gsl_poly.h>
#include <math.h>
#include <stdlib.h>

/* Roots in [0, 1] of a s^3 + b s^2 + c s + d = 0 (any of a, b, c zero);
 * returns how many (at most 3). */
static int unit_roots(double a, double b, double c, double d, double s[3])
{
    double x[3];
    int n;
    double scale = fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d)));
    if (fabs(a) > 1e-12 * scale)
        n = gsl_poly_solve_cubic(b / a, c / a, d / a, &x[0], &x[1], &x[2]);
    else
        n = gsl_poly_solve_quadratic(b, c, d, &x[0], &x[1]); /* also linear when b = 0 */
    int m = 0;
    for (int i = 0; i < n; i++)
        if (x[i] >= -1e-9 && x[i] <= 1 + 1e-9)
            s[m++] = fmin(fmax(x[i], 0.0), 1.0);
    return m;
}

int profile_radius(const profile_t *p, double h, double *radius)
{
    const double *domains;
    int n_domains;
    const bspline_t *shape = profile_shape(p, &domains, &n_domains);
    double h_rim = bspline_eval(shape, shape->knots[bspline_n_knots(shape) - 1]).y;
    bezier3_t *pieces = NULL;
    int n = h_rim > 0 && isfinite(h) ? bspline_to_bezier(shape, &pieces) : 0, found = 0;
    double target = h * h_rim, best = 0;
    for (int k = 0; k < n; k++) {
        const vec2 *q = pieces[k].p;
        /* The Bernstein form of h(s) in powers of s. */
        double a = -q[0].y + 3 * q[1].y - 3 * q[2].y + q[3].y, b = 3 * q[0].y - 6 * q[1].y + 3 * q[2].y;
        double c = 3 * (q[1].y - q[0].y), d = q[0].y - target, s[3];
        int m = unit_roots(a, b, c, d, s);
        for (int i = 0; i < m; i++) {
            double r = bezier3_eval(&pieces[k], s[i]).x;
            best = found++ ? fmax(best, r) : r;
        }
    }
    free(pieces);
    *radius = found ? best / h_rim : NAN;
    return found ? 0 : -1;
}
