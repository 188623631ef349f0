/* Mitsuba's `cylinder` in object space: the open tube of radius 1 around the
 * z axis from z = 0 to z = 1 (p0, p1 and radius become part of to_world),
 * traced by accel as ACCEL_KIND_CYLINDER (uv, param there); sampled
 * uniformly by area. */
#include "shapes/shape_impl.h"

static unsigned cylinder_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    (void)data;
    return accel_add_quadric(acc, ACCEL_KIND_CYLINDER, to_world, err, errlen);
}

static void cylinder_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    double phi = 2.0 * M_PI * u.x;
    h->p = v3(cos(phi), sin(phi), u.y);
    accel_quadric_at(ACCEL_KIND_CYLINDER, h->p, &h->n, &h->uv, h->param);
    h->part = 0;
    h->t = 0.0;
    *pdf = 1.0 / (2.0 * M_PI);
}

static double cylinder_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / (2.0 * M_PI);
}

static void cylinder_destroy(void *data) { (void)data; }

/* uv = (phi / 2 pi, z): dp/du = 2 pi (-y, x, 0), dp/dv = +z. */
static void cylinder_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    (void)data;
    *dpdu = v3(-2.0 * M_PI * h->p.y, 2.0 * M_PI * h->p.x, 0.0);
    *dpdv = v3(0.0, 0.0, 1.0);
}

static void cylinder_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1.0, -1.0, 0.0), *hi = v3(1.0, 1.0, 1.0);
}

static const shape_analytic_ops cylinder_ops = {cylinder_add, shape_analytic_local_hit, cylinder_sample, cylinder_pdf,
                                                cylinder_destroy, cylinder_tangents, cylinder_bounds, NULL, NULL};

static int cylinder_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                           char *err, size_t errlen)
{
    (void)opt;
    sh->is_mesh = false;
    sh->ops = &cylinder_ops;
    vec3 p0 = scene_obj_point(o, "p0", v3(0, 0, 0)), p1 = scene_obj_point(o, "p1", v3(0, 0, 1));
    double r = scene_obj_float(o, "radius", 1.0), len = v3_len(v3_sub(p1, p0));
    if (!(r > 0.0) || !(len > 0.0))
        return scene_obj_error(o, err, errlen, "cylinder needs radius > 0 and p0 != p1");
    /* The unit tube around z scaled by r across and len along p1 - p0. */
    frame3 f = frame3_from_normal(v3_scale(v3_sub(p1, p0), 1.0 / len));
    const double rows[16] = {r * f.s.x, r * f.t.x, len * f.n.x, p0.x, r * f.s.y, r * f.t.y, len * f.n.y, p0.y,
                             r * f.s.z, r * f.t.z, len * f.n.z, p0.z, 0, 0, 0, 1};
    transform4 local;
    if (transform_from_rows(rows, &local) != 0)
        return scene_obj_error(o, err, errlen, "degenerate cylinder");
    sh->to_world = transform_compose(to_world, &local);
    return 0;
}

static const scene_param_decl cylinder_params[] = {
    SHAPE_PARAMS_COMMON,
    {"p0", PARAM_POINT, 0, NULL},
    {"p1", PARAM_POINT, 0, NULL},
    {"radius", PARAM_FLOAT, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_cylinder = {
    .decl = {.cls = SCENE_SHAPE, .type = "cylinder", .params = cylinder_params, .children = shape_children},
    .create = cylinder_create,
};
