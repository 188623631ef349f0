/* Ray queries against the whole scene: triangle meshes through one Embree
 * scene (float precision), analytic shapes exactly in double precision after
 * a world-bounds slab test; the nearest of both wins. */
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/scene_impl.h"

int scene_trace_build(struct scene *s, char *err, size_t errlen)
{
    int nmesh = 0;
    s->analytic = malloc(sizeof *s->analytic * (size_t)(s->nshapes + 1));
    s->geom_shape = malloc(sizeof *s->geom_shape * (size_t)(s->nshapes + 1));
    if (!s->analytic || !s->geom_shape) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < s->nshapes; i++) {
        if (!s->shapes[i].is_mesh)
            s->analytic[s->nanalytic++] = i;
        else
            nmesh++;
    }
    if (nmesh == 0)
        return 0;
    RTCDevice dev = rtcNewDevice(NULL);
    if (!dev) {
        snprintf(err, errlen, "cannot start Embree (error %d)", (int)rtcGetDeviceError(NULL));
        return -1;
    }
    RTCScene scn = rtcNewScene(dev);
    rtcSetSceneFlags(scn, RTC_SCENE_FLAG_ROBUST);
    s->rtc_device = dev;
    s->rtc_scene = scn;
    for (int i = 0; i < s->nshapes; i++) {
        shape_mesh_data *m = &s->shapes[i].mesh;
        if (!s->shapes[i].is_mesh)
            continue;
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m->pos, 0, 3 * sizeof(float),
                                   (size_t)m->n_verts);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->tri, 0, 3 * sizeof(unsigned),
                                   (size_t)m->n_tris);
        rtcCommitGeometry(g);
        unsigned id = rtcAttachGeometry(scn, g);
        rtcReleaseGeometry(g);
        s->geom_shape[id] = i;
    }
    rtcCommitScene(scn);
    if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) {
        snprintf(err, errlen, "Embree could not build the scene (error %d)", (int)rtcGetDeviceError(dev));
        return -1;
    }
    return 0;
}

void scene_trace_free(struct scene *s)
{
    if (s->rtc_scene)
        rtcReleaseScene(s->rtc_scene);
    if (s->rtc_device)
        rtcReleaseDevice(s->rtc_device);
    free(s->analytic);
    free(s->geom_shape);
}

/* Slab test of the ray against world bounds; narrows [tmin, tmax]. */
static bool box_hit(vec3 lo, vec3 hi, const ray3 *r, double tmin, double tmax)
{
    const double o[3] = {r->o.x, r->o.y, r->o.z}, d[3] = {r->d.x, r->d.y, r->d.z};
    const double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int k = 0; k < 3; k++) {
        double inv = 1.0 / d[k];
        double t0 = (l[k] - o[k]) * inv, t1 = (h[k] - o[k]) * inv;
        if (inv < 0.0) {
            double t = t0;
            t0 = t1, t1 = t;
        }
        if (isnan(t0) || isnan(t1)) /* the ray lies in a slab's boundary plane */
            continue;
        tmin = fmax(tmin, t0);
        tmax = fmin(tmax, t1 * (1.0 + 4.0 * DBL_EPSILON));
        if (tmin > tmax)
            return false;
    }
    return true;
}

static void rtc_ray(struct RTCRay *q, const ray3 *r, double tmin, double tmax)
{
    q->org_x = (float)r->o.x, q->org_y = (float)r->o.y, q->org_z = (float)r->o.z;
    q->dir_x = (float)r->d.x, q->dir_y = (float)r->d.y, q->dir_z = (float)r->d.z;
    q->tnear = (float)tmin;
    q->tfar = tmax < (double)FLT_MAX ? (float)tmax : INFINITY;
    q->time = 0.0f;
    q->mask = ~0u;
    q->id = 0;
    q->flags = 0;
}

bool scene_intersect(const struct scene *s, const ray3 *r, double tmin, double tmax, surface_hit *hit)
{
    bool found = false;
    for (int k = 0; k < s->nanalytic; k++) {
        const shape_t *sh = &s->shapes[s->analytic[k]];
        if (!box_hit(sh->lo, sh->hi, r, tmin, tmax))
            continue;
        if (shape_analytic_intersect(sh, r, tmin, tmax, hit)) {
            tmax = hit->t;
            hit->shape = s->analytic[k];
            found = true;
        }
    }
    if (s->rtc_scene) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        struct RTCRayHit rh;
        rtc_ray(&rh.ray, r, tmin, tmax);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s->rtc_scene, &ctx, &rh);
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID && rh.ray.tfar < tmax) {
            int shape = s->geom_shape[rh.hit.geomID];
            shape_mesh_finish(&s->shapes[shape], (int)rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, hit);
            hit->shape = shape;
            found = true;
        }
    }
    return found;
}

bool scene_occluded(const struct scene *s, const ray3 *r, double tmin, double tmax)
{
    for (int k = 0; k < s->nanalytic; k++) {
        const shape_t *sh = &s->shapes[s->analytic[k]];
        surface_hit h;
        if (box_hit(sh->lo, sh->hi, r, tmin, tmax) && shape_analytic_intersect(sh, r, tmin, tmax, &h))
            return true;
    }
    if (s->rtc_scene) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        struct RTCRay q;
        rtc_ray(&q, r, tmin, tmax);
        rtcOccluded1(s->rtc_scene, &ctx, &q);
        if (q.tfar < 0.0f)
            return true;
    }
    return false;
}
