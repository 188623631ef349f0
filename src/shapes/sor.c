/* celadon's `sor` shape: the surface of revolution of a profile.json,
 * `height` high (the rim at y = height), the base closed and the mouth too
 * unless `caps` is false. Analytic by default: traced by accel as its SOR
 * user geometry (the exact intersector of sor.h in object space), plus
 * sampling by area for area emitters; under --geometry mesh:N revolved into
 * N angular segments instead. The wall's area element is
 * dA = s^2 r(u) |C'(u)| du dphi (s the profile scale): u is drawn from a
 * tabulated piecewise-constant CDF of r(u) |C'(u)|, phi uniformly; the caps
 * are discs. A part is chosen with probability proportional to its area.
 * Texture uv = (u, 1 - v) of the texture convention (docs/conventions.md):
 * the image's top row is the rim, as for the exported meshes read with
 * Mitsuba's flip_tex_coords. */
#include <stdio.h>
#include <stdlib.h>

#include <string.h>

#include "celadon/mesh.h"
#include "celadon/mesh_rings.h"
#include "celadon/profile.h"
#include "celadon/sor.h"
#include "shapes/shape_impl.h"

enum { SOR_TABLE = 1024 };
/* The most triangles one meshed SOR may have: 2^25, about 4 GB with
 * Embree's BVH (measured: 7 GB for 55 M). With the rings refined with N
 * (mesh_rings.h) a vessel of ~2000 rings reaches it near N = 8000. */
enum { SOR_MESH_MAX_TRIANGLES = 1 << 25 };

typedef struct {
    bspline_t curve;       /* profile, pixels */
    unsigned caps;         /* SOR_CAP_* */
    double scale;          /* object units per pixel */
    double height;
    distribution1d wall_u; /* over u in [0,1) */
    double part_prob[3];   /* wall, base, mouth */
    double cap_radius[3];  /* object-space radius of the base and mouth discs */
} sor_shape;

static vec2 sor_tex_uv(double phi, double v)
{
    double tu = phi <= M_PI ? 1.0 - phi / M_PI : phi / M_PI - 1.0;
    return v2(tu, 1.0 - v);
}

static void *sor_shape_create(const char *profile_path, double height, bool caps, char *err, size_t errlen)
{
    profile_t prof;
    char why[512];
    if (profile_read_json(profile_path, &prof, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return NULL;
    }
    sor_shape *s = calloc(1, sizeof *s);
    unsigned mask = SOR_CAP_BASE | (caps ? SOR_CAP_MOUTH : 0u);
    const double *domains;
    int n_domains;
    if (!s || bspline_copy(&s->curve, profile_shape(&prof, &domains, &n_domains)) != 0) { /* meridian if any */
        snprintf(err, errlen, "out of memory");
        free(s);
        profile_free(&prof);
        return NULL;
    }
    profile_free(&prof);
    /* sor_create validates the profile here, where the error names the shape;
     * accel builds the SOR traced. */
    sor_t *check = sor_create(&s->curve, height, mask, why, sizeof why);
    if (!check) {
        snprintf(err, errlen, "%s", why);
        bspline_free(&s->curve);
        free(s);
        return NULL;
    }
    s->scale = sor_profile_scale(check);
    sor_destroy(check);
    s->caps = mask;
    s->height = height;
    double f[SOR_TABLE], wall = 0.0;
    for (int i = 0; i < SOR_TABLE; i++) {
        vec2 d[2];
        bspline_eval_derivs(&s->curve, (i + 0.5) / SOR_TABLE, 1, d);
        f[i] = fmax(d[0].x, 0.0) * v2_len(d[1]);
        wall += f[i] / SOR_TABLE;
    }
    double area[3];
    area[0] = 2.0 * M_PI * s->scale * s->scale * wall;
    s->cap_radius[0] = 0.0;
    s->cap_radius[SOR_PART_BASE] = s->scale * fmax(bspline_eval(&s->curve, 0.0).x, 0.0);
    s->cap_radius[SOR_PART_MOUTH] = caps ? s->scale * fmax(bspline_eval(&s->curve, 1.0).x, 0.0) : 0.0;
    area[1] = M_PI * s->cap_radius[1] * s->cap_radius[1];
    area[2] = M_PI * s->cap_radius[2] * s->cap_radius[2];
    double total = area[0] + area[1] + area[2];
    if (distribution1d_init(&s->wall_u, f, SOR_TABLE) != 0 || !(total > 0.0)) {
        snprintf(err, errlen, "profile has no area");
        bspline_free(&s->curve);
        distribution1d_free(&s->wall_u);
        free(s);
        return NULL;
    }
    for (int i = 0; i < 3; i++)
        s->part_prob[i] = area[i] / total;
    return s;
}

static unsigned sor_shape_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    const sor_shape *s = data;
    return accel_add_sor(acc, &s->curve, s->height, s->caps, to_world, NULL, err, errlen);
}

