/* A user geometry (accel_add_user) as an Embree user geometry: the caller's
 * primitives, bounded and intersected by its callbacks in object space.
 * Placed like the analytic SOR: the callbacks map the caller's double ray
 * to object space themselves (see sor_user_geometry.c). */
#include <stdio.h>

#include "accel/accel_internal.h"

static void user_bounds_cb(const struct RTCBoundsFunctionArguments *args)
{
    const accel_geom *g = args->geometryUserPtr;
    vec3 lo, hi;
    g->user->bounds(g->user_data, args->primID, &lo, &hi);
    accel_world_bounds(g, lo, hi, args->bounds_o);
}

static void user_intersect_cb(const struct RTCIntersectFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit;
    accel_user_hit h;
    if (!g->user->intersect(g->user_data, args->primID, accel_object_ray(ctx, g, args->geomID), ctx->tmin,
                            fmin(ctx->tbest, (double)rh->ray.tfar), &h))
        return;
    accel_local_hit lh = {h.t, h.p, h.n, h.n, h.uv, SOR_PART_WALL, {h.param[0], h.param[1]}};
    accel_accept_hit(ctx, args, &lh);
}

static void user_occluded_cb(const struct RTCOccludedFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRay *ray = (struct RTCRay *)args->ray;
    accel_user_hit h;
    if (g->user->intersect(g->user_data, args->primID, accel_object_ray(ctx, g, args->geomID), ctx->tmin, ctx->tbest,
                           &h))
        ray->tfar = -INFINITY;
}

unsigned accel_add_user(accel_t *acc, const accel_user_ops *ops, const void *data, unsigned n_prims,
                        const transform4 *to_world, char *err, size_t errlen)
{
    if (!ops || !ops->bounds || !ops->intersect || n_prims == 0) {
        snprintf(err, errlen, "a user geometry needs bounds, intersect and at least one primitive");
        return ACCEL_INVALID_ID;
    }
    accel_geom *g = accel_geom_new(ACCEL_KIND_USER, to_world, err, errlen);
    if (!g)
        return ACCEL_INVALID_ID;
    g->user = ops;
    g->user_data = data;
    RTCGeometry geom = rtcNewGeometry(acc->device, RTC_GEOMETRY_TYPE_USER);
    if (!geom) {
        snprintf(err, errlen, "cannot create an Embree user geometry");
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    rtcSetGeometryUserPrimitiveCount(geom, n_prims);
    rtcSetGeometryUserData(geom, g);
    rtcSetGeometryBoundsFunction(geom, user_bounds_cb, NULL);
    rtcSetGeometryIntersectFunction(geom, user_intersect_cb);
    rtcSetGeometryOccludedFunction(geom, user_occluded_cb);
    return accel_attach(acc, geom, g, err, errlen);
}
