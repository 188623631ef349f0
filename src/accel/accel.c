/* The scene: an Embree device and scene, one record per geometry, and the
 * double-precision front end of rtcIntersect1 / rtcOccluded1. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/accel_internal.h"
#include "celadon/mesh_rings.h"

static void embree_error(void *user, enum RTCError code, const char *msg)
{
    (void)user;
    fprintf(stderr, "embree: error %d: %s\n", (int)code, msg ? msg : "");
}

accel_t *accel_create(accel_build build, char *err, size_t errlen)
{
    accel_t *acc = calloc(1, sizeof *acc);
    if (!acc) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    acc->device = rtcNewDevice(NULL);
    if (!acc->device) {
        snprintf(err, errlen, "cannot create an Embree device (error %d)", (int)rtcGetDeviceError(NULL));
        free(acc);
        return NULL;
    }
    rtcSetDeviceErrorFunction(acc->device, embree_error, NULL);
    acc->scene = rtcNewScene(acc->device);
    if (!acc->scene) {
        snprintf(err, errlen, "cannot create an Embree scene");
        rtcReleaseDevice(acc->device);
        free(acc);
        return NULL;
    }
    rtcSetSceneBuildQuality(acc->scene,
                            build & ACCEL_BUILD_BEST ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
    if (build & ACCEL_BUILD_ROBUST)
        rtcSetSceneFlags(acc->scene, RTC_SCENE_FLAG_ROBUST);
    return acc;
}

void accel_geom_free(accel_geom *g)
{
    if (!g)
        return;
    free(g->vtx);
    sor_destroy(g->sor);
    free(g);
}

void accel_destroy(accel_t *acc)
{
    if (!acc)
        return;
    rtcReleaseScene(acc->scene);
    rtcReleaseDevice(acc->device);
    for (int i = 0; i < acc->n_geoms; i++)
        accel_geom_free(acc->geoms[i]);
    free(acc->geoms);
    free(acc);
}

/* Finite, affine, and its carried inverse really inverts it (a singular
 * scale, say, leaves infinities there). */
static int transform_valid(const transform4 *t)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(t->m[i][j]) || !isfinite(t->inv[i][j]))
                return 0;
    if (t->m[3][0] != 0 || t->m[3][1] != 0 || t->m[3][2] != 0 || t->m[3][3] != 1)
        return 0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            double p = 0, scale = 0;
            for (int k = 0; k < 3; k++) {
                p += t->m[i][k] * t->inv[k][j];
                scale += fabs(t->m[i][k] * t->inv[k][j]);
            }
            if (!(fabs(p - (i == j)) <= 1e-9 * scale))
                return 0;
        }
    }
    return 1;
}

/* A record with its transforms; NULL with a reason when to_world is unusable. */
accel_geom *accel_geom_new(accel_kind kind, const transform4 *to_world, char *err, size_t errlen)
{
    accel_geom *g = calloc(1, sizeof *g);
    if (!g) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    g->kind = kind;
    g->to_world = to_world ? *to_world : transform_identity();
    if (!transform_valid(&g->to_world)) {
        snprintf(err, errlen, "transform is singular or not finite");
        free(g);
        return NULL;
    }
    g->to_object = transform_inverse(&g->to_world);
    g->placed = to_world != NULL;
    return g;
}

