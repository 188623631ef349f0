/* The analytic SOR through Embree (user geometry, one primitive per monotone
 * interval and cap) against sor_intersect / sor_occluded called directly on
 * the object-space ray, for every test profile, with and without transforms:
 * same hit or miss, t to 1e-9 relative, same part, same point and normals. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/accel.h"
#include "support/sor_profiles.h"
#include "test_accel_support.h"

#define HEIGHT 1.3
#define RAYS 4000

typedef struct {
    transform4 xf, inv; /* composed from the inverted factors by the test */
    transform4 R;       /* rotation part, for normals: A^-T = R S^-1 */
    vec3 scale;
} placement;

static placement place(vec3 scale, vec3 axis, double angle_deg, vec3 shift)
{
    placement p;
    transform4 S = transform_scale(scale), T = transform_translate(shift);
    p.R = transform_rotate(v3_norm(axis), angle_deg);
    transform4 RS = transform_compose(&p.R, &S);
    p.xf = transform_compose(&T, &RS);
    transform4 Si = transform_scale(v3(1 / scale.x, 1 / scale.y, 1 / scale.z)),
                Ri = transform_rotate(v3_norm(axis), -angle_deg), Ti = transform_translate(v3_neg(shift));
    transform4 RiTi = transform_compose(&Ri, &Ti);
    p.inv = transform_compose(&Si, &RiTi);
    p.scale = scale;
    return p;
}

static vec3 world_normal(const placement *pl, vec3 n)
{
    return v3_norm(transform_vector(&pl->R, v3(n.x / pl->scale.x, n.y / pl->scale.y, n.z / pl->scale.z)));
}

static void world_box(const placement *pl, const sor_t *s, vec3 *lo, vec3 *hi)
{
    vec3 a, b;
    sor_bounds(s, &a, &b);
    *lo = v3(INFINITY, INFINITY, INFINITY), *hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int k = 0; k < 8; k++) {
        vec3 w = transform_point(&pl->xf, v3(k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z));
        *lo = v3(fmin(lo->x, w.x), fmin(lo->y, w.y), fmin(lo->z, w.z));
        *hi = v3(fmax(hi->x, w.x), fmax(hi->y, w.y), fmax(hi->z, w.z));
    }
}

static void near3(vec3 a, vec3 b, double tol, const char *what, const char *name, int i)
{
    cr_assert(v3_len(v3_sub(a, b)) <= tol, "%s ray %d %s: (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", name, i, what,
              a.x, a.y, a.z, b.x, b.y, b.z);
}

/* One ray through both paths over (tmin, inf); returns the hit t or -1. */
static double compare_ray(const accel_t *acc, const sor_t *s, const placement *pl, ray3 r, double tmin,
                          const char *name, int i)
{
    ray3 ro = {transform_point(&pl->inv, r.o), transform_vector(&pl->inv, r.d)};
    sor_hit e;
    accel_hit h;
    int expect = sor_intersect(s, &ro, tmin, INFINITY, &e);
    int got = accel_intersect(acc, &r, tmin, INFINITY, &h);
    cr_assert_eq(got, expect, "%s ray %d (tmin %g): embree %d, direct %d", name, i, tmin, got, expect);
    if (!expect)
        return -1;
    cr_assert_eq(h.geom_id, 0u);
    cr_assert_eq(h.kind, ACCEL_KIND_SOR_ANALYTIC);
    cr_assert(fabs(h.t - e.t) <= 1e-9 * e.t, "%s ray %d: t %.17g vs %.17g", name, i, h.t, e.t);
    cr_assert_eq(h.part, e.part, "%s ray %d: part", name, i);
    double size = 1 + v3_len(r.o);
    near3(h.p, transform_point(&pl->xf, e.p), 1e-9 * size, "point", name, i);
    near3(h.p, ray3_at(r, h.t), 1e-9 * size, "point on the ray", name, i);
    near3(h.ng, world_normal(pl, e.ng), 1e-7, "geometric normal", name, i);
    near3(h.ns, world_normal(pl, e.shading.n), 1e-7, "shading normal", name, i);
    cr_assert_float_eq(h.uv.x, e.uv.x, 1e-9, "%s ray %d uv", name, i);
    cr_assert_float_eq(h.uv.y, e.uv.y, 1e-9, "%s ray %d uv", name, i);
    return e.t;
}

