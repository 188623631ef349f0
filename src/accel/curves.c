/* Round curves as Embree's own curve geometries (linear cones with spherical
 * joints, cubic B-spline swept spheres): the control points go to Embree in
 * world space; a hit is Embree's (float). As in Mitsuba, a curve is seen
 * only from outside: a ray leaving a point of the surface into the fibre
 * (the `hair` BSDF's transmitted lobes, which stand for the whole walk
 * inside it) passes out through the far side instead of hitting it. */
#include <stdio.h>
#include <string.h>

#include "accel_internal.h"

/* Embree 3 reports hits on the inside of a round curve; drop those whose
 * geometric normal (outward) faces along the ray. The N-wide ray and hit
 * are Embree's SOA layout (rtcore_ray.h; its accessors are C++ only):
 * the ray's dir_x, dir_y, dir_z are rows 4-6 of N floats, the hit's Ng
 * rows 0-2. */
static void cull_inside(const struct RTCFilterFunctionNArguments *args)
{
    const float *ray = (const float *)args->ray, *hit = (const float *)args->hit;
    unsigned n = args->N;
    for (unsigned i = 0; i < n; i++) {
        if (!args->valid[i])
            continue;
        float d = ray[4 * n + i] * hit[i] + ray[5 * n + i] * hit[n + i] + ray[6 * n + i] * hit[2 * n + i];
        if (d > 0.0f)
            args->valid[i] = 0;
    }
}

unsigned accel_add_curves(accel_t *acc, accel_kind kind, const float *points, int n_points, const unsigned *segments,
                          int n_segments, char *err, size_t errlen)
{
    unsigned span = kind == ACCEL_KIND_CURVE_LINEAR ? 2u : 4u;
    if ((kind != ACCEL_KIND_CURVE_LINEAR && kind != ACCEL_KIND_CURVE_BSPLINE) || n_points < (int)span ||
        n_segments < 1) {
        snprintf(err, errlen, "no curve segments");
        return ACCEL_INVALID_ID;
    }
    for (int i = 0; i < n_segments; i++)
        if (segments[i] > (unsigned)n_points - span) {
            snprintf(err, errlen, "curve segment %d starts at point %u of %d", i, segments[i], n_points);
            return ACCEL_INVALID_ID;
        }
    accel_geom *g = accel_geom_new(kind, NULL, err, errlen);
    if (!g)
        return ACCEL_INVALID_ID;
    RTCGeometry geom = rtcNewGeometry(acc->device, kind == ACCEL_KIND_CURVE_LINEAR ? RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE
                                                                                   : RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE);
    float *v = geom ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                              (size_t)n_points)
                    : NULL;
    unsigned *idx = v ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned),
                                                (size_t)n_segments)
                      : NULL;
    if (!idx) {
        snprintf(err, errlen, "cannot allocate Embree buffers for %d curve points", n_points);
        if (geom)
            rtcReleaseGeometry(geom);
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    rtcSetGeometryIntersectFilterFunction(geom, cull_inside);
    rtcSetGeometryOccludedFilterFunction(geom, cull_inside);
    memcpy(v, points, 4 * sizeof(float) * (size_t)n_points);
    memcpy(idx, segments, sizeof(unsigned) * (size_t)n_segments);
    return accel_attach(acc, geom, g, err, errlen);
}

void accel_curve_hit(const struct RTCRayHit *rh, const ray3 *ray, accel_hit *hit)
{
    hit->t = rh->ray.tfar;
    hit->p = hit->p_obj = v3_add(ray->o, v3_scale(ray->d, hit->t));
    vec3 ng = v3(rh->hit.Ng_x, rh->hit.Ng_y, rh->hit.Ng_z);
    hit->ng = hit->ns = hit->n_obj = v3_len(ng) > 0.0 ? v3_norm(ng) : v3_neg(v3_norm(ray->d));
    hit->uv = v2(0.0, rh->hit.u);
    hit->part = SOR_PART_WALL;
    hit->param[0] = rh->hit.u;
    hit->param[1] = 0.0;
}
