/* Internal to the curve module: the least-squares step of the B-spline fit. */
#ifndef CELADON_CURVE_FIT_LSQ_H
#define CELADON_CURVE_FIT_LSQ_H

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

/* The clamped cubic on [0,1] with the given strictly increasing interior
 * knots (in (0,1)) that interpolates q[0] and q[n-1] and minimises the sum of
 * squared residuals |C(u_i) - q_i|^2 over the rest. u must be increasing with
 * u[0] = 0 and u[n-1] = 1, and n_int + 4 <= n. out is (re)allocated; resid[i]
 * receives C(u_i) - q_i. Returns 0, or -1 on allocation or numerical failure. */
int fit_lsq_spline(const vec2 *q, const double *u, int n, const double *interior, int n_int, bspline_t *out,
                   vec2 *resid);

#endif
