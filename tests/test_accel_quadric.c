/* The quadric user geometries (sphere, disk, cylinder) through accel against
 * closed-form hits the test solves itself in world space for a placed shape
 * (uniform scale R, rotation, translation): same hit or miss, t, point,
 * normal, and the object-space fields (p_obj, n_obj, param, uv). Also: the
 * object-space fields of analytic SOR hits equal sor_intersect's, a triangle
 * hit's barycentrics rebuild its point, and one scene holding all kinds
 * returns the nearest. */
#include <criterion/criterion.h>
#include <string.h>

#include "celadon/accel.h"
#include "support/sor_profiles.h"
#include "test_accel_support.h"

#define RAYS 3000

typedef struct {
    transform4 xf;
    vec3 c, axis; /* world images of the object origin and of +z (unit) */
    double radius;
} placed;

/* Object scaled by (R, R, L) (L = R except for the cylinder's length),
 * rotated about axis by angle, moved to c. */
static placed place(double radius, double length, vec3 axis, double angle_deg, vec3 c)
{
    transform4 S = transform_scale(v3(radius, radius, length)), Rt = transform_rotate(v3_norm(axis), angle_deg),
               T = transform_translate(c);
    transform4 RS = transform_compose(&Rt, &S);
    placed p = {transform_compose(&T, &RS), c, v3_norm(transform_vector(&Rt, v3(0, 0, 1))), radius};
    return p;
}

