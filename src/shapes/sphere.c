/* Mitsuba's `sphere` in object space: the unit sphere at the origin (center
 * and radius become part of to_world), traced by accel as ACCEL_KIND_SPHERE
 * (uv, param there); sampled uniformly by area. */
#include "shapes/shape_impl.h"

static unsigned sphere_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    (void)data;
    return accel_add_quadric(acc, ACCEL_KIND_SPHERE, to_world, err, errlen);
}

static void sphere_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    h->p = warp_square_to_uniform_sphere(v2(u.x, u.y));
    accel_quadric_at(ACCEL_KIND_SPHERE, h->p, &h->n, &h->uv, h->param);
    h->part = 0;
    h->t = 0.0;
    *pdf = 1.0 / (4.0 * M_PI);
}

static double sphere_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / (4.0 * M_PI);
}

static void sphere_destroy(void *data) { (void)data; }

/* uv = (phi / 2 pi, theta / pi): dp/du = 2 pi (-y, x, 0), dp/dv = pi dp/dtheta. */
static void sphere_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    (void)data;
    double phi = h->param[1], theta = h->param[0];
    *dpdu = v3(-2.0 * M_PI * h->p.y, 2.0 * M_PI * h->p.x, 0.0);
    *dpdv = v3_scale(v3(cos(theta) * cos(phi), cos(theta) * sin(phi), -sin(theta)), M_PI);
}

static const shape_analytic_ops sphere_ops = {sphere_add, shape_analytic_local_hit, sphere_sample, sphere_pdf,
                                             sphere_destroy, sphere_tangents};

static int sphere_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                         size_t errlen)
{
    (void)opt;
    sh->is_mesh = false;
    sh->ops = &sphere_ops;
    double r = scene_obj_float(o, "radius", 1.0);
    if (!(r > 0.0))
        return scene_obj_error(o, err, errlen, "sphere radius must be > 0");
    transform4 t = transform_translate(scene_obj_point(o, "center", v3(0, 0, 0)));
    transform4 sc = transform_scale(v3(r, r, r));
    transform4 local = transform_compose(&t, &sc);
    sh->to_world = transform_compose(to_world, &local);
    return 0;
}

static const scene_param_decl sphere_params[] = {
    SHAPE_PARAMS_COMMON,
    {"center", PARAM_POINT, 0, NULL},
    {"radius", PARAM_FLOAT, 0, NULL},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_sphere = {
    .decl = {.cls = SCENE_SHAPE, .type = "sphere", .params = sphere_params, .children = shape_children},
    .create = sphere_create,
};
