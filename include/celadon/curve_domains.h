/* Curvature-adaptive split of the profile parameter range into domains. */
#ifndef CELADON_CURVE_DOMAINS_H
#define CELADON_CURVE_DOMAINS_H

#include "celadon/bspline.h"

/* Splits the curve's parameter range [first knot, last knot] into domains
 * [u_k, u_k+1] such that on each domain the curve stays within tol_px of its
 * chord (the sagitta of the domain, measured at 16 interior samples, is
 * <= tol_px): each knot span is bisected recursively until that holds (at
 * most 2^16 domains per span). The chord deviation of an arc of length L and
 * curvature kappa is about kappa L^2 / 8, so domains shrink as 1/sqrt(kappa)
 * where the profile bends and stay whole knot spans where it is straight;
 * a polyline through the domain boundaries (a mesh ring per boundary) is
 * within tol_px of the curve. Every distinct knot is a boundary.
 * *u (malloc'd) receives the increasing boundaries, *n their number (domains
 * + 1). Returns 0, or -1 for an invalid curve, tol_px <= 0 or NaN, or
 * allocation failure. */
int curve_domains_by_curvature(const bspline_t *c, double tol_px, double **u, int *n);

/* The same split with a second criterion on the curvature variation: a domain
 * is also bisected while the curve's tangent angle departs by more than
 * tol_normal_deg from its linear interpolation in arc length between the
 * domain's ends (sampled at 16 interior points). The angle is linear in arc
 * length exactly where the curvature is constant, so this puts more domains
 * where the curvature changes fast (the departure is about |dk/ds| L^2 / 8);
 * and since a mesh interpolates its normals between rings, it bounds the
 * shading-normal error of the revolved mesh. tol_normal_deg = INFINITY gives
 * curve_domains_by_curvature. Returns as that does; also -1 for
 * tol_normal_deg <= 0 or NaN. */
int curve_domains_by_curvature_variation(const bspline_t *c, double tol_px, double tol_normal_deg, double **u,
                                         int *n);

#endif
