/* Mitsuba's `disk` in object space: the unit disk in the z = 0 plane, normal
 * +z, traced by accel as ACCEL_KIND_DISK (uv, param there); sampled
 * uniformly by area. */
#include "shapes/shape_impl.h"

static unsigned disk_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    (void)data;
    return accel_add_quadric(acc, ACCEL_KIND_DISK, to_world, err, errlen);
}

static void disk_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    vec2 p = warp_square_to_concentric_disk(v2(u.x, u.y));
    h->p = v3(p.x, p.y, 0.0);
    accel_quadric_at(ACCEL_KIND_DISK, h->p, &h->n, &h->uv, h->param);
    h->part = 0;
    h->t = 0.0;
    *pdf = 1.0 / M_PI;
}

static double disk_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / M_PI;
}

static void disk_destroy(void *data) { (void)data; }

/* uv = (r, phi / 2 pi): dp/du the radial direction, dp/dv = 2 pi (-y, x, 0). */
static void disk_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    (void)data;
    double phi = h->param[1];
    *dpdu = v3(cos(phi), sin(phi), 0.0);
    *dpdv = v3(-2.0 * M_PI * h->p.y, 2.0 * M_PI * h->p.x, 0.0);
}

static void disk_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1.0, -1.0, 0.0), *hi = v3(1.0, 1.0, 0.0);
}

static bool disk_flat_normal(const void *data, vec3 *n)
{
    (void)data;
    *n = v3(0.0, 0.0, 1.0);
    return true;
}

static const shape_analytic_ops disk_ops = {disk_add, shape_analytic_local_hit, disk_sample, disk_pdf,
                                            disk_destroy, disk_tangents, disk_bounds, disk_flat_normal, NULL};

static int disk_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                       size_t errlen)
{
    (void)o, (void)opt, (void)err, (void)errlen;
    sh->is_mesh = false;
    sh->ops = &disk_ops;
    transform4 local = transform_identity();
    sh->to_world = transform_compose(to_world, &local);
    return 0;
}

static const scene_param_decl disk_params[] = {SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_disk = {
    .decl = {.cls = SCENE_SHAPE, .type = "disk", .params = disk_params, .children = shape_children},
    .create = disk_create,
};
