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

/* World box of the transformed object box, widened so Embree's float ray
 * (rounded from the double one) cannot miss a box the double ray enters. */
static void sor_prim_bounds_cb(const struct RTCBoundsFunctionArguments *args)
{
    const accel_geom *g = args->geometryUserPtr;
    vec3 lo, hi;
    sor_prim_bounds(g->sor, (int)args->primID, &lo, &hi);
    vec3 wlo = v3(INFINITY, INFINITY, INFINITY), whi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int k = 0; k < 8; k++) {
        vec3 c = v3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        vec3 w = transform_point(&g->to_world, c);
        wlo = v3(fmin(wlo.x, w.x), fmin(wlo.y, w.y), fmin(wlo.z, w.z));
        whi = v3(fmax(whi.x, w.x), fmax(whi.y, w.y), fmax(whi.z, w.z));
    }
    double pad = 1e-6 * (v3_len(v3_sub(whi, wlo)) + fmax(v3_len(wlo), v3_len(whi)));
    struct RTCBounds *b = args->bounds_o;
    b->lower_x = float_down(wlo.x - pad);
    b->lower_y = float_down(wlo.y - pad);
    b->lower_z = float_down(wlo.z - pad);
    b->upper_x = float_up(whi.x + pad);
    b->upper_y = float_up(whi.y + pad);
    b->upper_z = float_up(whi.z + pad);
}

/* The caller's ray in this geometry's object space (t is preserved by an affine
 * map), cached per geometry since a ray visits several primitives. */
static const ray3 *object_ray(accel_context *ctx, const accel_geom *g, unsigned geom_id)
{
    if (ctx->obj_geom != geom_id) {
        ctx->obj_ray.o = transform_point(&g->to_object, ctx->ray.o);
        ctx->obj_ray.d = transform_vector(&g->to_object, ctx->ray.d);
        ctx->obj_geom = geom_id;
    }
    return &ctx->obj_ray;
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
    if (!sor_prim_intersect(g->sor, (int)args->primID, object_ray(ctx, g, args->geomID), ctx->tmin, tmax, &h))
        return;
    ctx->tbest = h.t;
    ctx->sor_hit = h;
    ctx->sor_geom = args->geomID;
    rh->ray.tfar = float_up(h.t);
    rh->hit.geomID = args->geomID;
    rh->hit.primID = args->primID;
    rh->hit.instID[0] = args->context->instID[0];
    rh->hit.u = (float)h.uv.x;
    rh->hit.v = (float)h.uv.y;
    rh->hit.Ng_x = (float)h.ng.x;
    rh->hit.Ng_y = (float)h.ng.y;
    rh->hit.Ng_z = (float)h.ng.z;
}

static void sor_occluded_cb(const struct RTCOccludedFunctionNArguments *args)
{
    if (args->N != 1 || !args->valid[0])
        return;
    accel_context *ctx = (accel_context *)args->context;
    const accel_geom *g = args->geometryUserPtr;
    struct RTCRay *ray = (struct RTCRay *)args->ray;
    sor_hit h;
    if (sor_prim_intersect(g->sor, (int)args->primID, object_ray(ctx, g, args->geomID), ctx->tmin, ctx->tbest, &h))
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