/* accel's SOR hit: param = (u, phi), uv of docs/conventions.md, flipped in v here. */
static void sor_shape_local_hit(const void *data, const accel_hit *ah, shape_local_hit *h)
{
    shape_analytic_local_hit(data, ah, h);
    h->uv.y = 1.0 - h->uv.y;
}

/* Density per object area of a wall point at profile parameter u. */
static double wall_pdf(const sor_shape *s, double u)
{
    vec2 d[2];
    bspline_eval_derivs(&s->curve, u, 1, d);
    double jac = s->scale * s->scale * d[0].x * v2_len(d[1]) * 2.0 * M_PI;
    return jac > 0.0 ? s->part_prob[0] * distribution1d_pdf(&s->wall_u, fmin(u, 1.0 - 1e-12)) / jac : 0.0;
}

static double sor_shape_pdf(const void *data, const shape_local_hit *h)
{
    const sor_shape *s = data;
    if (h->part == SOR_PART_WALL)
        return wall_pdf(s, h->param[0]);
    double rad = s->cap_radius[h->part];
    return rad > 0.0 ? s->part_prob[h->part] / (M_PI * rad * rad) : 0.0;
}

static void sor_shape_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    const sor_shape *s = data;
    double uz = u.z;
    int part = uz < s->part_prob[0] ? 0 : (uz < s->part_prob[0] + s->part_prob[1] ? 1 : 2);
    if (s->part_prob[part] <= 0.0) /* a zero-area part is never chosen; guard the u = boundary case */
        part = 0;
    h->t = 0.0;
    h->part = part;
    if (part == SOR_PART_WALL) {
        double cell_pdf;
        int cell;
        double pu = distribution1d_sample_continuous(&s->wall_u, u.x, &cell_pdf, &cell);
        double phi = 2.0 * M_PI * u.y;
        vec2 d[2];
        bspline_eval_derivs(&s->curve, pu, 1, d);
        double c = cos(phi), sn = sin(phi);
        h->p = v3(s->scale * d[0].x * c, s->scale * d[0].y, s->scale * d[0].x * sn);
        h->n = v3_norm(v3(d[1].y * c, -d[1].x, d[1].y * sn));
        h->uv = sor_tex_uv(phi, d[0].y * s->scale / s->height);
        h->param[0] = pu;
        h->param[1] = phi;
        *pdf = wall_pdf(s, pu);
        return;
    }
    vec2 q = warp_square_to_concentric_disk(v2(u.x, u.y));
    double rad = s->cap_radius[part], y = part == SOR_PART_BASE ? 0.0 : s->height;
    double phi = atan2(q.y, q.x);
    phi = phi < 0.0 ? phi + 2.0 * M_PI : phi;
    h->p = v3(rad * q.x, y, rad * q.y);
    h->n = v3(0.0, part == SOR_PART_BASE ? -1.0 : 1.0, 0.0);
    h->uv = sor_tex_uv(phi, part == SOR_PART_BASE ? 0.0 : 1.0);
    h->param[0] = part == SOR_PART_BASE ? 0.0 : 1.0;
    h->param[1] = phi;
    *pdf = s->part_prob[part] / (M_PI * rad * rad);
}

static void sor_shape_destroy(void *data)
{
    sor_shape *s = data;
    if (!s)
        return;
    bspline_free(&s->curve);
    distribution1d_free(&s->wall_u);
    free(s);
}

/* Texture u runs with the angle (u = 1 - phi / pi on [0, pi], phi / pi - 1
 * beyond), so dp/du = -/+ pi dp/dphi; texture v = 1 - y / height, so dp/dv
 * = -height dp/dy along the meridian, whose direction m is the one
 * perpendicular to the normal and to dp/dphi (dp/dy = m / m.y, bounded
 * where the wall turns horizontal). On the caps, v is constant: dp/dv is
 * taken along the normal x dp/du. */
static void sor_shape_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    const sor_shape *s = data;
    double phi = h->param[1];
    vec3 dphi = v3(-h->p.z, 0.0, h->p.x); /* dp/dphi: (-r sin phi, 0, r cos phi) */
    *dpdu = v3_scale(dphi, phi <= M_PI ? -M_PI : M_PI);
    vec3 m = v3_norm(v3_cross(dphi, h->n));
    if (h->part != SOR_PART_WALL || v3_len(dphi) == 0.0) {
        *dpdv = v3_cross(h->n, *dpdu);
        return;
    }
    if (m.y < 0.0)
        m = v3_neg(m);
    *dpdv = v3_scale(m, -s->height / fmax(m.y, 1e-3));
}