/* Attaches geom (taking our reference) and files g under Embree's id. */
unsigned accel_attach(accel_t *acc, RTCGeometry geom, accel_geom *g, char *err, size_t errlen)
{
    if (acc->n_geoms == acc->cap_geoms) {
        int cap = acc->cap_geoms ? 2 * acc->cap_geoms : 8;
        accel_geom **p = realloc(acc->geoms, (size_t)cap * sizeof *p);
        if (!p) {
            snprintf(err, errlen, "out of memory");
            rtcReleaseGeometry(geom);
            accel_geom_free(g);
            return ACCEL_INVALID_ID;
        }
        acc->geoms = p;
        acc->cap_geoms = cap;
    }
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(acc->scene, geom);
    rtcReleaseGeometry(geom);
    /* Ids are handed out in order from 0 while nothing is detached. */
    if (id != (unsigned)acc->n_geoms) {
        snprintf(err, errlen, "Embree returned geometry id %u, expected %d", id, acc->n_geoms);
        if (id != RTC_INVALID_GEOMETRY_ID)
            rtcDetachGeometry(acc->scene, id);
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    acc->geoms[acc->n_geoms++] = g;
    return id;
}

static unsigned add_triangles(accel_t *acc, const mesh_t *m, accel_kind kind, const transform4 *to_world, char *err,
                              size_t errlen)
{
    if (!m || m->n_verts < 3 || m->n_tris < 1 || !m->pos || !m->tri) {
        snprintf(err, errlen, "mesh has no triangles");
        return ACCEL_INVALID_ID;
    }
    for (size_t i = 0; i < 3 * (size_t)m->n_tris; i++) {
        if (m->tri[i] >= (uint32_t)m->n_verts) {
            snprintf(err, errlen, "mesh triangle %zu refers to vertex %u of %d", i / 3, m->tri[i], m->n_verts);
            return ACCEL_INVALID_ID;
        }
    }
    accel_geom *g = accel_geom_new(kind, to_world, err, errlen);
    if (!g)
        return ACCEL_INVALID_ID;
    g->n_verts = m->n_verts;
    g->n_tris = m->n_tris;
    size_t nv = (size_t)m->n_verts;
    if (!(g->vtx = calloc(nv, sizeof *g->vtx))) {
        snprintf(err, errlen, "out of memory");
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    RTCGeometry geom = rtcNewGeometry(acc->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *pos = geom ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                3 * sizeof(float), (size_t)m->n_verts)
                      : NULL;
    uint32_t *tri = pos ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                  3 * sizeof(uint32_t), (size_t)m->n_tris)
                        : NULL;
    if (!tri) {
        snprintf(err, errlen, "cannot allocate Embree buffers for %d vertices", m->n_verts);
        if (geom)
            rtcReleaseGeometry(geom);
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    for (int i = 0; i < m->n_verts; i++) {
        vec3 p = transform_point(&g->to_world, v3(m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]));
        if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z)) {
            snprintf(err, errlen, "mesh vertex %d is not finite", i);
            rtcReleaseGeometry(geom);
            accel_geom_free(g);
            return ACCEL_INVALID_ID;
        }
        pos[3 * i] = (float)p.x;
        pos[3 * i + 1] = (float)p.y;
        pos[3 * i + 2] = (float)p.z;
    }
    g->has_nrm = m->nrm != NULL;
    g->has_uv = m->uv != NULL;
    for (size_t i = 0; i < nv; i++) {
        memcpy(g->vtx[i].p, m->pos + 3 * i, sizeof g->vtx[i].p);
        if (m->nrm)
            memcpy(g->vtx[i].n, m->nrm + 3 * i, sizeof g->vtx[i].n);
        if (m->uv)
            memcpy(g->vtx[i].uv, m->uv + 2 * i, sizeof g->vtx[i].uv);
    }
    memcpy(tri, m->tri, 3 * sizeof(uint32_t) * (size_t)m->n_tris);
    g->tri = tri;
    return accel_attach(acc, geom, g, err, errlen);
}

unsigned accel_add_mesh(accel_t *acc, const mesh_t *mesh, const transform4 *to_world, char *err, size_t errlen)
{
    return add_triangles(acc, mesh, ACCEL_KIND_MESH, to_world, err, errlen);
}

