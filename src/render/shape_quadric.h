/* Roots of a t^2 + 2 b t + c = 0 without cancellation (shared by the
 * sphere and the cylinder). Returns the number of real roots, t0 <= t1. */
#ifndef CELADON_SHAPE_QUADRIC_H
#define CELADON_SHAPE_QUADRIC_H

#include <math.h>

static inline int shape_solve_quadratic(double a, double b, double c, double *t0, double *t1)
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

static inline double shape_wrap_angle(double phi) { return phi < 0.0 ? phi + 2.0 * M_PI : phi; }

#endif
