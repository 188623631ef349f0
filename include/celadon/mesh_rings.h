/* Where a meshed surface of revolution places its rings (the profile
 * parameters revolved into vertex circles), for every caller that meshes an
 * SOR to stand in for the exact surface (render --geometry mesh:N, accel's
 * meshed SOR). */
#ifndef CELADON_MESH_RINGS_H
#define CELADON_MESH_RINGS_H

#include "celadon/bspline.h"

/* Relative floor of mesh_ring_tolerance: 2^-22, four float ulps. */
#define MESH_RING_TOL_FLOOR (1.0 / 4194304.0)

/* The profile chord tolerance (profile units) that matches N angular
 * segments: the sagitta r_max (1 - cos(pi/N)) ~ 4.93 r_max / N^2 of the
 * widest ring's chords, r_max bounded by the control polygon, but not below
 * MESH_RING_TOL_FLOOR r_max (float vertices resolve nothing finer; the
 * floor takes over near N = 4500). Rings placed at this tolerance keep the
 * profile's chord error no larger than the angular one, so the mesh's
 * distance to the surface falls as N^-2 with both.
 * Returns 0 for an invalid curve or segments < 3. */
double mesh_ring_tolerance(const bspline_t *profile, int segments);

/* The ring parameters: every boundary of keep[0..n_keep-1] (strictly
 * increasing, inside the curve's parameter range, e.g. profile.json's
 * domains; NULL for none) merged with
 * curve_domains_by_curvature_variation(profile, tol_px, 2 tol_px / r_max
 * radians), near-coincident values (closer than 1e-12 of the range) counted
 * once. The normal tolerance is (pi/N)^2 when tol_px is the tolerance of N
 * segments: a mesh interpolates its shading normals linearly between rings,
 * and where the profile's curvature changes that departs from the true
 * normal by about |dk/ds| L^2 / 8 over a ring spacing L; bounding it like
 * the chords makes the shading normals converge as N^-2 too (with the chord
 * criterion alone their mean error fell as N^-1.5 on the showcase). *u (malloc'd) receives the increasing parameters, *n their number.
 * Returns 0, or -1 for an invalid curve, tol_px <= 0 or NaN, keep not
 * increasing or outside the range, or allocation failure. */
int mesh_rings(const bspline_t *profile, const double *keep, int n_keep, double tol_px, double **u, int *n);

#endif
