/* Mitsuba's `sphere` in object space: the unit sphere at the origin (center
 * and radius become part of to_world), traced by accel as ACCEL_KIND_SPHERE
 * (uv, param there). Sampled uniformly by area, and, from a point outside
 * when to_world keeps it a sphere, uniformly in the cone it subtends (its
 * visible cap), which wastes no sample on the far side. */
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

static void sphere_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1.0, -1.0, -1.0), *hi = v3(1.0, 1.0, 1.0);
}

static const shape_analytic_ops sphere_ops = {sphere_add, shape_analytic_local_hit, sphere_sample, sphere_pdf,
                                              sphere_destroy, sphere_tangents, sphere_bounds, NULL, NULL};

/* The cone from ref: 1 - cos of its half-angle (stable for far spheres),
 * or 0 when ref is not outside. */
static double cone_one_minus_cos(const shape_t *sh, vec3 ref, vec3 *to_center, double *dist, double *radius)
{
    vec3 c = transform_point(&sh->to_world, v3(0.0, 0.0, 0.0));
    double r = v3_len(transform_vector(&sh->to_world, v3(1.0, 0.0, 0.0)));
    *to_center = v3_sub(c, ref);
    double d2 = v3_dot(*to_center, *to_center), sin2 = r * r / d2;
    *dist = sqrt(d2), *radius = r;
    if (!(sin2 < 1.0 - 1e-9))
        return 0.0;
    return sin2 / (1.0 + sqrt(1.0 - sin2));
}

static double sphere_cone_pdf(const shape_t *sh, vec3 ref)
{
    vec3 to_c;
    double dist, r, omc = cone_one_minus_cos(sh, ref, &to_c, &dist, &r);
    return omc > 0.0 ? 1.0 / (2.0 * M_PI * omc) : 0.0;
}

/* A direction in the cone, and where it meets the near side: with theta its
 * angle to the centre, the sphere's normal there makes the angle
 * alpha = asin(sin theta / sin theta_max) - theta with the direction back
 * to ref (the law of sines in the triangle ref, centre, point). */
static double sphere_cone_sample(const shape_t *sh, vec3 ref, vec2 u, surface_hit *hit)
{
    vec3 to_c;
    double dist, r, omc = cone_one_minus_cos(sh, ref, &to_c, &dist, &r);
    if (!(omc > 0.0))
        return 0.0;
    double sin2_max = (r / dist) * (r / dist), sin_max = r / dist;
    double t = u.x * omc, cos_t = 1.0 - t, sin2_t = t * (2.0 - t);
    double q = fmin(1.0, sin2_t / sin2_max);
    double cos_a = sin2_t / sin_max + cos_t * sqrt(1.0 - q), sin_a = sqrt(fmax(0.0, 1.0 - cos_a * cos_a));
    double phi = 2.0 * M_PI * u.y;
    frame3 f = frame3_from_normal(v3_scale(to_c, 1.0 / dist));
    vec3 side = v3_add(v3_scale(f.s, cos(phi)), v3_scale(f.t, sin(phi)));
    vec3 n = v3_add(v3_scale(f.n, -cos_a), v3_scale(side, sin_a));
    /* to_world is r times a rotation: back to the unit sphere by its
     * transpose. */
    vec3 m = transform_vector(&sh->to_world, v3(1.0, 0.0, 0.0)), m1 = transform_vector(&sh->to_world, v3(0.0, 1.0, 0.0));
    vec3 m2 = transform_vector(&sh->to_world, v3(0.0, 0.0, 1.0));
    shape_local_hit lh;
    lh.p = v3_norm(v3(v3_dot(m, n), v3_dot(m1, n), v3_dot(m2, n)));
    accel_quadric_at(ACCEL_KIND_SPHERE, lh.p, &lh.n, &lh.uv, lh.param);
    lh.part = 0;
    lh.t = 0.0;
    shape_analytic_finish(sh, &lh, hit);
    return 1.0 / (2.0 * M_PI * omc);
}

static const shape_solid_angle_ops sphere_cone = {sphere_cone_pdf, sphere_cone_sample};

/* Whether the 3x3 part of t is a rotation times a uniform scale. */
static bool is_similarity(const transform4 *t)
{
    vec3 c[3] = {transform_vector(t, v3(1, 0, 0)), transform_vector(t, v3(0, 1, 0)), transform_vector(t, v3(0, 0, 1))};
    double l = v3_dot(c[0], c[0]), tol = 1e-9 * l;
    return fabs(v3_dot(c[1], c[1]) - l) <= tol && fabs(v3_dot(c[2], c[2]) - l) <= tol &&
           fabs(v3_dot(c[0], c[1])) <= tol && fabs(v3_dot(c[0], c[2])) <= tol && fabs(v3_dot(c[1], c[2])) <= tol;
}

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
    sh->solid_angle = is_similarity(&sh->to_world) ? &sphere_cone : NULL;
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
