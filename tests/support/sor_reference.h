/* A brute-force reference for ray-SOR intersection, independent of the
 * library's solver: the B-spline is evaluated in long double from its own
 * Cox-de Boor recursion (no Bézier conversion, no monotone split), and roots
 * are found by interval bisection with a rigorous Lipschitz exclusion test, so
 * every root is found down to ~1e-15 of a knot span; a root that cannot be
 * told from a tangency at that resolution is reported as ambiguous. */
#ifndef CELADON_TEST_SOR_REFERENCE_H
#define CELADON_TEST_SOR_REFERENCE_H

#include <stdint.h>

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

typedef struct sor_ref sor_ref;

enum { SOR_REF_MISS = 0, SOR_REF_HIT = 1, SOR_REF_AMBIGUOUS = -1 };

/* Same meaning of profile, height and caps as sor_create. NULL on bad input. */
sor_ref *sor_ref_create(const bspline_t *profile, double height, unsigned caps);
void sor_ref_destroy(sor_ref *ref);
/* The reference for test profile i (sor_profiles.h) at height 1. */
sor_ref *sor_ref_create_profile(int i, unsigned caps);

/* Nearest t in (tmin, tmax) where the ray meets the closed surface. Returns
 * SOR_REF_HIT (and *t), SOR_REF_MISS, or SOR_REF_AMBIGUOUS when a tangency
 * nearer than any clear hit cannot be resolved. */
int sor_ref_intersect(const sor_ref *ref, const ray3 *ray, double tmin, double tmax, long double *t);

/* Inside the closed surface (ray-parity in the (r, h) half-plane): 1, 0, or
 * -1 when the point is too close to the surface to call. */
int sor_ref_inside(const sor_ref *ref, vec3 p);

/* An upper bound of the distance from p to the closed surface (exact to
 * rounding for points on it). */
double sor_ref_surface_distance(const sor_ref *ref, vec3 p);

/* The wall point at profile parameter u and angle phi, object space. */
vec3 sor_ref_wall_point(const sor_ref *ref, double u, double phi);
/* Interior joints of the profile: the distinct interior knots (Bézier joints). */
int sor_ref_joint_count(const sor_ref *ref);
double sor_ref_joint(const sor_ref *ref, int k);
/* The outward normal direction of the wall there (unnormalised). */
vec3 sor_ref_wall_normal(const sor_ref *ref, double u, double phi);

/* Object extent: max radius, min and max height, and the size used for tolerances. */
double sor_ref_size(const sor_ref *ref);
double sor_ref_rmax(const sor_ref *ref);
double sor_ref_hmin(const sor_ref *ref);
double sor_ref_hmax(const sor_ref *ref);
/* Cap radii (0 when the cap is absent). */
double sor_ref_cap_radius(const sor_ref *ref, int mouth);

/* Deterministic random numbers for the tests (splitmix64). */
typedef struct {
    uint64_t s;
} sor_rng;
double sor_rng_uniform(sor_rng *g); /* [0, 1) */

/* A test ray: a mix of rays from afar through the object's box or at wall
 * points, nearly horizontal and nearly (or exactly) vertical rays, and rays
 * from near the object in any direction. Direction not normalised. */
ray3 sor_ref_random_ray(const sor_ref *ref, sor_rng *g);

#endif
