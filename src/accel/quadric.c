/* Mitsuba's quadrics in their object space (accel.h), intersected exactly in
 * double precision: the sphere and the cylinder solve a quadratic, the disk
 * a plane. */
#include "accel/accel_internal.h"
#include "celadon/polynomial.h"

static double wrap_angle(double phi) { return phi < 0.0 ? phi + 2.0 * M_PI : phi; }

void accel_quadric_at(accel_kind kind, vec3 p, vec3 *n, vec2 *uv, double param[2])
{
    if (kind == ACCEL_KIND_SPHERE) {
        *n = v3_norm(p);
        double phi = wrap_angle(atan2(n->y, n->x));
        double theta = acos(fmax(-1.0, fmin(1.0, n->z)));
        *uv = v2(phi / (2.0 * M_PI), theta / M_PI);
        param[0] = theta;
        param[1] = phi;
    } else if (kind == ACCEL_KIND_DISK) {
        double phi = wrap_angle(atan2(p.y, p.x));
        *n = v3(0.0, 0.0, 1.0);
        *uv = v2(hypot(p.x, p.y), phi / (2.0 * M_PI));
        param[0] = uv->x;
        param[1] = phi;
    } else { /* cylinder */
        double phi = wrap_angle(atan2(p.y, p.x));
        *n = v3(cos(phi), sin(phi), 0.0);
        *uv = v2(phi / (2.0 * M_PI), p.z);
        param[0] = p.z;
        param[1] = phi;
    }
}

/* The nearest t in (tmin, tmax), or 0 for none. */
static double quadric_t(accel_kind kind, const ray3 *r, double tmin, double tmax)
{
    double t[2];
    if (kind == ACCEL_KIND_DISK) {
        if (r->d.z == 0.0)
            return 0.0;
        double td = -r->o.z / r->d.z;
        if (td <= tmin || td >= tmax)
            return 0.0;
        double x = r->o.x + td * r->d.x, y = r->o.y + td * r->d.y;
        return x * x + y * y > 1.0 ? 0.0 : td;
    }
    if (kind == ACCEL_KIND_SPHERE) {
        if (!poly_quadratic_roots(v3_dot(r->d, r->d), v3_dot(r->o, r->d), v3_dot(r->o, r->o) - 1.0, &t[0], &t[1]))
            return 0.0;
        double ts = t[0] > tmin ? t[0] : t[1];
        return ts <= tmin || ts >= tmax ? 0.0 : ts;
    }
    if (!poly_quadratic_roots(r->d.x * r->d.x + r->d.y * r->d.y, r->o.x * r->d.x + r->o.y * r->d.y,
                         r->o.x * r->o.x + r->o.y * r->o.y - 1.0, &t[0], &t[1]))
        return 0.0;
    for (int i = 0; i < 2; i++) {
        double z = r->o.z + t[i] * r->d.z;
        if (t[i] > tmin && t[i] < tmax && z >= 0.0 && z <= 1.0)
            return t[i];
    }
    return 0.0;
}

int quadric_intersect(accel_kind kind, const ray3 *r, double tmin, double tmax, accel_local_hit *h)
{
    double t = quadric_t(kind, r, tmin, tmax);
    if (!(t > tmin)) /* 0 <= tmin means none */
        return 0;
    h->t = t;
    h->p = ray3_at(*r, t);
    if (kind == ACCEL_KIND_DISK)
        h->p.z = 0.0; /* exactly in its plane */
    accel_quadric_at(kind, h->p, &h->ng, &h->uv, h->param);
    h->ns = h->ng;
    h->part = SOR_PART_WALL;
    return 1;
}

void quadric_bounds(accel_kind kind, vec3 *lo, vec3 *hi)
{
    *lo = v3(-1.0, -1.0, kind == ACCEL_KIND_SPHERE ? -1.0 : 0.0);
    *hi = v3(1.0, 1.0, kind == ACCEL_KIND_DISK ? 0.0 : 1.0);
}
