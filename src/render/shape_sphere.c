/* Mitsuba's `sphere` in object space: the unit sphere at the origin (center
 * and radius become part of to_world), traced by accel as ACCEL_KIND_SPHERE
 * (uv, param there); sampled uniformly by area. */
#include "celadon/sampling.h"
#include "render/scene_impl.h"

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

const shape_analytic_ops shape_sphere_ops = {"sphere", sphere_add, shape_analytic_local_hit, sphere_sample, sphere_pdf,
                                             sphere_destroy};
