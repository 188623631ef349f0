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
 * domains; NULL for none) merged with curve_domains_by_curvature(profile,
 * tol_px), near-coincident values (closer than 1e-12 of the range) counted
 * once. *u (malloc'd) receives the increasing parameters, *n their number.
 * Returns 0, or -1 for an invalid curve, tol_px <= 0 or NaN, keep not
 * increasing or outside the range, or allocation failure. */
int mesh_rings(const bspline_t *profile, const double *keep, int n_keep, double tol_px, double **u, int *n);

#endif
