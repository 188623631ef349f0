/* Exact ray intersection with a surface of revolution (SOR) whose profile is a
 * clamped cubic B-spline C(u) = (r(u), h(u)), u in [0,1] from base to rim.
 *
 * Object space (docs/conventions.md): Y is the axis, the base at y = 0, the profile scaled
 * uniformly so the rim is at y = height. A profile point (r, h) at angle phi is
 * (r cos phi, h, r sin phi), phi = atan2(z, x) in [0, 2 pi). Texture u is
 * 1 - phi/pi on [0, pi] and phi/pi - 1 on [pi, 2 pi]; v = h / height.
 * The wall is closed by analytic caps: a base disc at y = 0 and, unless asked
 * to stay open, a mouth disc at y = height. */
#ifndef CELADON_SOR_H
#define CELADON_SOR_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

typedef struct sor sor_t;

enum { SOR_CAP_BASE = 1u, SOR_CAP_MOUTH = 2u, SOR_CAPS_ALL = 3u };
typedef enum { SOR_PART_WALL = 0, SOR_PART_BASE = 1, SOR_PART_MOUTH = 2 } sor_part;

typedef struct {
    double t;        /* ray parameter */
    double u;        /* profile parameter on the wall (0 on the base cap, 1 on the mouth cap) */
    double phi;      /* angle around the axis, [0, 2 pi) */
    vec3 p;          /* hit point, object space */
    vec3 ng;         /* geometric normal, unit, outward */
    frame3 shading;  /* shading frame: n = ng, s along dP/dphi where defined */
    vec2 uv;         /* texture coordinates (see above) */
    sor_part part;
    int prim;        /* primitive index (see sor_prim_count) */
} sor_hit;

/* Profile coordinates (pixels) beyond this magnitude are refused: squares
 * of them stay far from overflow, and no photo is that large. */
#define SOR_PROFILE_MAX_COORD 1e9
/* The least profile height h(1), pixels: below it the scale to object
 * space would overflow. */
#define SOR_PROFILE_MIN_HEIGHT 1e-6

/* Why the profile cannot be revolved, or NULL when it can: it must be a
 * valid clamped cubic B-spline, its control points within
 * SOR_PROFILE_MAX_COORD, h(0) = 0 < SOR_PROFILE_MIN_HEIGHT <= h(1) and r >= 0
 * on every Bezier control point (so on the whole curve) and r > 0 on one of
 * them (a profile on the axis has no surface), all up to rounding (1e-9 of
 * the largest control coordinate). The reason is a static string
 * without the file name. Every reader of a profile applies this, so a
 * profile is accepted or refused alike by the exact and the meshed SOR. */
const char *sor_profile_check(const bspline_t *profile);

/* Builds the SOR of a profile that sor_profile_check accepts; height > 0.
 * caps is a mask of SOR_CAP_*. Returns NULL with a one-line reason in err on
 * invalid input. Control points with r or h(0) off by rounding are snapped. */
sor_t *sor_create(const bspline_t *profile, double height, unsigned caps, char *err, size_t errlen);
void sor_destroy(sor_t *s);

/* Nearest hit with t in (tmin, tmax). Returns 1 and fills hit, or 0. The ray
 * direction need not be unit length. */
int sor_intersect(const sor_t *s, const ray3 *ray, double tmin, double tmax, sor_hit *hit);
/* Any hit with t in (tmin, tmax): cheaper than sor_intersect for shadow rays. */
int sor_occluded(const sor_t *s, const ray3 *ray, double tmin, double tmax);

/* Axis-aligned bounds of the whole surface, object space. */
void sor_bounds(const sor_t *s, vec3 *lo, vec3 *hi);

/* Primitives, for a BVH that culls them (Embree user geometry): one per
 * monotone interval of the wall, then the base cap, then the mouth cap if
 * present. Each has its own bounds and intersection. */
int sor_prim_count(const sor_t *s);
void sor_prim_bounds(const sor_t *s, int prim, vec3 *lo, vec3 *hi);
int sor_prim_intersect(const sor_t *s, int prim, const ray3 *ray, double tmin, double tmax, sor_hit *hit);

/* Reference for benchmarks and tests: the same exact leaf solver applied to
 * every Bézier piece of the wall with no hierarchy, plus the caps. */
int sor_intersect_naive(const sor_t *s, const ray3 *ray, double tmin, double tmax, sor_hit *hit);

/* Scale from profile units (pixels) to object space: height / h(1). */
double sor_profile_scale(const sor_t *s);

#endif
