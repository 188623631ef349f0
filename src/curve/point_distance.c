/* Foot point of a point on the curve by Newton's method on
 * f(u) = (C(u) - p) . C'(u), f'(u) = |C'|^2 + (C(u) - p) . C''(u). */
#include "celadon/curve_distance.h"

enum { MAX_NEWTON = 12 };

double curve_point_distance_near(const bspline_t *c, vec2 p, double u_guess, double *u_foot)
{
    double lo = c->knots[0], hi = c->knots[bspline_n_knots(c) - 1];
    double u = u_guess < lo ? lo : (u_guess > hi ? hi : u_guess);
    vec2 d[3];
    bspline_eval_derivs(c, u, 2, d);
    double best_u = u, best = v2_len(v2_sub(d[0], p));
    for (int it = 0; it < MAX_NEWTON; it++) {
        vec2 e = v2_sub(d[0], p);
        double f = v2_dot(e, d[1]), fp = v2_dot(d[1], d[1]) + v2_dot(e, d[2]);
        /* Away from a minimum (fp <= 0) step along the gradient instead. */
        double step = fp > 0.0 ? f / fp : f / (v2_dot(d[1], d[1]) + 1e-300);
        double un = u - step;
        un = un < lo ? lo : (un > hi ? hi : un);
        if (un == u)
            break;
        u = un;
        bspline_eval_derivs(c, u, 2, d);
        double dist = v2_len(v2_sub(d[0], p));
        if (dist < best) {
            best = dist;
            best_u = u;
        }
        if (fabs(step) < 1e-14 * (hi - lo))
            break;
    }
    if (u_foot)
        *u_foot = best_u;
    return best;
}
