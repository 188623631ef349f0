/* Round curves as Embree's own curve geometries (linear cones with spherical
 * joints, cubic B-spline swept spheres): the control points go to Embree in
 * world space; a hit is Embree's (float). */
#include <stdio.h>
#include <string.h>

#include "accel_internal.h"

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
