/* Mitsuba's `cylinder` in object space: the open tube of radius 1 around
 * the z axis from z = 0 to z = 1 (p0, p1 and radius become part of
 * to_world), normal outward, uv = (phi / 2pi, z). */
#include "render/scene_impl.h"
#include "render/shape_quadric.h"

static void cylinder_fill(vec3 p, shape_local_hit *h)
{
    double phi = shape_wrap_angle(atan2(p.y, p.x));
    h->p = p;
    h->n = v3(cos(phi), sin(phi), 0.0);
    h->uv = v2(phi / (2.0 * M_PI), p.z);
    h->part = 0;
    h->param[0] = p.z;
    h->param[1] = phi;
}

static int cylinder_intersect(const void *data, const ray3 *r, double tmin, double tmax, shape_local_hit *h)
{
    (void)data;
    double t[2];
    if (!shape_solve_quadratic(r->d.x * r->d.x + r->d.y * r->d.y, r->o.x * r->d.x + r->o.y * r->d.y,
                               r->o.x * r->o.x + r->o.y * r->o.y - 1.0, &t[0], &t[1]))
        return 0;
    for (int i = 0; i < 2; i++) {
        if (t[i] <= tmin || t[i] >= tmax)
            continue;
        vec3 p = ray3_at(*r, t[i]);
        if (p.z < 0.0 || p.z > 1.0)
            continue;
        h->t = t[i];
        cylinder_fill(p, h);
        return 1;
    }
    return 0;
}

static void cylinder_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    double phi = 2.0 * M_PI * u.x;
    cylinder_fill(v3(cos(phi), sin(phi), u.y), h);
    h->t = 0.0;
    *pdf = 1.0 / (2.0 * M_PI);
}

static double cylinder_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / (2.0 * M_PI);
}

static void cylinder_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1, -1, 0);
    *hi = v3(1, 1, 1);
}

static void cylinder_destroy(void *data) { (void)data; }

const shape_analytic_ops shape_cylinder_ops = {"cylinder", cylinder_intersect, cylinder_sample, cylinder_pdf,
                                               cylinder_bounds, cylinder_destroy};