static unsigned add_sor_analytic(accel_t *acc, const bspline_t *profile, double height, unsigned caps,
                                 const transform4 *to_world, char *err, size_t errlen)
{
    accel_geom *g = accel_geom_new(ACCEL_KIND_SOR_ANALYTIC, to_world, err, errlen);
    if (!g)
        return ACCEL_INVALID_ID;
    g->sor = sor_create(profile, height, caps, err, errlen);
    if (!g->sor) {
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    RTCGeometry geom = sor_user_geometry_new(acc->device, g);
    if (!geom) {
        snprintf(err, errlen, "cannot create an Embree user geometry");
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    return accel_attach(acc, geom, g, err, errlen);
}

static unsigned add_sor_mesh(accel_t *acc, const bspline_t *profile, double height, unsigned caps,
                             const transform4 *to_world, const accel_sor_mode *mode, char *err, size_t errlen)
{
    /* sor_create validates the profile, height and caps the same way for both forms. */
    sor_t *check = sor_create(profile, height, caps, err, errlen);
    if (!check)
        return ACCEL_INVALID_ID;
    sor_destroy(check);
    double *rings = NULL;
    const double *u = mode->u_rings;
    int n = mode->n_rings;
    if (!u) {
        if (!(mode->tol_px > 0) || mesh_rings(profile, NULL, 0, mode->tol_px, &rings, &n) != 0) {
            snprintf(err, errlen, "cannot place mesh rings at curvature tolerance %g px", mode->tol_px);
            return ACCEL_INVALID_ID;
        }
        u = rings;
    }
    unsigned mesh_caps = (caps & SOR_CAP_BASE ? MESH_CAP_BASE : 0u) | (caps & SOR_CAP_MOUTH ? MESH_CAP_MOUTH : 0u);
    mesh_t m;
    int rc = mesh_revolve(profile, u, n, height, mode->segments, mesh_caps, &m);
    free(rings);
    if (rc != 0) {
        snprintf(err, errlen, "cannot revolve the profile (%d rings, %d segments)", n, mode->segments);
        return ACCEL_INVALID_ID;
    }
    unsigned id = add_triangles(acc, &m, ACCEL_KIND_SOR_MESH, to_world, err, errlen);
    mesh_free(&m);
    return id;
}

unsigned accel_add_quadric(accel_t *acc, accel_kind kind, const transform4 *to_world, char *err, size_t errlen)
{
    if (kind != ACCEL_KIND_SPHERE && kind != ACCEL_KIND_DISK && kind != ACCEL_KIND_CYLINDER) {
        snprintf(err, errlen, "geometry kind %d is not a quadric", (int)kind);
        return ACCEL_INVALID_ID;
    }
    accel_geom *g = accel_geom_new(kind, to_world, err, errlen);
    if (!g)
        return ACCEL_INVALID_ID;
    RTCGeometry geom = quadric_user_geometry_new(acc->device, g);
    if (!geom) {
        snprintf(err, errlen, "cannot create an Embree user geometry");
        accel_geom_free(g);
        return ACCEL_INVALID_ID;
    }
    return accel_attach(acc, geom, g, err, errlen);
}

unsigned accel_add_sor(accel_t *acc, const bspline_t *profile, double height, unsigned caps, const transform4 *to_world,
                       const accel_sor_mode *mode, char *err, size_t errlen)
{
    if (!mode || mode->segments == 0)
        return add_sor_analytic(acc, profile, height, caps, to_world, err, errlen);
    if (mode->segments < 3) {
        snprintf(err, errlen, "a meshed SOR needs at least 3 angular segments, got %d", mode->segments);
        return ACCEL_INVALID_ID;
    }
    return add_sor_mesh(acc, profile, height, caps, to_world, mode, err, errlen);
}

int accel_commit(accel_t *acc, char *err, size_t errlen)
{
    rtcCommitScene(acc->scene);
    enum RTCError e = rtcGetDeviceError(acc->device);
    if (e != RTC_ERROR_NONE) {
        snprintf(err, errlen, "Embree scene build failed (error %d)", (int)e);
        return -1;
    }
    return 0;
}

static void context_init(accel_context *ctx, const accel_t *acc, const ray3 *ray, double tmin, double tmax)
{
    rtcInitIntersectContext(&ctx->rtc);
    ctx->acc = acc;
    ctx->ray = *ray;
    ctx->tmin = tmin;
    ctx->tbest = tmax;
    ctx->obj_geom = ACCEL_INVALID_ID;
}

void accel_world_bounds(const accel_geom *g, vec3 lo, vec3 hi, struct RTCBounds *b)
{
    vec3 wlo = v3(INFINITY, INFINITY, INFINITY), whi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int k = 0; k < 8; k++) {
        vec3 c = v3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        vec3 w = transform_point(&g->to_world, c);
        wlo = v3(fmin(wlo.x, w.x), fmin(wlo.y, w.y), fmin(wlo.z, w.z));
        whi = v3(fmax(whi.x, w.x), fmax(whi.y, w.y), fmax(whi.z, w.z));
    }
    double pad = 1e-6 * (v3_len(v3_sub(whi, wlo)) + fmax(v3_len(wlo), v3_len(whi)));
    b->lower_x = float_down(wlo.x - pad);
    b->lower_y = float_down(wlo.y - pad);
    b->lower_z = float_down(wlo.z - pad);
    b->upper_x = float_up(whi.x + pad);
    b->upper_y = float_up(whi.y + pad);
    b->upper_z = float_up(whi.z + pad);
}

void accel_accept_hit(accel_context *ctx, const struct RTCIntersectFunctionNArguments *args, const accel_local_hit *h)
{
    struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit;
    ctx->tbest = h->t;
    ctx->best = *h;
    rh->ray.tfar = float_up(h->t);
    rh->hit.geomID = args->geomID;
    rh->hit.primID = args->primID;
    rh->hit.instID[0] = args->context->instID[0];
    rh->hit.u = (float)h->uv.x;
    rh->hit.v = (float)h->uv.y;
    rh->hit.Ng_x = (float)h->ng.x;
    rh->hit.Ng_y = (float)h->ng.y;
    rh->hit.Ng_z = (float)h->ng.z;
}

static void embree_ray(struct RTCRay *r, const ray3 *ray, double tmin, double tmax)
{
    r->org_x = (float)ray->o.x;
    r->org_y = (float)ray->o.y;
    r->org_z = (float)ray->o.z;
    r->dir_x = (float)ray->d.x;
    r->dir_y = (float)ray->d.y;
    r->dir_z = (float)ray->d.z;
    float tnear = float_down(tmin);
    r->tnear = tnear > 0.0f ? tnear : 0.0f; /* NaN too: fmaxf's 0, without its call */
    r->tfar = float_up(tmax);
    r->time = 0.0f;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

/* Möller–Trumbore in double: the triangle hit of the double ray itself, not
 * Embree's float estimate. Returns 0 when the ray is parallel to the triangle
 * (then Embree's t, u, v stand). */
static int triangle_refine(vec3 a, vec3 b, vec3 c, const ray3 *ray, double *t, double *u, double *v)
{
    vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a);
    vec3 pv = v3_cross(ray->d, e2);
    double det = v3_dot(e1, pv);
    if (det == 0.0 || !isfinite(det))
        return 0;
    vec3 tv = v3_sub(ray->o, a), qv = v3_cross(tv, e1);
    *u = v3_dot(tv, pv) / det;
    *v = v3_dot(ray->d, qv) / det;
    *t = v3_dot(e2, qv) / det;
    return 1;
}

static vec3 f3(const float *a) { return v3(a[0], a[1], a[2]); }

/* Embree found the triangle in world space (float); the hit (t and the
 * barycentrics of the second and third vertex) is recomputed in object
 * space, on the vertices as given, from the double ray mapped there, so a
 * transform costs no precision. */
static void triangle_refined(const accel_geom *g, const struct RTCRayHit *rh, const ray3 *ray, accel_hit *hit)
{
    const uint32_t *t = g->tri + 3 * (size_t)rh->hit.primID;
    vec3 a = f3(g->vtx[t[0]].p), b = f3(g->vtx[t[1]].p), c = f3(g->vtx[t[2]].p);
    ray3 ro = g->placed ? (ray3){transform_point(&g->to_object, ray->o), transform_vector(&g->to_object, ray->d)}
                        : *ray;
    double tt = rh->ray.tfar, bu = rh->hit.u, bv = rh->hit.v;
    triangle_refine(a, b, c, &ro, &tt, &bu, &bv);
    hit->t = tt;
    hit->param[0] = bu;
    hit->param[1] = bv;
}

/* The rest of a triangle hit from its refined barycentrics. */
static void triangle_hit(const accel_geom *g, const struct RTCRayHit *rh, accel_hit *hit)
{
    const uint32_t *t = g->tri + 3 * (size_t)rh->hit.primID;
    const accel_vertex *va = &g->vtx[t[0]], *vb = &g->vtx[t[1]], *vc = &g->vtx[t[2]];
    vec3 a = f3(va->p), b = f3(vb->p), c = f3(vc->p);
    double bu = hit->param[0], bv = hit->param[1], bw = 1.0 - bu - bv;
    hit->p_obj = v3_add(v3_add(v3_scale(a, bw), v3_scale(b, bu)), v3_scale(c, bv));
    hit->p = transform_point(&g->to_world, hit->p_obj);
    /* The counter-clockwise side in object space, carried by A^-T (which keeps
     * it on the same side of the surface even when the transform mirrors). */
    hit->n_obj = v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    hit->ng = world_normal(g, hit->n_obj);
    hit->ns = hit->ng;
    if (g->has_nrm) {
        vec3 n = v3_add(v3_add(v3_scale(f3(va->n), bw), v3_scale(f3(vb->n), bu)), v3_scale(f3(vc->n), bv));
        if (v3_len(n) > 0)
            hit->ns = world_normal(g, n);
    }
    hit->uv = g->has_uv ? v2(bw * va->uv[0] + bu * vb->uv[0] + bv * vc->uv[0],
                             bw * va->uv[1] + bu * vb->uv[1] + bv * vc->uv[1])
                        : v2(bu, bv);
    hit->part = SOR_PART_WALL;
}

static void analytic_hit(const accel_geom *g, const accel_local_hit *h, accel_hit *hit)
{
    hit->t = h->t;
    hit->p = transform_point(&g->to_world, h->p);
    hit->ng = world_normal(g, h->ng);
    hit->ns = world_normal(g, h->ns);
    hit->uv = h->uv;
    hit->part = h->part;
    hit->p_obj = h->p;
    hit->n_obj = h->ng;
    hit->param[0] = h->param[0];
    hit->param[1] = h->param[1];
}

/* Whether Embree takes the ray: it asserts, and so aborts the process, on
 * an origin or a direction beyond FLT_LARGE (1.844e18) or not finite, or a
 * NaN bound (RayK::valid). Scenes keep their shapes well inside
 * (shape_list_commit); a ray that still fails, from a camera placed beyond
 * or a NaN upstream, meets nothing. */
static bool embree_takes(const struct RTCRay *r)
{
    const float large = 1.844e18f;
    return fabsf(r->org_x) <= large && fabsf(r->org_y) <= large && fabsf(r->org_z) <= large &&
           fabsf(r->dir_x) <= large && fabsf(r->dir_y) <= large && fabsf(r->dir_z) <= large && !isnan(r->tnear) &&
           !isnan(r->tfar);
}

static int intersect(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit, bool whole)
{
    accel_context ctx;
    context_init(&ctx, acc, ray, tmin, tmax);
    struct RTCRayHit rh;
    embree_ray(&rh.ray, ray, tmin, tmax);
    if (!embree_takes(&rh.ray)) {
        hit->geom_id = ACCEL_INVALID_ID;
        return 0;
    }
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(acc->scene, &ctx.rtc, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        hit->geom_id = ACCEL_INVALID_ID;
        return 0;
    }
    const accel_geom *g = acc->geoms[rh.hit.geomID];
    hit->geom_id = rh.hit.geomID;
    hit->prim = rh.hit.primID;
    hit->kind = g->kind;
    if (g->kind == ACCEL_KIND_MESH || g->kind == ACCEL_KIND_SOR_MESH) {
        triangle_refined(g, &rh, ray, hit);
        if (whole || g->kind != ACCEL_KIND_MESH)
            triangle_hit(g, &rh, hit);
    } else if (g->kind == ACCEL_KIND_CURVE_LINEAR || g->kind == ACCEL_KIND_CURVE_BSPLINE) {
        accel_curve_hit(&rh, ray, hit);
    } else {
        analytic_hit(g, &ctx.best, hit); /* the last accepted user-geometry hit is this geometry's */
    }
    return 1;
}

int accel_intersect(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit)
{
    return intersect(acc, ray, tmin, tmax, hit, true);
}

int accel_intersect_refined(const accel_t *acc, const ray3 *ray, double tmin, double tmax, accel_hit *hit)
{
    return intersect(acc, ray, tmin, tmax, hit, false);
}

int accel_occluded(const accel_t *acc, const ray3 *ray, double tmin, double tmax)
{
    accel_context ctx;
    context_init(&ctx, acc, ray, tmin, tmax);
    struct RTCRay r;
    embree_ray(&r, ray, tmin, tmax);
    if (!embree_takes(&r))
        return 0;
    rtcOccluded1(acc->scene, &ctx.rtc, &r);
    return r.tfar == -INFINITY;
}

accel_kind accel_geometry_kind(const accel_t *acc, unsigned id)
{
    return id < (unsigned)acc->n_geoms ? acc->geoms[id]->kind : ACCEL_KIND_MESH;
}

const sor_t *accel_geometry_sor(const accel_t *acc, unsigned id)
{
    return id < (unsigned)acc->n_geoms ? acc->geoms[id]->sor : NULL;
}

int accel_geometry_triangles(const accel_t *acc, unsigned id)
{
    return id < (unsigned)acc->n_geoms ? acc->geoms[id]->n_tris : 0;
}

void accel_bounds(const accel_t *acc, vec3 *lo, vec3 *hi)
{
    struct RTCBounds b;
    rtcGetSceneBounds(acc->scene, &b);
    *lo = v3(b.lower_x, b.lower_y, b.lower_z);
    *hi = v3(b.upper_x, b.upper_y, b.upper_z);
}
