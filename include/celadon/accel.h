/* One ray-tracing scene for every shape: an Embree 3 device and scene holding
 * triangle meshes, surfaces of revolution (SORs), the quadrics sphere, disk
 * and cylinder, curves, and user geometries the caller intersects itself,
 * each placed by an affine object-to-world transform.
 *
 * Placement is a transform4 (celadon/transform.h: the matrix with its inverse),
 * as scenes carry it; NULL means the identity.
 *
 * An SOR enters the scene in one of two forms behind the same call:
 *  - analytic: an Embree user geometry with one primitive per monotone interval
 *    of the profile plus its caps (sor_prim_*), so Embree's BVH culls intervals
 *    and the exact double-precision solver of sor.h runs at the leaves;
 *  - meshed: mesh_revolve at N angular segments, rings at the profile's
 *    curvature domains, traced by Embree as triangles.
 *
 * Rays and hits are double at this interface. Embree traverses in float; the
 * analytic callbacks and the final triangle hit are recomputed from the double
 * ray, so an analytic hit through the scene has the same t as sor_intersect.
 *
 * Thread safety: after accel_commit, accel_intersect and accel_occluded may be
 * called from any number of threads. Building (add, commit) is single-threaded. */
#ifndef CELADON_ACCEL_H
#define CELADON_ACCEL_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/mesh.h"
#include "celadon/sor.h"
#include "celadon/transform.h"
#include "celadon/vecmath.h"

typedef struct accel accel_t;

#define ACCEL_INVALID_ID 0xffffffffu

/* The quadrics are Mitsuba's shapes in their object space, exact in double
 * precision as Embree user geometries (one primitive each):
 *  - sphere: the unit sphere at the origin; param = (theta from +z, phi),
 *    uv = (phi / 2pi, theta / pi);
 *  - disk: the unit disk in z = 0, normal +z; param = (radius, phi),
 *    uv = (radius, phi / 2pi);
 *  - cylinder: the open tube of radius 1 around z from z = 0 to 1, normal
 *    outward; param = (z, phi), uv = (phi / 2pi, z);
 * phi = atan2(y, x) in [0, 2pi). */
typedef enum {
    ACCEL_KIND_MESH = 0,
    ACCEL_KIND_SOR_ANALYTIC = 1,
    ACCEL_KIND_SOR_MESH = 2,
    ACCEL_KIND_SPHERE = 3,
    ACCEL_KIND_DISK = 4,
    ACCEL_KIND_CYLINDER = 5,
    ACCEL_KIND_CURVE_LINEAR = 6,  /* Embree's round linear curves */
    ACCEL_KIND_CURVE_BSPLINE = 7, /* Embree's round cubic B-spline curves */
    ACCEL_KIND_USER = 8           /* primitives the caller intersects (accel_add_user) */
} accel_kind;

/* How an SOR enters the scene. segments = 0: analytic. segments >= 3: meshed
 * with that many angular segments and rings at u_rings[0..n_rings-1] when given
 * (e.g. profile.json's domains), otherwise at mesh_rings(tol_px) (mesh_rings.h;
 * tol_px = mesh_ring_tolerance(segments) is the rule render --geometry mesh:N
 * uses, where the mesh converges as N^-2). */
typedef struct {
    int segments;
    const double *u_rings;
    int n_rings;
    double tol_px;
} accel_sor_mode;

typedef struct {
    unsigned geom_id; /* as returned by accel_add_*; ACCEL_INVALID_ID on a miss */
    unsigned prim;    /* triangle index, or SOR primitive (sor_prim_count order) */
    accel_kind kind;
    double t;
    vec3 p;      /* world */
    vec3 ng;     /* world, unit: SOR outward normal; mesh face normal (counter-clockwise side) */
    vec3 ns;     /* world, unit shading normal: SOR analytic normal; mesh interpolated normal
                    (face normal when the mesh has none) */
    vec2 uv;     /* SOR: sor_hit.uv; quadric: as above; mesh: interpolated uv (barycentrics when
                    the mesh has none) */
    sor_part part; /* analytic SOR: the part hit; quadrics and meshes: SOR_PART_WALL */
    /* The hit in the geometry's object space, for what is defined there
     * (densities per object area, surface parameters): */
    vec3 p_obj;      /* point */
    vec3 n_obj;      /* unit: SOR and quadric outward normal; mesh counter-clockwise face normal */
    double param[2]; /* analytic SOR: profile u and phi (sor_hit.u, .phi); quadric: as above;
                        triangle: barycentrics of its second and third vertex */
} accel_hit;

/* BVH build effort: FAST is Embree's default (medium quality); BEST adds
 * spatial splits, slower to build (several times, for millions of triangles)
 * and faster to trace, for static scenes traced many times. Either may be
 * or-ed with ROBUST: Embree's watertight triangle test (no ray slips between
 * two triangles sharing an edge), a little slower. */
typedef enum { ACCEL_BUILD_FAST = 0, ACCEL_BUILD_BEST = 1, ACCEL_BUILD_ROBUST = 2 } accel_build;

/* A new empty scene on its own Embree device. Returns NULL with a reason in err. */
accel_t *accel_create(accel_build build, char *err, size_t errlen);
void accel_destroy(accel_t *acc);

