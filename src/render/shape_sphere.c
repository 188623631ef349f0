/* Mitsuba's `sphere` in object space: the unit sphere at the origin (center
 * and radius become part of to_world). uv = (phi / 2pi, theta / pi) with
 * theta from +z, as Mitsuba. */
#include "celadon/sampling.h"
#include "render/scene_impl.h"
#include "render/shape_quadric.h"

static void sphere_fill(vec3 p, shape_local_hit *h)
{
    h->p = p;
    h->n = v3_norm(p);
    double phi = shape_wrap_angle(atan2(h->n.y, h->n.x));
    double theta = acos(fmax(-1.0, fmin(1.0, h->n.z)));
    h->uv = v2(phi / (2.0 * M_PI), theta / M_PI);
    h->part = 0;
    h->param[0] = theta;
    h->param[1] = phi;
}

static int sphere_intersect(const void *data, const ray3 *r, double tmin, double tmax, shape_local_hit *h)
{
    (void)data;
    double t0, t1;
    if (!shape_solve_quadratic(v3_dot(r->d, r->d), v3_dot(r->o, r->d), v3_dot(r->o, r->o) - 1.0, &t0, &t1))
        return 0;
    double t = t0 > tmin ? t0 : t1;
    if (t <= tmin || t >= tmax)
        return 0;
    h->t = t;
    sphere_fill(ray3_at(*r, t), h);
    return 1;
}

static void sphere_sample(const void *data, vec3 u, shape_local_hit *h, double *pdf)
{
    (void)data;
    sphere_fill(warp_square_to_uniform_sphere(v2(u.x, u.y)), h);
    h->t = 0.0;
    *pdf = 1.0 / (4.0 * M_PI);
}

static double sphere_pdf(const void *data, const shape_local_hit *h)
{
    (void)data;
    (void)h;
    return 1.0 / (4.0 * M_PI);
}

static void sphere_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(-1, -1, -1);
    *hi = v3(1, 1, 1);
}

static void sphere_destroy(void *data) { (void)data; }

const shape_analytic_ops shape_sphere_ops = {"sphere", sphere_intersect, sphere_sample, sphere_pdf, sphere_bounds,
                                             sphere_destroy};