static void check_profiles(const placement *pl, uint64_t seed)
{
    for (int p = 0; p < sor_test_profile_count(); p++) {
        const char *name = sor_test_profile_name(p);
        bspline_t c;
        sor_test_profile(p, &c);
        char err[256] = "";
        sor_t *s = sor_create(&c, HEIGHT, SOR_CAPS_ALL, err, sizeof err);
        cr_assert_not_null(s, "%s: %s", name, err);
        accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
        cr_assert_not_null(acc, "%s", err);
        accel_sor_mode analytic = {0};
        cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, &pl->xf, &analytic, err, sizeof err), 0u, "%s: %s",
                     name, err);
        cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
        cr_assert_eq(accel_geometry_kind(acc, 0), ACCEL_KIND_SOR_ANALYTIC);
        cr_assert_not_null(accel_geometry_sor(acc, 0));
        vec3 lo, hi;
        world_box(pl, s, &lo, &hi);
        test_rng rng = {seed + (uint64_t)p};
        int hits = 0, second = 0;
        for (int i = 0; i < RAYS; i++) {
            ray3 r = i % 4 == 3 ? test_ray_inside_box(&rng, lo, hi) : test_ray_toward_box(&rng, lo, hi);
            double t = compare_ray(acc, s, pl, r, 0.0, name, i);
            ray3 ro = {transform_point(&pl->inv, r.o), transform_vector(&pl->inv, r.d)};
            /* Occlusion over a random range that contains the hit or stops short of it. */
            double tmax = t > 0 ? 2.0 * t * test_rng_uniform(&rng) : INFINITY;
            cr_assert_eq(accel_occluded(acc, &r, 0.0, tmax), sor_occluded(s, &ro, 0.0, tmax),
                         "%s ray %d: occlusion up to %g (hit at %g)", name, i, tmax, t);
            if (t < 0)
                continue;
            hits++;
            /* The next hit along the ray: Embree's float tnear must not lose it. */
            second += compare_ray(acc, s, pl, r, t * (1 + 1e-9), name, i) > 0;
        }
        cr_assert_gt(hits, RAYS / 4, "%s: %d of %d rays hit", name, hits, RAYS);
        cr_assert_gt(second, hits / 2, "%s: %d of %d hits have a second one", name, second, hits);
        accel_destroy(acc);
        sor_destroy(s);
        bspline_free(&c);
    }
}

Test(accel_sor, analytic_matches_direct_untransformed, .timeout = 60)
{
    placement pl = place(v3(1, 1, 1), v3(0, 1, 0), 0.0, v3(0, 0, 0));
    check_profiles(&pl, 1000);
}

Test(accel_sor, analytic_matches_direct_rigid_and_scaled, .timeout = 60)
{
    placement pl = place(v3(0.7, 0.7, 0.7), v3(1, -2, 0.5), 120.0, v3(3, 1, -7));
    check_profiles(&pl, 2000);
}

Test(accel_sor, analytic_matches_direct_nonuniform_scale, .timeout = 60)
{
    placement pl = place(v3(2, 0.5, 1.25), v3(0.3, 0.2, 1), -46.0, v3(-1, 0, 2));
    check_profiles(&pl, 3000);
}

