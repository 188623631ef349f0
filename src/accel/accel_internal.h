/* Shared between the files of src/accel: the scene record, one record per
 * Embree geometry, and the extended intersect context that carries the double
 * ray into the user-geometry callbacks. */
#ifndef CELADON_ACCEL_INTERNAL_H
#define CELADON_ACCEL_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>

#include "celadon/accel.h"

/* One vertex of our copy, attributes side by side: a hit reads the three
 * vertices of one triangle, so interleaving costs it the fewest cache lines. */
typedef struct {
    float p[3], n[3], uv[2];
} accel_vertex;

typedef struct {
    accel_kind kind;
    transform4 to_world, to_object; /* each carries the other as its inverse */
    /* Triangles (ACCEL_KIND_MESH, ACCEL_KIND_SOR_MESH): Embree's buffers hold the
     * world-space vertices it traverses (float) and the indices; our copy keeps
     * the mesh as given, in object space, where hits are refined in double. */
    int n_verts, n_tris;
    const uint32_t *tri;
    accel_vertex *vtx;
    int has_nrm, has_uv;
    /* Analytic SOR (ACCEL_KIND_SOR_ANALYTIC). */
    sor_t *sor;
} accel_geom;

/* A unit normal mapped to world space (by the inverse transpose). */
static inline vec3 world_normal(const accel_geom *g, vec3 n) { return v3_norm(transform_normal(&g->to_world, n)); }

struct accel {
    RTCDevice device;
    RTCScene scene;
    accel_geom **geoms; /* indexed by Embree geometry id; records never move (callbacks hold them) */
    int n_geoms, cap_geoms;
};

/* Embree hands our context pointer to the callbacks, so they can read the exact
 * double ray and keep the exact nearest analytic hit (Embree's ray is float). */
typedef struct {
    struct RTCIntersectContext rtc; /* first member: the pointer Embree passes */
    const accel_t *acc;
    ray3 ray;          /* world */
    double tmin, tbest; /* tbest: nearest accepted analytic t so far (starts at tmax) */
    unsigned obj_geom;  /* geometry whose object-space ray is cached in obj_ray */
    ray3 obj_ray;
    unsigned sor_geom;  /* geometry of sor_hit, ACCEL_INVALID_ID when none */
    sor_hit sor_hit;    /* object space */
} accel_context;


/* Creates the Embree user geometry of an analytic SOR whose record is g
 * (g->sor, transforms set). Returns the uncommitted geometry or NULL. */
RTCGeometry sor_user_geometry_new(RTCDevice device, accel_geom *g);

/* The float nearest x on the far (resp. near) side: Embree's float ray
 * interval must contain the double one. */
static inline float float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

static inline float float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

#endif