static accel_t *scene_of(accel_kind kind, const transform4 *xf)
{
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    cr_assert_eq(accel_add_quadric(acc, kind, xf, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    cr_assert_eq(accel_geometry_kind(acc, 0), kind);
    return acc;
}

static void near3(vec3 a, vec3 b, double tol, const char *what, int i)
{
    cr_assert(v3_len(v3_sub(a, b)) <= tol, "ray %d %s: (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", i, what, a.x, a.y,
              a.z, b.x, b.y, b.z);
}

static double angle_of(double y, double x)
{
    double phi = atan2(y, x);
    return phi < 0 ? phi + 2 * M_PI : phi;
}

/* The smaller root of |w + t d|^2 = R^2 above tmin (textbook form), or -1. */
static double sphere_root(vec3 w, vec3 d, double r2, double tmin)
{
    double a = v3_dot(d, d), b = v3_dot(w, d), c = v3_dot(w, w) - r2, disc = b * b - a * c;
    if (disc < 0)
        return -1;
    double t0 = (-b - sqrt(disc)) / a, t1 = (-b + sqrt(disc)) / a;
    return t0 > tmin ? t0 : (t1 > tmin ? t1 : -1);
}

/* Checks accel's hit of ray i (or its miss) against the expected t; the
 * object-space fields are checked by the callers. Returns whether it hit. */
static int check_t(const accel_t *acc, ray3 r, double t_expect, accel_hit *h, int i)
{
    int got = accel_intersect(acc, &r, 0.0, INFINITY, h);
    /* Rays within rounding of the silhouette may go either way. */
    cr_assert_eq(got, t_expect > 0, "ray %d: accel %d, closed form t %.17g", i, got, t_expect);
    if (!got)
        return 0;
    cr_assert(fabs(h->t - t_expect) <= 1e-9 * t_expect, "ray %d: t %.17g vs %.17g", i, h->t, t_expect);
    cr_assert_eq(h->geom_id, 0u);
    cr_assert_eq(h->part, SOR_PART_WALL);
    near3(h->p, ray3_at(r, h->t), 1e-9 * (1 + v3_len(r.o)), "point on the ray", i);
    /* Occlusion agrees: blocked up to just past the hit, free up to just before. */
    cr_assert(accel_occluded(acc, &r, 0.0, h->t * (1 + 1e-6)), "ray %d: not occluded past the hit", i);
    cr_assert(!accel_occluded(acc, &r, 0.0, h->t * (1 - 1e-6)), "ray %d: occluded before the hit", i);
    return 1;
}

/* Skips rays that graze the silhouette (closed form and accel may differ there). */
static int grazing(double disc_rel) { return fabs(disc_rel) < 1e-9; }

Test(accel_quadric, sphere_matches_closed_form, .timeout = 60)
{
    placed pl = place(0.8, 0.8, v3(1, 2, -0.5), 70.0, v3(1, -2, 3));
    accel_t *acc = scene_of(ACCEL_KIND_SPHERE, &pl.xf);
    vec3 e = v3(pl.radius, pl.radius, pl.radius), lo = v3_sub(pl.c, e), hi = v3_add(pl.c, e);
    test_rng rng = {11};
    int hits = 0;
    for (int i = 0; i < RAYS; i++) {
        ray3 r = i % 4 == 3 ? test_ray_inside_box(&rng, lo, hi) : test_ray_toward_box(&rng, lo, hi);
        vec3 w = v3_sub(r.o, pl.c);
        double b = v3_dot(w, r.d), a = v3_dot(r.d, r.d), c = v3_dot(w, w) - pl.radius * pl.radius;
        if (grazing((b * b - a * c) / (a * pl.radius * pl.radius)))
            continue;
        accel_hit h;
        if (!check_t(acc, r, sphere_root(w, r.d, pl.radius * pl.radius, 0.0), &h, i))
            continue;
        hits++;
        vec3 n = v3_scale(v3_sub(h.p, pl.c), 1 / pl.radius);
        near3(h.ng, n, 1e-7, "normal", i);
        near3(h.ns, n, 1e-7, "shading normal", i);
        /* Object space: the unit sphere, so p_obj = n_obj there. */
        near3(h.n_obj, h.p_obj, 1e-9, "object normal", i);
        cr_assert_float_eq(v3_len(h.p_obj), 1.0, 1e-9, "ray %d: |p_obj|", i);
        double theta = acos(h.p_obj.z), phi = angle_of(h.p_obj.y, h.p_obj.x);
        cr_assert_float_eq(h.param[0], theta, 1e-7, "ray %d theta", i);
        cr_assert(fabs(h.param[1] - phi) < 1e-7 || fabs(fabs(h.param[1] - phi) - 2 * M_PI) < 1e-7, "ray %d phi", i);
        cr_assert_float_eq(h.uv.x, h.param[1] / (2 * M_PI), 1e-12, "ray %d u", i);
        cr_assert_float_eq(h.uv.y, h.param[0] / M_PI, 1e-12, "ray %d v", i);
    }
    cr_assert_gt(hits, RAYS / 3, "%d hits", hits);
    accel_destroy(acc);
}

Test(accel_quadric, disk_matches_closed_form, .timeout = 60)
{
    placed pl = place(1.7, 1.7, v3(-1, 0.3, 2), 130.0, v3(-4, 0.5, 2));
    accel_t *acc = scene_of(ACCEL_KIND_DISK, &pl.xf);
    vec3 e = v3(pl.radius, pl.radius, pl.radius), lo = v3_sub(pl.c, e), hi = v3_add(pl.c, e);
    test_rng rng = {12};
    int hits = 0;
    for (int i = 0; i < RAYS; i++) {
        ray3 r = test_ray_toward_box(&rng, lo, hi);
        double dn = v3_dot(r.d, pl.axis), t = dn != 0 ? v3_dot(v3_sub(pl.c, r.o), pl.axis) / dn : -1;
        double rho = t > 0 ? v3_len(v3_sub(ray3_at(r, t), pl.c)) / pl.radius : 2;
        if (fabs(rho - 1) < 1e-9)
            continue;
        accel_hit h;
        if (!check_t(acc, r, rho < 1 ? t : -1, &h, i))
            continue;
        hits++;
        near3(h.ng, pl.axis, 1e-9, "normal", i);
        near3(h.n_obj, v3(0, 0, 1), 0, "object normal", i);
        cr_assert_eq(h.p_obj.z, 0.0, "ray %d: p_obj off the plane", i);
        cr_assert_float_eq(h.param[0], rho, 1e-9, "ray %d radius", i);
        cr_assert_float_eq(h.param[1], angle_of(h.p_obj.y, h.p_obj.x), 1e-12, "ray %d phi", i);
        cr_assert_float_eq(h.uv.x, rho, 1e-9, "ray %d u", i);
        cr_assert_float_eq(h.uv.y, h.param[1] / (2 * M_PI), 1e-12, "ray %d v", i);
    }
    cr_assert_gt(hits, RAYS / 5, "%d hits", hits);
    accel_destroy(acc);
}

Test(accel_quadric, cylinder_matches_closed_form, .timeout = 60)
{
    const double len = 2.5;
    placed pl = place(0.6, len, v3(0.2, 1, 0.7), 50.0, v3(2, 2, -1));
    accel_t *acc = scene_of(ACCEL_KIND_CYLINDER, &pl.xf);
    vec3 far = v3_add(pl.c, v3_scale(pl.axis, len)), e = v3(pl.radius, pl.radius, pl.radius);
    vec3 lo = v3_sub(v3(fmin(pl.c.x, far.x), fmin(pl.c.y, far.y), fmin(pl.c.z, far.z)), e);
    vec3 hi = v3_add(v3(fmax(pl.c.x, far.x), fmax(pl.c.y, far.y), fmax(pl.c.z, far.z)), e);
    test_rng rng = {13};
    int hits = 0, inner = 0;
    for (int i = 0; i < RAYS; i++) {
        ray3 r = i % 4 == 3 ? test_ray_inside_box(&rng, lo, hi) : test_ray_toward_box(&rng, lo, hi);
        /* Components across the axis: |w + t d| = R in the plane normal to it. */
        vec3 w = v3_sub(r.o, pl.c), wp = v3_sub(w, v3_scale(pl.axis, v3_dot(w, pl.axis)));
        vec3 dp = v3_sub(r.d, v3_scale(pl.axis, v3_dot(r.d, pl.axis)));
        double a = v3_dot(dp, dp), b = v3_dot(wp, dp), c = v3_dot(wp, wp) - pl.radius * pl.radius;
        double disc = b * b - a * c, t = -1;
        if (a > 0 && grazing(disc / (a * pl.radius * pl.radius)))
            continue;
        int skip = 0;
        for (int k = 0; k < 2 && a > 0 && disc >= 0 && t < 0; k++) {
            double tk = (-b + (k ? 1 : -1) * sqrt(disc)) / a;
            double z = v3_dot(v3_sub(ray3_at(r, tk), pl.c), pl.axis) / len;
            skip |= tk > 0 && (fabs(z) < 1e-9 || fabs(z - 1) < 1e-9); /* at a rim */
            if (tk > 0 && z >= 0 && z <= 1)
                t = tk;
        }
        if (skip)
            continue;
        accel_hit h;
        if (!check_t(acc, r, t, &h, i))
            continue;
        hits++;
        vec3 q = v3_sub(h.p, pl.c), radial = v3_sub(q, v3_scale(pl.axis, v3_dot(q, pl.axis)));
        near3(h.ng, v3_scale(radial, 1 / pl.radius), 1e-7, "normal", i);
        inner += v3_dot(h.ng, r.d) > 0;
        double z = v3_dot(q, pl.axis) / len;
        cr_assert_float_eq(h.param[0], z, 1e-9, "ray %d z", i);
        cr_assert_float_eq(h.p_obj.z, z, 1e-9, "ray %d p_obj.z", i);
        cr_assert_float_eq(hypot(h.p_obj.x, h.p_obj.y), 1.0, 1e-9, "ray %d p_obj radius", i);
        near3(h.n_obj, v3(h.p_obj.x, h.p_obj.y, 0), 1e-9, "object normal", i);
        cr_assert_float_eq(h.param[1], angle_of(h.p_obj.y, h.p_obj.x), 1e-12, "ray %d phi", i);
        cr_assert_float_eq(h.uv.x, h.param[1] / (2 * M_PI), 1e-12, "ray %d u", i);
        cr_assert_float_eq(h.uv.y, z, 1e-9, "ray %d v", i);
    }
    cr_assert_gt(hits, RAYS / 4, "%d hits", hits);
    cr_assert_gt(inner, RAYS / 50, "%d hits from inside the open tube", inner);
    accel_destroy(acc);
}

Test(accel_quadric, quadric_at_matches_hits)
{
    /* A hit's object-space fields are what accel_quadric_at reports at its point. */
    const accel_kind kinds[3] = {ACCEL_KIND_SPHERE, ACCEL_KIND_DISK, ACCEL_KIND_CYLINDER};
    const ray3 rays[3] = {{v3(0.3, 0.2, 5), v3(0, 0, -1)}, {v3(0.3, -0.4, 2), v3(0, 0.1, -1)},
                          {v3(-3, 0.4, 0.6), v3(1, 0, 0)}};
    for (int k = 0; k < 3; k++) {
        accel_t *acc = scene_of(kinds[k], NULL);
        accel_hit h;
        cr_assert(accel_intersect(acc, &rays[k], 0.0, INFINITY, &h), "kind %d", kinds[k]);
        vec3 n;
        vec2 uv;
        double param[2];
        accel_quadric_at(kinds[k], h.p_obj, &n, &uv, param);
        near3(n, h.n_obj, 1e-15, "normal", k);
        cr_assert(uv.x == h.uv.x && uv.y == h.uv.y && param[0] == h.param[0] && param[1] == h.param[1], "kind %d",
                  kinds[k]);
        cr_assert(v3_dot(h.ng, rays[k].d) < 0, "kind %d: the ray meets the outside first", kinds[k]);
        accel_destroy(acc);
    }
}

Test(accel_quadric, rejects_non_quadric_kinds)
{
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_eq(accel_add_quadric(acc, ACCEL_KIND_MESH, NULL, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "quadric"), "%s", err);
    transform4 flat = transform_scale(v3(1, 0, 1));
    cr_assert_eq(accel_add_quadric(acc, ACCEL_KIND_SPHERE, &flat, err, sizeof err), ACCEL_INVALID_ID);
    accel_destroy(acc);
}

Test(accel_quadric, sor_object_space_fields_match_sor_intersect, .timeout = 60)
{
    /* Placed SOR: p_obj, n_obj and param = (u, phi) are sor_intersect's on the object-space ray. */
    bspline_t c;
    sor_test_profile(0, &c);
    char err[256] = "";
    sor_t *s = sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    transform4 S = transform_scale(v3(1.5, 0.5, 1.5)), T = transform_translate(v3(1, 2, 3));
    transform4 xf = transform_compose(&T, &S), inv = transform_inverse(&xf);
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_eq(accel_add_sor(acc, &c, 1.0, SOR_CAPS_ALL, &xf, NULL, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    vec3 lo, hi;
    sor_bounds(s, &lo, &hi);
    lo = transform_point(&xf, lo), hi = transform_point(&xf, hi);
    test_rng rng = {14};
    int parts[3] = {0, 0, 0};
    for (int i = 0; i < RAYS; i++) {
        ray3 r = test_ray_toward_box(&rng, lo, hi), ro = {transform_point(&inv, r.o), transform_vector(&inv, r.d)};
        sor_hit e;
        accel_hit h;
        int expect = sor_intersect(s, &ro, 0.0, INFINITY, &e);
        cr_assert_eq(accel_intersect(acc, &r, 0.0, INFINITY, &h), expect, "ray %d", i);
        if (!expect)
            continue;
        parts[e.part]++;
        cr_assert_eq(h.part, e.part, "ray %d part", i);
        near3(h.p_obj, e.p, 1e-9, "p_obj", i);
        near3(h.n_obj, e.ng, 1e-9, "n_obj", i);
        cr_assert_float_eq(h.param[0], e.u, 1e-9, "ray %d u", i);
        cr_assert_float_eq(h.param[1], e.phi, 1e-9, "ray %d phi", i);
    }
    cr_assert(parts[SOR_PART_WALL] > RAYS / 4 && parts[SOR_PART_MOUTH] > 0, "wall %d base %d mouth %d",
              parts[SOR_PART_WALL], parts[SOR_PART_BASE], parts[SOR_PART_MOUTH]);
    accel_destroy(acc);
    sor_destroy(s);
    bspline_free(&c);
}

Test(accel_quadric, one_scene_returns_the_nearest_of_all_kinds)
{
    /* Along -z from z = 10: a disk at z = 4, a sphere spanning z in [1, 3], a
     * cylinder across x, a triangle at z = -1; removing nearer ones in turn by tmin. */
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_FAST | ACCEL_BUILD_ROBUST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    float pos[10] = {-5, -5, -1, 5, -5, -1, 0, 5, -1, 0};
    uint32_t tri[3] = {0, 1, 2};
    mesh_t m = {3, 1, pos, NULL, NULL, tri};
    transform4 disk = transform_translate(v3(0, 0, 4)), sphere = transform_translate(v3(0, 0, 2));
    transform4 rot = transform_rotate(v3(0, 1, 0), 90), shift = transform_translate(v3(-2, 0, -0.5)),
               half = transform_scale(v3(0.25, 0.25, 4)), rs = transform_compose(&rot, &half);
    transform4 cyl = transform_compose(&shift, &rs); /* axis along +x through (.., 0, -0.5), radius 0.25 */
    cr_assert_eq(accel_add_mesh(acc, &m, NULL, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_add_quadric(acc, ACCEL_KIND_SPHERE, &sphere, err, sizeof err), 1u, "%s", err);
    cr_assert_eq(accel_add_quadric(acc, ACCEL_KIND_DISK, &disk, err, sizeof err), 2u, "%s", err);
    cr_assert_eq(accel_add_quadric(acc, ACCEL_KIND_CYLINDER, &cyl, err, sizeof err), 3u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    const ray3 r = {v3(0.1, 0.05, 10), v3(0, 0, -1)};
    const double tmin[6] = {0, 6.5, 7.5, 9.3, 10.4, 10.9};
    const unsigned geom[6] = {2, 1, 1, 3, 3, 0};
    const accel_kind kind[6] = {ACCEL_KIND_DISK, ACCEL_KIND_SPHERE, ACCEL_KIND_SPHERE, ACCEL_KIND_CYLINDER,
                                ACCEL_KIND_CYLINDER, ACCEL_KIND_MESH};
    double sz = sqrt(1 - 0.1 * 0.1 - 0.05 * 0.05), cz = sqrt(0.25 * 0.25 - 0.05 * 0.05);
    const double t[6] = {6, 8 - sz, 8 + sz, 10.5 - cz, 10.5 + cz, 11};
    for (int k = 0; k < 6; k++) {
        accel_hit h;
        cr_assert(accel_intersect(acc, &r, tmin[k], INFINITY, &h), "case %d", k);
        cr_assert_eq(h.geom_id, geom[k], "case %d: geometry %u", k, h.geom_id);
        cr_assert_eq(h.kind, kind[k], "case %d", k);
        cr_assert_float_eq(h.t, t[k], 1e-12, "case %d: t %.17g", k, h.t);
        /* Occlusion of triangles is Embree's float test: a margin of float ulps. */
        double margin = kind[k] == ACCEL_KIND_MESH ? 1e-5 * t[k] : 1e-9;
        cr_assert(accel_occluded(acc, &r, tmin[k], t[k] + margin) && !accel_occluded(acc, &r, tmin[k], t[k] - margin),
                  "case %d", k);
    }
    /* The triangle's barycentrics rebuild its object-space point. */
    accel_hit h;
    cr_assert(accel_intersect(acc, &r, 10.9, INFINITY, &h));
    double b1 = h.param[0], b2 = h.param[1], b0 = 1 - b1 - b2;
    vec3 p = v3(b0 * pos[0] + b1 * pos[3] + b2 * pos[6], b0 * pos[1] + b1 * pos[4] + b2 * pos[7], -1);
    near3(h.p_obj, p, 1e-12, "barycentric point", 0);
    near3(h.p_obj, v3(0.1, 0.05, -1), 1e-12, "triangle point", 0);
    near3(h.n_obj, v3(0, 0, 1), 1e-15, "triangle normal", 0);
    accel_destroy(acc);
}
