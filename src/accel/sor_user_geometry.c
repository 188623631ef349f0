/* The analytic SOR as an Embree user geometry: one primitive per monotone
 * interval of the wall plus the caps (sor_prim_*), so Embree's BVH culls
 * intervals before the exact solver runs.
 *
 * Placement: the callbacks map the ray to object space themselves, in double,
 * rather than putting the SOR under an Embree instance. An instance would hand
 * the callback Embree's float ray, already transformed in float, and the exact
 * solver would then answer for a ray up to ~1e-7 away from the one asked; here
 * the callback reads the caller's double ray from the extended context. A flat
 * scene also saves the second BVH level per SOR. The price is that the BVH
 * bounds the world box of each primitive's transformed object box, slightly
 * looser than an instance's object-space boxes under rotation. */
#include "accel/accel_internal.h"

static void sor_prim_bounds_cb(const struct RTCBoundsFunctionArguments *args)
{
    const accel_geom *g = args->geometryUserPtr;
    vec3 lo, hi;
    sor_prim_bounds(g->sor, (int)args->primID, &lo, &hi);
    accel_world_bounds(g, lo, hi, args->bounds_o);
}

/* Only accel_intersect calls Embree, always through rtcIntersect1 (N = 1) with
 * an accel_context; the float ray's tfar may already be cut by a triangle hit. */
static void sor_intersect_cb(const struct RTCIntersectFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit;
    double tmax = fmin(ctx->tbest, (double)rh->ray.tfar);
    sor_hit h;
    if (!sor_prim_intersect(g->sor, (int)args->primID, accel_object_ray(ctx, g, args->geomID), ctx->tmin, tmax, &h))
        return;
    accel_local_hit lh = {h.t, h.p, h.ng, h.shading.n, h.uv, h.part, {h.u, h.phi}};
    accel_accept_hit(ctx, args, &lh);
}

static void sor_occluded_cb(const struct RTCOccludedFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRay *ray = (struct RTCRay *)args->ray;
    sor_hit h;
    if (sor_prim_intersect(g->sor, (int)args->primID, accel_object_ray(ctx, g, args->geomID), ctx->tmin, ctx->tbest,
                           &h))
        ray->tfar = -INFINITY;
}

RTCGeometry sor_user_geometry_new(RTCDevice device, accel_geom *g)
{
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!geom)
        return NULL;
    rtcSetGeometryUserPrimitiveCount(geom, (unsigned)sor_prim_count(g->sor));
    rtcSetGeometryUserData(geom, g);
    rtcSetGeometryBoundsFunction(geom, sor_prim_bounds_cb, NULL);
    rtcSetGeometryIntersectFunction(geom, sor_intersect_cb);
    rtcSetGeometryOccludedFunction(geom, sor_occluded_cb);
    return geom;
}
