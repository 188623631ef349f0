/* Real roots of low-degree polynomials in double precision, for ray-surface
 * intersections: the quadrics' quadratic, the SDF grid's cubic along a ray
 * through a voxel. */
#ifndef CELADON_POLYNOMIAL_H
#define CELADON_POLYNOMIAL_H

/* Roots of a t^2 + 2 b t + c = 0 without cancellation. Returns 0 when there
 * are none (or a = 0), else 2 with *t0 <= *t1 (equal for a double root). */
int poly_quadratic_roots(double a, double b, double c, double *t0, double *t1);

/* The smallest root in [lo, hi] of c[0] + c[1] t + c[2] t^2 + c[3] t^3 at
 * which the polynomial changes sign or is zero, larger than after: 1 and
 * *root, or 0 when there is none. The interval is split at the critical
 * points (roots of the derivative) into pieces on which the polynomial is
 * monotone, so each piece holds at most one root, bracketed exactly by the
 * signs at its ends; the root is then polished by Newton's method kept
 * inside its bracket, to within a few ulps of the interval. A root of even
 * multiplicity (a touch without a crossing) counts only where the computed
 * value is exactly zero. Requires lo <= hi. */
int poly_cubic_first_root(const double c[4], double lo, double hi, double after, double *root);

#endif
