/* Shared between the files of src/accel: the scene record, one record per
 * Embree geometry, and the extended intersect context that carries the double
 * ray into the user-geometry callbacks. */
#ifndef CELADON_ACCEL_INTERNAL_H
#define CELADON_ACCEL_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "celadon/accel.h"

/* One vertex of our copy, attributes side by side: a hit reads the three
 * vertices of one triangle, so interleaving costs it the fewest cache lines. */
typedef struct {
    float p[3], n[3], uv[2];
} accel_vertex;

typedef struct {
    accel_kind kind;
    transform4 to_world, to_object; /* each carries the other as its inverse */
    bool placed;                    /* false: to_world is the identity (none was given) */
    /* Triangles (ACCEL_KIND_MESH, ACCEL_KIND_SOR_MESH): Embree's buffers hold the
     * world-space vertices it traverses (float) and the indices; our copy keeps
     * the mesh as given, in object space, where hits are refined in double. */
    int n_verts, n_tris;
    const uint32_t *tri;
    accel_vertex *vtx;
    int has_nrm, has_uv;
    /* Analytic SOR (ACCEL_KIND_SOR_ANALYTIC). */
    sor_t *sor;
    /* User geometry (ACCEL_KIND_USER): the caller's callbacks and data. */
    const accel_user_ops *user;
    const void *user_data;
} accel_geom;

/* An exact hit on a user geometry (analytic SOR or quadric), object space. */
typedef struct {
    double t;
    vec3 p, ng, ns; /* ng, ns unit */
    vec2 uv;
    sor_part part;
    double param[2];
} accel_local_hit;

/* A new record of kind placed by to_world (NULL: identity); NULL with err
 * when the transform is singular or memory runs out. */
accel_geom *accel_geom_new(accel_kind kind, const transform4 *to_world, char *err, size_t errlen);
void accel_geom_free(accel_geom *g);
/* Attaches geom (taking our reference) and files g under Embree's id, which
 * it returns, or ACCEL_INVALID_ID with err (g freed). */
unsigned accel_attach(accel_t *acc, RTCGeometry geom, accel_geom *g, char *err, size_t errlen);
/* The hit of a ray on a curve geometry, from Embree's (curves.c). */
void accel_curve_hit(const struct RTCRayHit *rh, const ray3 *ray, accel_hit *hit);

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
    accel_local_hit best; /* the last accepted user-geometry hit: the nearest so far */
} accel_context;

/* Creates the Embree user geometry of an analytic SOR whose record is g
 * (g->sor, transforms set). Returns the uncommitted geometry or NULL. */
RTCGeometry sor_user_geometry_new(RTCDevice device, accel_geom *g);
/* The same for a quadric (g->kind one of ACCEL_KIND_SPHERE, _DISK, _CYLINDER). */
RTCGeometry quadric_user_geometry_new(RTCDevice device, accel_geom *g);

/* Exact object-space hit of a quadric with t in (tmin, tmax) (quadric.c). */
int quadric_intersect(accel_kind kind, const ray3 *r, double tmin, double tmax, accel_local_hit *h);
/* The quadric's object-space box. */
void quadric_bounds(accel_kind kind, vec3 *lo, vec3 *hi);

/* Writes to b the world box of g's transformed object box [lo, hi], widened so
 * Embree's float ray (rounded from the double one) cannot miss a box the
 * double ray enters. */
void accel_world_bounds(const accel_geom *g, vec3 lo, vec3 hi, struct RTCBounds *b);

/* The caller's ray in g's object space (t is preserved by an affine map),
 * cached per geometry since a ray visits several primitives. */
static inline const ray3 *accel_object_ray(accel_context *ctx, const accel_geom *g, unsigned geom_id)
{
    if (ctx->obj_geom != geom_id) {
        ctx->obj_ray.o = transform_point(&g->to_object, ctx->ray.o);
        ctx->obj_ray.d = transform_vector(&g->to_object, ctx->ray.d);
        ctx->obj_geom = geom_id;
    }
    return &ctx->obj_ray;
}

/* Records h as the nearest hit so far and tells Embree (float ray cut at h.t). */
void accel_accept_hit(accel_context *ctx, const struct RTCIntersectFunctionNArguments *args,
                      const accel_local_hit *h);

/* The float nearest x on the far (resp. near) side: Embree's float ray
 * interval must contain the double one. */
/* The float next to f toward +infinity (away: -1) for finite or infinite
 * f that is not that end itself: nextafterf's result, without its call
 * into libm (a zero steps to the smallest subnormal of that sign). */
static inline float float_step(float f, int away)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    if (f == 0.0f)
        b = away > 0 ? 1u : 0x80000001u;
    else if ((b >> 31) == (away > 0 ? 1u : 0u))
        b--; /* toward zero */
    else
        b++;
    memcpy(&f, &b, sizeof f);
    return f;
}

static inline float float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? float_step(f, 1) : f;
}

static inline float float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? float_step(f, -1) : f;
}

#endif
