/* Mitsuba's `cylinder` in object space: the open tube of radius 1 around the
 * z axis from z = 0 to z = 1 (p0, p1 and radius become part of to_world),
 * traced by accel as ACCEL_KIND_CYLINDER (uv, param there); sampled
 * uniformly by area. */
#include "render/scene_impl.h"

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

const shape_analytic_ops shape_cylinder_ops = {"cylinder", cylinder_add, shape_analytic_local_hit, cylinder_sample,
                                               cylinder_pdf, cylinder_destroy};