/* Adds a copy of the mesh (pos, tri required; nrm, uv optional), placed by to_world.
 * Returns the geometry id, or ACCEL_INVALID_ID with a reason in err. */
unsigned accel_add_mesh(accel_t *acc, const mesh_t *mesh, const transform4 *to_world, char *err, size_t errlen);

/* Adds the SOR of sor_create(profile, height, caps) placed by to_world, in the form
 * mode asks for. Returns the geometry id, or ACCEL_INVALID_ID with a reason. */
unsigned accel_add_sor(accel_t *acc, const bspline_t *profile, double height, unsigned caps,
                       const transform4 *to_world, const accel_sor_mode *mode, char *err, size_t errlen);

/* Adds the quadric kind (ACCEL_KIND_SPHERE, _DISK or _CYLINDER) placed by
 * to_world. Returns the geometry id, or ACCEL_INVALID_ID with a reason. */
unsigned accel_add_quadric(accel_t *acc, accel_kind kind, const transform4 *to_world, char *err, size_t errlen);

/* Adds round curves of kind ACCEL_KIND_CURVE_LINEAR or _BSPLINE: n_points
 * world-space control points of four floats (x, y, z, radius) and n_segments
 * segments, segment i made of the 2 (linear) or 4 (B-spline) points from
 * index segments[i]. A hit reports t, p, ng (unit, Embree's), prim (the
 * segment) and param[0] (the curve parameter within the segment, in
 * [0, 1]); rays starting inside a curve do not hit it (Embree's).
 * Returns the geometry id, or ACCEL_INVALID_ID with a reason. */
unsigned accel_add_curves(accel_t *acc, accel_kind kind, const float *points, int n_points, const unsigned *segments,
                          int n_segments, char *err, size_t errlen);

/* A user geometry: primitives that the caller bounds and intersects
 * itself, exactly, in the geometry's object space (the SDF grid shape).
 * Embree's BVH culls the primitives by their boxes and calls intersect on
 * those a ray's box test passes, from any number of threads at once. */
typedef struct {
    double t;
    vec3 p, n;       /* object-space point and unit geometric normal */
    vec2 uv;
    double param[2]; /* the caller's own surface parameters, reported back in accel_hit */
} accel_user_hit;

typedef struct {
    /* The object-space box of primitive prim. */
    void (*bounds)(const void *data, unsigned prim, vec3 *lo, vec3 *hi);
    /* The nearest hit of primitive prim along the object-space ray r (d not
     * unit; t as in the world) with t in (tmin, tmax): 1 with *h, or 0. */
    int (*intersect)(const void *data, unsigned prim, const ray3 *r, double tmin, double tmax, accel_user_hit *h);
} accel_user_ops;

/* Adds a user geometry of n_prims primitives (at least 1) placed by
 * to_world; data is handed to ops and must outlive the scene. A hit
 * reports kind ACCEL_KIND_USER, prim, t, p, ng = ns, uv and param from the
 * caller's hit, part SOR_PART_WALL. Returns the geometry id, or
 * ACCEL_INVALID_ID with a reason. */
unsigned accel_add_user(accel_t *acc, const accel_user_ops *ops, const void *data, unsigned n_prims,
                        const transform4 *to_world, char *err, size_t errlen);

/* What a hit at the point p of a quadric's object-space surface reports
 * there (unit outward normal, uv, param), e.g. for a point sampled on it. */
void accel_quadric_at(accel_kind kind, vec3 p, vec3 *n, vec2 *uv, double param[2]);

/* Builds the BVH; call after the last add and before tracing. Returns 0 or -1. */
int accel_commit(accel_t *acc, char *err, size_t errlen);

/* Nearest hit with t in (tmin, tmax), 0 <= tmin, of a world-space ray (d need not be unit). */
int accel_intersect(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit);
/* The same nearest hit, except that a triangle of a mesh added by
 * accel_add_mesh (ACCEL_KIND_MESH) reports only geom_id, prim, kind, t and
 * param (its barycentrics, refined in double as accel_intersect's): for a
 * caller that completes the hit from its own copy of the mesh (the
 * renderer's shapes), which then costs no interpolation twice. */
int accel_intersect_refined(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit);
/* Any hit with t in (tmin, tmax). */
int accel_occluded(const accel_t *acc, const ray3 *ray, double tmin, double tmax);

/* Introspection: the analytic SOR of a geometry (NULL unless ACCEL_KIND_SOR_ANALYTIC),
 * its triangle count (0 for user geometries: analytic SORs, quadrics), and
 * the scene's world bounds. */
accel_kind accel_geometry_kind(const accel_t *acc, unsigned geom_id);
const sor_t *accel_geometry_sor(const accel_t *acc, unsigned geom_id);
int accel_geometry_triangles(const accel_t *acc, unsigned geom_id);
void accel_bounds(const accel_t *acc, vec3 *lo, vec3 *hi);

/* Distance from an object-space point p to the closed SOR of (profile, height,
 * caps): the wall, plus the base disc and the mouth disc when capped. Measures
 * how far a tessellation's points lie from the exact surface. */
double accel_sor_distance(const bspline_t *profile, double height, unsigned caps, vec3 p);

#endif
