/* Clamped B-spline curves in the plane: evaluation, derivatives, Bézier
 * decomposition. The profile curve C(u) = (r(u), h(u)), u in [0,1], is one. */
#ifndef CELADON_BSPLINE_H
#define CELADON_BSPLINE_H

#include "celadon/vecmath.h"

typedef struct {
    int degree;    /* p; the profile uses 3 */
    int n_ctrl;    /* n + 1 control points */
    double *knots; /* n_ctrl + degree + 1 values, non-decreasing, clamped */
    vec2 *ctrl;
} bspline_t;

/* A cubic Bézier piece of a B-spline: control points and the parameter range
 * [u0, u1] of the B-spline that it covers (its own parameter is s in [0,1]). */
typedef struct {
    vec2 p[4];
    double u0, u1;
} bezier3_t;

/* Allocates knots and control points (zeroed). Returns 0 or -1. */
int bspline_init(bspline_t *c, int degree, int n_ctrl);
void bspline_free(bspline_t *c);
int bspline_copy(bspline_t *dst, const bspline_t *src);
int bspline_n_knots(const bspline_t *c);

/* Checks the invariants (degree >= 1, enough control points, knots finite,
 * non-decreasing, clamped at both ends, interior multiplicity <= degree).
 * Returns NULL when valid, otherwise a static description of what is wrong. */
const char *bspline_validate(const bspline_t *c);

/* Knot span index k with knots[k] <= u < knots[k+1] (the last non-empty span
 * at the right end). u is clamped to the domain. */
int bspline_find_span(const bspline_t *c, double u);

vec2 bspline_eval(const bspline_t *c, double u);
/* out[0..nder]: the curve and its first nder derivatives at u (nder <= 3). */
void bspline_eval_derivs(const bspline_t *c, double u, int nder, vec2 *out);
/* Signed curvature of the planar curve at u. */
double bspline_curvature(const bspline_t *c, double u);

/* Splits a cubic B-spline into its non-degenerate Bézier pieces by knot
 * insertion (Boehm). Returns the number of pieces written to *out (malloc'd),
 * or -1 when the curve is not cubic or allocation fails. */
int bspline_to_bezier(const bspline_t *c, bezier3_t **out);

/* The largest |x| (axis 0: a profile's radius) or y (axis 1: its height)
 * the cubic curve reaches, exactly (each Bézier piece's ends and stationary
 * points); -1 when the curve is not cubic or allocation fails. */
double bspline_largest(const bspline_t *curve, int axis);

/* Bézier piece evaluation (de Casteljau) and derivative. */
vec2 bezier3_eval(const bezier3_t *b, double s);
vec2 bezier3_deriv(const bezier3_t *b, double s);

#endif
