/* One ray-tracing scene for every shape: an Embree 3 device and scene holding
 * triangle meshes and surfaces of revolution (SORs), each placed by an affine
 * object-to-world transform.
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

typedef enum { ACCEL_KIND_MESH = 0, ACCEL_KIND_SOR_ANALYTIC = 1, ACCEL_KIND_SOR_MESH = 2 } accel_kind;

/* How an SOR enters the scene. segments = 0: analytic. segments >= 3: meshed
 * with that many angular segments and rings at u_rings[0..n_rings-1] when given
 * (e.g. profile.json's domains), otherwise at curve_domains_by_curvature(tol_px). */
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
    vec2 uv;     /* SOR: sor_hit.uv; mesh: interpolated uv (barycentrics when the mesh has none) */
    sor_part part; /* analytic SOR: the part hit; meshes: SOR_PART_WALL */
} accel_hit;

/* BVH build effort: FAST is Embree's default (medium quality); BEST adds
 * spatial splits, slower to build (several times, for millions of triangles)
 * and faster to trace, for static scenes traced many times. */
typedef enum { ACCEL_BUILD_FAST = 0, ACCEL_BUILD_BEST = 1 } accel_build;

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

/* Builds the BVH; call after the last add and before tracing. Returns 0 or -1. */
int accel_commit(accel_t *acc, char *err, size_t errlen);

/* Nearest hit with t in (tmin, tmax) of a world-space ray (d need not be unit). */
int accel_intersect(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit);
/* Any hit with t in (tmin, tmax). */
int accel_occluded(const accel_t *acc, const ray3 *ray, double tmin, double tmax);

/* Introspection: the analytic SOR of a geometry (NULL unless ACCEL_KIND_SOR_ANALYTIC),
 * its triangle count (0 for analytic SORs), and the scene's world bounds. */
accel_kind accel_geometry_kind(const accel_t *acc, unsigned geom_id);
const sor_t *accel_geometry_sor(const accel_t *acc, unsigned geom_id);
int accel_geometry_triangles(const accel_t *acc, unsigned geom_id);
void accel_bounds(const accel_t *acc, vec3 *lo, vec3 *hi);

/* Distance from an object-space point p to the closed SOR of (profile, height,
 * caps): the wall, plus the base disc and the mouth disc when capped. Measures
 * how far a tessellation's points lie from the exact surface. */
double accel_sor_distance(const bspline_t *profile, double height, unsigned caps, vec3 p);

#endif