/* The control polygon holds the B-spline (its convex hull property): the
 * widest control point bounds the radius, the lowest and highest the
 * height. */
static void sor_shape_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    const sor_shape *s = data;
    double r = 0.0, y0 = INFINITY, y1 = -INFINITY;
    for (int i = 0; i < s->curve.n_ctrl; i++) {
        r = fmax(r, fabs(s->curve.ctrl[i].x));
        y0 = fmin(y0, s->curve.ctrl[i].y), y1 = fmax(y1, s->curve.ctrl[i].y);
    }
    r *= s->scale;
    *lo = v3(-r, s->scale * y0, -r), *hi = v3(r, s->scale * y1, r);
}

static const shape_analytic_ops sor_ops = {sor_shape_add, sor_shape_local_hit, sor_shape_sample, sor_shape_pdf,
                                           sor_shape_destroy, sor_shape_tangents, sor_shape_bounds, NULL, NULL};

static int sor_mesh(const char *profile_path, double height, bool caps, int segments, shape_mesh_data *m, char *err,
                    size_t errlen)
{
    profile_t prof;
    char why[512];
    if (profile_read_json(profile_path, &prof, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    /* Rings at the profile's curvature domains, refined with the segments so
     * the profile chord error shrinks like the angular one (mesh_rings.h). */
    double *rings = NULL;
    int n_rings = 0;
    const double *domains;
    int n_domains;
    const bspline_t *shape = profile_shape(&prof, &domains, &n_domains); /* the meridian when there is one */
    if (mesh_rings(shape, domains, n_domains, mesh_ring_tolerance(shape, segments), &rings, &n_rings) != 0) {
        snprintf(err, errlen, "cannot place mesh rings for %d segments", segments);
        profile_free(&prof);
        return -1;
    }
    double tris = 2.0 * segments * (n_rings + 1);
    if (tris > SOR_MESH_MAX_TRIANGLES) {
        snprintf(err, errlen, "%d segments x %d rings would make %.3g triangles (at most %d); use fewer segments",
                 segments, n_rings, tris, SOR_MESH_MAX_TRIANGLES);
        free(rings);
        profile_free(&prof);
        return -1;
    }
    mesh_t mesh;
    unsigned mask = MESH_CAP_BASE | (caps ? MESH_CAP_MOUTH : 0u);
    int rc = mesh_revolve(shape, rings, n_rings, height, segments, mask, &mesh);
    free(rings);
    profile_free(&prof);
    if (rc != 0) {
        snprintf(err, errlen, "cannot revolve the profile into %d segments", segments);
        return -1;
    }
    memset(m, 0, sizeof *m);
    m->n_verts = mesh.n_verts;
    m->n_tris = mesh.n_tris;
    m->pos = mesh.pos;
    m->nrm = mesh.nrm;
    m->uv = mesh.uv;
    m->tri = mesh.tri;
    for (int i = 0; i < m->n_verts; i++)
        m->uv[2 * i + 1] = 1.0f - m->uv[2 * i + 1];
    return 0;
}

static int sor_plugin_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                      size_t errlen)
{
    const char *file = scene_obj_string(o, "filename", NULL);
    double height = scene_obj_float(o, "height", 1.0);
    bool caps = scene_obj_bool(o, "caps", true);
    if (!(height > 0.0))
        return scene_obj_error(o, err, errlen, "sor height must be > 0");
    char why[600] = "";
    int rc;
    if (opt->mesh_segments > 0) {
        rc = sor_mesh(file, height, caps, opt->mesh_segments, &sh->mesh, why, sizeof why);
    } else {
        sh->is_mesh = false;
        sh->ops = &sor_ops;
        sh->data = sor_shape_create(file, height, caps, why, sizeof why);
        sh->to_world = *to_world;
        rc = sh->data ? 0 : -1;
    }
    if (rc != 0)
        return scene_obj_error(o, err, errlen, "<shape type=\"%s\">: %s", o->type, why);
    return 0;
}

static const scene_param_decl sor_params[] = {
    SHAPE_PARAMS_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"height", PARAM_FLOAT, 0, NULL},
    {"caps", PARAM_BOOL, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_sor = {
    .decl = {.cls = SCENE_SHAPE, .type = "sor", .params = sor_params, .children = shape_children},
    .create = sor_plugin_create,
};
