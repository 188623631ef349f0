/* The cases where lathe intersectors are known to fail (speckles, holes):
 * each has its own test, checked against geometry the test knows exactly or
 * against the brute-force reference. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "celadon/sor.h"
#include "support/sor_profiles.h"
#include "support/sor_reference.h"

/* Compares sor_intersect with the reference on one ray; returns 1 if they
 * agree (or the reference calls it ambiguous: *amb is incremented). */
static int agrees(const sor_t *s, const sor_ref *ref, ray3 ray, int *amb)
{
    long double tr;
    int rr = sor_ref_intersect(ref, &ray, 0.0, INFINITY, &tr);
    if (rr == SOR_REF_AMBIGUOUS) {
        ++*amb;
        return 1;
    }
    sor_hit h;
    int rs = sor_intersect(s, &ray, 0.0, INFINITY, &h);
    if (rs != rr || (rs && fabs((double)(h.t - tr)) * v3_len(ray.d) > 1e-9 * sor_ref_size(ref))) {
        fprintf(stderr, "disagree: o=(%.17g,%.17g,%.17g) d=(%.17g,%.17g,%.17g) sor=%d t=%.17g ref=%d t=%.17Lg\n", ray.o.x,
                ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z, rs, rs ? h.t : 0.0, rr, rr ? tr : 0.0L);
        return 0;
    }
    return 1;
}

/* Runs gen(ref, rng, k, &ray) for n rays on every profile and requires
 * agreement with the reference, with at most max_amb ambiguous rays. */
typedef ray3 (*ray_gen)(const sor_ref *ref, sor_rng *g, int k);
static void against_reference(ray_gen gen, int n, int max_amb, const char *what)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        sor_rng g = {77u + (uint64_t)i};
        int bad = 0, amb = 0;
        for (int k = 0; k < n; k++)
            bad += !agrees(s, ref, gen(ref, &g, k), &amb);
        cr_expect_eq(bad, 0, "%s, %s: %d of %d rays disagree", what, sor_test_profile_name(i), bad, n);
        cr_expect_leq(amb, max_amb, "%s, %s: %d ambiguous", what, sor_test_profile_name(i), amb);
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}

static double uniform(sor_rng *g, double a, double b) { return a + (b - a) * sor_rng_uniform(g); }

Test(sor_degenerate, rays_along_the_axis)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        const char *name = sor_test_profile_name(i);
        sor_hit h;
        /* Up the axis from below, with a non-unit direction: the base at y = 0. */
        ray3 up = {{0.0, -1.0, 0.0}, {0.0, 7.0, 0.0}};
        cr_assert(sor_intersect(s, &up, 0.0, INFINITY, &h), "%s", name);
        cr_assert_float_eq(h.t, 1.0 / 7.0, 1e-14, "%s: t %.17g", name, h.t);
        cr_assert_float_eq(h.p.y, 0.0, 1e-14, "%s", name);
        cr_assert_float_eq(h.ng.y, -1.0, 1e-12, "%s: base normal points down", name);
        /* Down the axis from above: the mouth (or the closed top) at y = 1. */
        ray3 down = {{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}};
        cr_assert(sor_intersect(s, &down, 0.0, INFINITY, &h), "%s", name);
        cr_assert_float_eq(h.t, 2.0, 1e-12, "%s: t %.17g", name, h.t);
        cr_assert_float_eq(h.ng.y, 1.0, 1e-12, "%s: top normal points up", name);
        /* From inside, up the axis: leaves through the top, normal along the ray. */
        ray3 in = {{0.0, 0.5, 0.0}, {0.0, 1.0, 0.0}};
        cr_assert(sor_intersect(s, &in, 0.0, INFINITY, &h), "%s", name);
        cr_assert_float_eq(h.t, 0.5, 1e-12, "%s", name);
        cr_assert_gt(h.ng.y, 0.0, "%s", name);
        cr_assert(sor_occluded(s, &in, 0.0, INFINITY), "%s", name);
        cr_assert_not(sor_occluded(s, &in, 0.0, 0.49), "%s", name);
        sor_destroy(s);
    }
}

