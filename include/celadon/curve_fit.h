/* Fitting a clamped cubic B-spline to a profile polyline the way Dierckx's
 * FITPACK (curfit/parcur) does: least squares on a knot set that grows, one
 * knot at a time, in the knot interval with the largest sum of squared
 * residuals, until the residual is small enough. docs/algorithms-curve.md. */
#ifndef CELADON_CURVE_FIT_H
#define CELADON_CURVE_FIT_H

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

typedef struct {
    double s;       /* the smoothing target met (for bspline_fit_profile: the SSR it stopped at) */
    double ssr;     /* sum of squared residuals |C(u_i) - p_i|^2 of the result */
    int n_ctrl;     /* control points of the result */
    int iterations; /* least-squares fits solved (one per knot set tried) */
} bspline_fit_info;

/* Parametrises the polyline by chord length normalised to [0,1] (u = 0 at
 * pts[0], the base), drops repeated points, and fits a clamped cubic that
 * interpolates the first and last point exactly. Knots are added until the
 * sum of squared residuals is <= s; when s cannot be met before there are as
 * many control points as points, the result is the interpolating spline
 * (not-a-knot). out is allocated (bspline_free). info may be NULL.
 * Returns 0, or -1 on degenerate input (fewer than 4 distinct points, a
 * non-finite coordinate, s negative or NaN) or allocation failure. */
int bspline_fit_smoothing(const vec2 *pts, int n, double s, bspline_t *out, bspline_fit_info *info);

/* The default profile fit: the same knot sequence, stopped at the first
 * (fewest control points) spline for which every polyline point lies within
 * max_dev_px of the curve (distance to the nearest curve point). Returns 0 or
 * -1 as above (also for max_dev_px <= 0 or NaN). */
int bspline_fit_profile(const vec2 *pts, int n, double max_dev_px, bspline_t *out, bspline_fit_info *info);

#endif
