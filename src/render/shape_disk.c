/* Mitsuba's `disk` in object space: the unit disk in the z = 0 plane,
 * normal +z, uv = (radius, phi / 2pi). */
#include "celadon/sampling.h"
#include "render/scene_impl.h"
#include "render/shape_quadric.h"

static void disk_fill(double x, double y, shape_local_hit *h)
{
    h->p = v3(x, y, 0.0);
    h->n = v3(0.0, 0.0, 1.0);
    double phi = shape_wrap_angle(atan2(y, x));
    h->uv = v2(hypot(x, y), phi / (2.0 * M_PI));
    h->part = 0;
    h->param[0] = h->uv.x;
    h->param[1] = phi;
}

static int disk_intersect(const void *data, const ray3 *r, double tmin, double tmax, shape_local_hit *h)
{
    (void)data;
    if (r->d.z == 0.0)
        return 0;
    double t = -r->o.z / r->d.z;
    if (t <= tmin || t >= tmax)
        return 0;
    double x = r->o.x + t * r->d.x, y = r->o.y + t * r->d.y;
    if (x * x + y * y > 1.0)
        return 0;
    h->t = t;
    disk_fill(x, y, h);
    return 1;
}

static void disk_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    vec2 p = warp_square_to_concentric_disk(v2(u.x, u.y));
    disk_fill(p.x, p.y, h);
    h->t = 0.0;
    *pdf = 1.0 / M_PI;
}

static double disk_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / M_PI;
}

static void disk_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1, -1, 0);
    *hi = v3(1, 1, 0);
}

static void disk_destroy(void *data) { (void)data; }

const shape_analytic_ops shape_disk_ops = {"disk", disk_intersect, disk_sample, disk_pdf, disk_bounds, disk_destroy};