Test(sor_degenerate, open_mouth_lets_the_axis_ray_reach_the_base)
{
    sor_t *s = sor_test_create(0, SOR_CAP_BASE); /* the bowl, no mouth disc */
    sor_hit h;
    ray3 down = {{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}};
    cr_assert(sor_intersect(s, &down, 0.0, INFINITY, &h));
    cr_assert_float_eq(h.t, 3.0, 1e-12);
    cr_assert_eq(h.part, SOR_PART_BASE);
    cr_assert_float_eq(h.ng.y, -1.0, 1e-12, "the geometric normal stays outward, away from the ray");
    /* Neither cap: the same ray finds nothing; each cap is one primitive. */
    sor_t *bare = sor_test_create(0, 0u), *all = sor_test_create(0, SOR_CAPS_ALL);
    cr_assert_not(sor_intersect(bare, &down, 0.0, INFINITY, &h));
    cr_assert_eq(sor_prim_count(s), sor_prim_count(bare) + 1);
    cr_assert_eq(sor_prim_count(all), sor_prim_count(bare) + 2);
    sor_destroy(all);
    sor_destroy(bare);
    sor_destroy(s);
}

static ray3 gen_vertical(const sor_ref *ref, sor_rng *g, int k)
{
    double rho = sor_ref_rmax(ref) * uniform(g, 0.0, 1.1), phi = uniform(g, 0.0, 2.0 * M_PI);
    if (k % 10 == 0)
        rho = 0.0;
    double sign = k & 1 ? 1.0 : -1.0, lean = k % 7 == 3 && rho > 0.0 ? 1e-170 : 0.0; /* a tilt whose square underflows */
    return (ray3){{rho * cos(phi), 0.5 - 3.0 * sign, rho * sin(phi)}, {lean, sign, 0.0}};
}

Test(sor_degenerate, rays_parallel_to_the_axis) { against_reference(gen_vertical, 2000, 2, "vertical"); }

static ray3 gen_through_axis(const sor_ref *ref, sor_rng *g, int k)
{
    double y = uniform(g, sor_ref_hmin(ref) - 0.05, sor_ref_hmax(ref) + 0.05), phi = uniform(g, 0.0, 2.0 * M_PI);
    vec3 on_axis = {0.0, y, 0.0};
    vec3 dir = k % 2 ? v3(cos(phi), 0.0, sin(phi)) : v3(cos(phi), uniform(g, -2.0, 2.0), sin(phi));
    return (ray3){v3_sub(on_axis, v3_scale(dir, 3.0)), dir};
}

Test(sor_degenerate, rays_through_the_axis) { against_reference(gen_through_axis, 2000, 2, "through axis"); }

static ray3 gen_horizontal(const sor_ref *ref, sor_rng *g, int k)
{
    (void)k;
    double y = uniform(g, sor_ref_hmin(ref) - 0.05, sor_ref_hmax(ref) + 0.05), phi = uniform(g, 0.0, 2.0 * M_PI);
    double off = uniform(g, -1.1, 1.1) * sor_ref_rmax(ref);
    vec3 dir = v3(cos(phi), 0.0, sin(phi)), side = v3(-sin(phi), 0.0, cos(phi));
    return (ray3){v3_add(v3(0.0, y, 0.0), v3_add(v3_scale(dir, -3.0), v3_scale(side, off))), dir};
}

Test(sor_degenerate, exactly_horizontal_rays) { against_reference(gen_horizontal, 3000, 2, "horizontal"); }

static ray3 gen_near_horizontal(const sor_ref *ref, sor_rng *g, int k)
{
    static const double tilts[] = {1e-4, 1e-6, 1e-9, 1e-12};
    ray3 r = gen_horizontal(ref, g, k);
    r.d.y = tilts[k % 4] * (k & 1 ? 1.0 : -1.0);
    return r;
}

Test(sor_degenerate, nearly_horizontal_rays) { against_reference(gen_near_horizontal, 3000, 5, "near horizontal"); }

/* Below ~1e-14 of tilt the reference's own bisection cannot separate the
 * entry and exit roots; such a ray must then hit where the horizontal ray
 * does (the height differs by under 1e-14 over the object). */
Test(sor_degenerate, rays_tilted_below_resolution_behave_as_horizontal)
{
    static const double tilts[] = {1e-15, -1e-17, 1e-300, -4.9e-324};
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        sor_rng g = {31u + (uint64_t)i};
        int bad = 0, amb = 0;
        for (int k = 0; k < 2000; k++) {
            ray3 flat = gen_horizontal(ref, &g, k), tilted = flat;
            tilted.d.y = tilts[k % 4];
            long double tr;
            int rr = sor_ref_intersect(ref, &flat, 0.0, INFINITY, &tr);
            if (rr == SOR_REF_AMBIGUOUS) {
                amb++;
                continue;
            }
            sor_hit h;
            int rs = sor_intersect(s, &tilted, 0.0, INFINITY, &h);
            bad += rs != rr || (rs && fabs((double)(h.t - tr)) > 1e-9);
        }
        cr_expect_eq(bad, 0, "%s: %d rays disagree with the horizontal reference", sor_test_profile_name(i), bad);
        cr_expect_leq(amb, 2, "%s: %d ambiguous", sor_test_profile_name(i), amb);
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}

