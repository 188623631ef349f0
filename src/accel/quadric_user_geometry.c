/* A quadric (sphere, disk, cylinder) as an Embree user geometry of one
 * primitive, placed like the analytic SOR: the callbacks map the caller's
 * double ray to object space themselves (see sor_user_geometry.c). */
#include "accel/accel_internal.h"

static void quadric_bounds_cb(const struct RTCBoundsFunctionArguments *args)
{
    const accel_geom *g = args->geometryUserPtr;
    vec3 lo, hi;
    quadric_bounds(g->kind, &lo, &hi);
    accel_world_bounds(g, lo, hi, args->bounds_o);
}

static void quadric_intersect_cb(const struct RTCIntersectFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit;
    accel_local_hit h;
    if (quadric_intersect(g->kind, accel_object_ray(ctx, g, args->geomID), ctx->tmin,
                          fmin(ctx->tbest, (double)rh->ray.tfar), &h))
        accel_accept_hit(ctx, args, &h);
}

static void quadric_occluded_cb(const struct RTCOccludedFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRay *ray = (struct RTCRay *)args->ray;
    accel_local_hit h;
    if (quadric_intersect(g->kind, accel_object_ray(ctx, g, args->geomID), ctx->tmin, ctx->tbest, &h))
        ray->tfar = -INFINITY;
}

RTCGeometry quadric_user_geometry_new(RTCDevice device, accel_geom *g)
{
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!geom)
        return NULL;
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, g);
    rtcSetGeometryBoundsFunction(geom, quadric_bounds_cb, NULL);
    rtcSetGeometryIntersectFunction(geom, quadric_intersect_cb);
    rtcSetGeometryOccludedFunction(geom, quadric_occluded_cb);
    return geom;
}
