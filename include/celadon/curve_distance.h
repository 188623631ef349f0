/* Distances between a profile curve and points or a polyline. */
#ifndef CELADON_CURVE_DISTANCE_H
#define CELADON_CURVE_DISTANCE_H

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

/* Distance from p to the curve near parameter u_guess: Newton iterations on
 * (C(u) - p) . C'(u) = 0 from u_guess, clamped to the domain, never returning
 * a point farther than C(u_guess). *u_foot (may be NULL) receives the foot
 * parameter. A local search: the caller supplies a good guess. */
double curve_point_distance_near(const bspline_t *c, vec2 p, double u_guess, double *u_foot);

/* The two one-sided Hausdorff distances between the curve and the polyline
 * poly[0..n-1] (n >= 1): the largest distance from a curve point to the
 * polyline, and from a polyline point (vertices and segment interiors) to the
 * curve. Both sides are sampled densely (spacing <= 0.25 px), searched with a
 * bounding-box tree over segments, and the maxima polished locally (golden section; Newton foot
 * points on the curve), so they are exact to about 1e-6 px. Both are NaN
 * when the curve is invalid, n < 1, or a coordinate (polyline point or
 * control point) is not finite or exceeds 1e100 in magnitude. */
void curve_polyline_hausdorff(const bspline_t *c, const vec2 *poly, int n, double *curve_to_polyline,
                              double *polyline_to_curve);

/* The same with the curve side restricted to the parameters [u_lo, u_hi]
 * (clamped to the curve's domain): the curve over a piece of the polyline,
 * where the polyline has gaps that the curve bridges. */
void curve_range_polyline_hausdorff(const bspline_t *c, double u_lo, double u_hi, const vec2 *poly, int n,
                                    double *curve_to_polyline, double *polyline_to_curve);

#endif