/* Rays tangent to the wall at a random point, shifted off it along the normal
 * by +-1e-7 of the size: just outside they miss there, just inside they cut
 * a tiny chord. */
static ray3 gen_grazing(const sor_ref *ref, sor_rng *g, int k)
{
    double u = sor_rng_uniform(g), phi = uniform(g, 0.0, 2.0 * M_PI);
    vec3 p = sor_ref_wall_point(ref, u, phi), n = v3_norm(sor_ref_wall_normal(ref, u, phi));
    vec3 a = fabs(n.y) < 0.9 ? v3(0.0, 1.0, 0.0) : v3(1.0, 0.0, 0.0);
    vec3 t1 = v3_norm(v3_cross(n, a)), t2 = v3_cross(n, t1);
    double ang = uniform(g, 0.0, 2.0 * M_PI);
    vec3 dir = v3_add(v3_scale(t1, cos(ang)), v3_scale(t2, sin(ang)));
    double shift = (k & 1 ? 1e-7 : -1e-7) * sor_ref_size(ref);
    vec3 q = v3_add(p, v3_scale(n, shift));
    return (ray3){v3_sub(q, v3_scale(dir, 3.0)), dir};
}

Test(sor_degenerate, grazing_rays_at_the_silhouette) { against_reference(gen_grazing, 3000, 10, "grazing"); }

Test(sor_degenerate, horizontal_tangent_to_a_cylinder)
{
    int ci = -1;
    for (int i = 0; i < sor_test_profile_count(); i++)
        if (!strcmp(sor_test_profile_name(i), "cylinder"))
            ci = i;
    cr_assert_geq(ci, 0);
    sor_t *s = sor_test_create(ci, SOR_CAPS_ALL);
    sor_ref *ref = sor_ref_create_profile(ci, SOR_CAPS_ALL);
    for (int k = 1; k < 20; k++) {
        vec3 p = sor_ref_wall_point(ref, k / 20.0, 0.0); /* (R, y, 0) */
        double R = p.x;
        sor_hit h;
        ray3 in = {{R * (1.0 - 1e-9), p.y, -3.0}, {0.0, 0.0, 1.0}};
        cr_assert(sor_intersect(s, &in, 0.0, INFINITY, &h), "1e-9 inside the silhouette must hit (u=%g)", k / 20.0);
        double half = sqrt(R * R - in.o.x * in.o.x);
        cr_assert_float_eq(h.t, 3.0 - half, 1e-9, "t %.17g vs %.17g", h.t, 3.0 - half);
        ray3 out = {{R * (1.0 + 1e-9), p.y, -3.0}, {0.0, 0.0, 1.0}};
        cr_assert_not(sor_intersect(s, &out, 0.0, INFINITY, &h), "1e-9 outside the silhouette must miss (u=%g)",
                      k / 20.0);
    }
    sor_ref_destroy(ref);
    sor_destroy(s);
}

/* Aims rays at p from many directions; each must reach p (within 1e-9) or
 * stop at an earlier surface point. Returns how many reached p itself. */
static int aim_at(const sor_t *s, const sor_ref *ref, vec3 p, sor_rng *g, int n)
{
    int reached = 0;
    double size = sor_ref_size(ref);
    for (int k = 0; k < n; k++) {
        double y = uniform(g, -1.0, 1.0), phi = uniform(g, 0.0, 2.0 * M_PI), c = sqrt(1.0 - y * y);
        vec3 o = v3_add(p, v3_scale(v3(c * cos(phi), y, c * sin(phi)), 3.0 * size));
        ray3 ray = {o, v3_sub(p, o)};
        sor_hit h;
        cr_assert(sor_intersect(s, &ray, 0.0, 1.0 + 1e-6, &h), "ray at (%.17g,%.17g,%.17g) from (%.17g,%.17g,%.17g) passed",
                  p.x, p.y, p.z, o.x, o.y, o.z);
        if (v3_len(v3_sub(h.p, p)) <= 1e-9 * size) {
            reached++;
        } else {
            cr_assert_lt(h.t, 1.0);
            cr_assert_leq(sor_ref_surface_distance(ref, h.p), 1e-9 * size);
        }
    }
    return reached;
}