/* Two placed copies and a quad: the nearest of the three, as each alone says. */
Test(accel_sor, nearest_among_instances_and_triangles)
{
    bspline_t c;
    sor_test_profile(2, &c);
    char err[256] = "";
    sor_t *s = sor_create(&c, HEIGHT, SOR_CAPS_ALL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    placement a = place(v3(1, 1, 1), v3(0, 0, 1), 17.0, v3(0.4, 0, 0)),
              b = place(v3(1.2, 1.2, 1.2), v3(1, 0, 0), -11.0, v3(-0.5, 0.2, 0.3));
    mesh_t quad = {.n_verts = 4, .n_tris = 2};
    float pos[13] = {-2, 0.5f, -2, 2, 0.5f, -2, 2, 0.5f, 2, -2, 0.5f, 2, 0};
    uint32_t tri[6] = {0, 2, 1, 0, 3, 2};
    quad.pos = pos, quad.tri = tri;
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    accel_sor_mode analytic = {0};
    cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, &a.xf, &analytic, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, &b.xf, &analytic, err, sizeof err), 1u, "%s", err);
    cr_assert_eq(accel_add_mesh(acc, &quad, NULL, err, sizeof err), 2u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    vec3 lo, hi;
    accel_bounds(acc, &lo, &hi);
    lo.x = lo.z = -1.5, hi.x = hi.z = 1.5; /* around the vessels, not the whole quad */
    test_rng rng = {99};
    int seen[3] = {0, 0, 0};
    for (int i = 0; i < 2000; i++) {
        ray3 r = test_ray_toward_box(&rng, lo, hi);
        double best = INFINITY;
        unsigned who = ACCEL_INVALID_ID;
        const placement *pls[2] = {&a, &b};
        for (unsigned k = 0; k < 2; k++) {
            ray3 ro = {transform_point(&pls[k]->inv, r.o), transform_vector(&pls[k]->inv, r.d)};
            sor_hit e;
            if (sor_intersect(s, &ro, 0, best, &e))
                best = e.t, who = k;
        }
        double tq = (0.5 - r.o.y) / r.d.y;
        vec3 q = ray3_at(r, tq);
        if (tq > 0 && tq < best && fabs(q.x) < 2 && fabs(q.z) < 2)
            best = tq, who = 2;
        accel_hit h;
        int got = accel_intersect(acc, &r, 0, INFINITY, &h);
        cr_assert_eq(got, who != ACCEL_INVALID_ID, "ray %d", i);
        cr_assert_eq(accel_occluded(acc, &r, 0, INFINITY), got, "ray %d", i);
        if (!got)
            continue;
        cr_assert_eq(h.geom_id, who, "ray %d: geometry %u, expected %u", i, h.geom_id, who);
        cr_assert(fabs(h.t - best) <= 1e-9 * best, "ray %d: t %.17g vs %.17g", i, h.t, best);
        seen[who]++;
    }
    for (int k = 0; k < 3; k++)
        cr_assert_gt(seen[k], 50, "geometry %d is nearest for %d rays", k, seen[k]);
    accel_destroy(acc);
    sor_destroy(s);
    bspline_free(&c);
}

Test(accel_sor, rejects_bad_sors)
{
    bspline_t c;
    sor_test_profile(0, &c);
    char err[256];
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    accel_sor_mode two = {.segments = 2, .tol_px = 1e-3}, mesh = {.segments = 64, .tol_px = 1e-3};
    err[0] = 0;
    cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, NULL, &two, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "segments"), "%s", err);
    err[0] = 0;
    cr_assert_eq(accel_add_sor(acc, &c, -1.0, SOR_CAPS_ALL, NULL, &mesh, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert_neq(err[0], 0, "a reason is given");
    err[0] = 0;
    accel_sor_mode no_rings = {.segments = 64};
    cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, NULL, &no_rings, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "tolerance"), "%s", err);
    c.ctrl[0].x = -0.5; /* r < 0 */
    err[0] = 0;
    cr_assert_eq(accel_add_sor(acc, &c, HEIGHT, SOR_CAPS_ALL, NULL, NULL, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert_neq(err[0], 0, "a reason is given");
    accel_destroy(acc);
    bspline_free(&c);
}