Test(sor_degenerate, hits_exactly_at_rim_and_base_corners)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        sor_rng g = {5u + (uint64_t)i};
        int reached = 0;
        for (int k = 0; k < 8; k++) {
            double phi = uniform(&g, 0.0, 2.0 * M_PI);
            reached += aim_at(s, ref, sor_ref_wall_point(ref, 0.0, phi), &g, 40);
            reached += aim_at(s, ref, sor_ref_wall_point(ref, 1.0, phi), &g, 40);
        }
        cr_expect_gt(reached, 8 * 80 / 4, "%s: corners should mostly be visible", sor_test_profile_name(i));
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}

Test(sor_degenerate, hits_exactly_at_bezier_joints)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        sor_rng g = {9u + (uint64_t)i};
        for (int j = 0; j < sor_ref_joint_count(ref); j++)
            for (int k = 0; k < 4; k++)
                aim_at(s, ref, sor_ref_wall_point(ref, sor_ref_joint(ref, j), uniform(&g, 0.0, 2.0 * M_PI)), &g, 30);
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}

Test(sor_degenerate, profile_touching_the_axis)
{
    int gi = -1;
    for (int i = 0; i < sor_test_profile_count(); i++)
        if (!strcmp(sor_test_profile_name(i), "gourd"))
            gi = i;
    cr_assert_geq(gi, 0);
    sor_t *s = sor_test_create(gi, SOR_CAPS_ALL);
    sor_ref *ref = sor_ref_create_profile(gi, SOR_CAPS_ALL);
    cr_assert_eq(sor_ref_cap_radius(ref, 0), 0.0, "the gourd's base is a point on the axis");
    cr_assert_eq(sor_ref_cap_radius(ref, 1), 0.0, "and so is its top");
    sor_rng g = {3u};
    /* Rays at the two tips from every side (the lower hemisphere for the base tip, etc.). */
    int reached = aim_at(s, ref, v3(0.0, 0.0, 0.0), &g, 400) + aim_at(s, ref, v3(0.0, 1.0, 0.0), &g, 400);
    cr_assert_gt(reached, 200, "the tips are visible from about half the directions");
    /* The normal at a tip is the axis direction. */
    sor_hit h;
    ray3 up = {{0.0, -1.0, 0.0}, {0.0, 1.0, 0.0}};
    cr_assert(sor_intersect(s, &up, 0.0, INFINITY, &h));
    cr_assert_float_eq(h.ng.y, -1.0, 1e-9);
    sor_ref_destroy(ref);
    sor_destroy(s);
}

Test(sor_degenerate, bad_input_is_rejected_with_a_reason)
{
    bspline_t c;
    sor_test_profile(0, &c);
    char err[128];
    err[0] = 0;
    cr_assert_null(sor_create(&c, 0.0, SOR_CAPS_ALL, err, sizeof err));
    cr_assert_neq(err[0], 0);
    cr_assert_null(sor_create(&c, NAN, SOR_CAPS_ALL, err, sizeof err));
    cr_assert_null(sor_create(&c, 1.0, 8u, err, sizeof err));
    c.ctrl[1].x = -0.1;
    cr_assert_null(sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err));
    c.ctrl[1].x = -1e-12; /* rounding noise of a fit: snapped to the axis */
    sor_t *snapped = sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err);
    cr_assert_not_null(snapped, "%s", err);
    sor_destroy(snapped);
    c.ctrl[1].x = 0.55;
    c.ctrl[0].y = 0.01;
    cr_assert_null(sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err), "h(0) must be 0");
    c.ctrl[0].y = 0.0;
    c.ctrl[c.n_ctrl - 1].y = -0.2;
    cr_assert_null(sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err), "h(1) must be > 0");
    c.ctrl[c.n_ctrl - 1].y = 0.6;
    c.knots[1] = 0.1;
    cr_assert_null(sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err), "unclamped knots");
    c.knots[1] = 0.0;
    sor_t *s = sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    sor_hit h;
    ray3 zero = {{0.0, -1.0, 0.0}, {0.0, 0.0, 0.0}}, nan_o = {{NAN, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    cr_assert_not(sor_intersect(s, &zero, 0.0, INFINITY, &h));
    cr_assert_not(sor_intersect(s, &nan_o, 0.0, INFINITY, &h));
    cr_assert_not(sor_occluded(s, &zero, 0.0, INFINITY));
    cr_assert_not(sor_prim_intersect(s, -1, &zero, 0.0, INFINITY, &h));
    sor_destroy(s);
    sor_destroy(NULL);
    bspline_free(&c);
}
