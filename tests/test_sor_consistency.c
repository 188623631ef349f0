/* The entry points agree with each other (hierarchy vs naive, whole vs per
 * primitive, intersect vs occluded), and the hit record is what sor.h and
 * docs/conventions.md promise: unit outward normals, an orthonormal shading
 * frame along dP/dphi, (u, v) in [0,1] from phi and height, continuous across
 * Bézier joints. */
#include <criterion/criterion.h>
#include <stdio.h>

#include "celadon/sor.h"
#include "support/counted_check.h"
#include "support/sor_profiles.h"
#include "support/sor_reference.h"

#define RAYS 20000


/* Two results of the same ray agree, or the reference finds the ray ambiguous. */
static int same(const sor_ref *ref, const ray3 *ray, int ha, const sor_hit *a, int hb, const sor_hit *b)
{
    double size = sor_ref_size(ref);
    if (ha == hb && (!ha || fabs(a->t - b->t) * v3_len(ray->d) <= 1e-9 * size))
        return 1;
    long double t;
    return sor_ref_intersect(ref, ray, 0.0, INFINITY, &t) == SOR_REF_AMBIGUOUS;
}

Test(sor_consistency, hierarchy_agrees_with_naive_and_with_primitives)
{
    failures = 0;
    for (int i = 0; i < sor_test_profile_count(); i++) {
        const char *name = sor_test_profile_name(i);
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        double size = sor_ref_size(ref);
        int np = sor_prim_count(s);
        sor_rng g = {400u + (uint64_t)i};
        for (int k = 0; k < RAYS; k++) {
            ray3 ray = sor_ref_random_ray(ref, &g);
            sor_hit h, hn, hp, best;
            int hit = sor_intersect(s, &ray, 0.0, INFINITY, &h);
            int hit_n = sor_intersect_naive(s, &ray, 0.0, INFINITY, &hn);
            CHECK(same(ref, &ray, hit, &h, hit_n, &hn), "%s ray %d: tree %d t=%.17g, naive %d t=%.17g", name, k, hit, h.t,
                  hit_n, hn.t);
            int any = 0;
            for (int p = 0; p < np; p++) {
                if (!sor_prim_intersect(s, p, &ray, 0.0, INFINITY, &hp))
                    continue;
                vec3 lo, hi;
                sor_prim_bounds(s, p, &lo, &hi);
                double e = 1e-9 * size;
                CHECK(hp.prim == p, "%s: prim %d reports %d", name, p, hp.prim);
                CHECK(hp.p.x >= lo.x - e && hp.p.y >= lo.y - e && hp.p.z >= lo.z - e && hp.p.x <= hi.x + e &&
                          hp.p.y <= hi.y + e && hp.p.z <= hi.z + e,
                      "%s: prim %d hit outside its bounds", name, p);
                if (!any || hp.t < best.t)
                    best = hp;
                any = 1;
            }
            CHECK(same(ref, &ray, hit, &h, any, &best), "%s ray %d: whole %d t=%.17g, primitives %d t=%.17g", name, k,
                  hit, h.t, any, best.t);
            if (hit && any && fabs(h.t - best.t) * v3_len(ray.d) <= 1e-12 * size)
                CHECK(h.prim == best.prim || h.part == SOR_PART_WALL, "%s: prim index %d vs %d", name, h.prim, best.prim);
            /* Occlusion over a random part of the ray. */
            double tmax = hit ? h.t * (sor_rng_uniform(&g) < 0.5 ? 0.999 : 1.001) : 1e30;
            int occ = sor_occluded(s, &ray, 0.0, tmax);
            CHECK(occ == (hit && h.t < tmax) || !same(ref, &ray, 1, &h, 1, &h), "%s ray %d: occluded %d, hit %d t=%g tmax=%g",
                  name, k, occ, hit, h.t, tmax);
        }
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
    cr_assert_eq(failures, 0, "%d failures (first ones printed above)", failures);
}

Test(sor_consistency, hit_records_follow_the_conventions)
{
    failures = 0;
    for (int i = 0; i < sor_test_profile_count(); i++) {
        const char *name = sor_test_profile_name(i);
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        double size = sor_ref_size(ref);
        vec3 lo, hi;
        sor_bounds(s, &lo, &hi);
        sor_rng g = {500u + (uint64_t)i};
        for (int k = 0; k < RAYS; k++) {
            ray3 ray = sor_ref_random_ray(ref, &g);
            sor_hit h;
            if (!sor_intersect(s, &ray, 0.0, INFINITY, &h))
                continue;
            vec3 p = h.p, n = h.ng;
            double e = 1e-9 * size;
            CHECK(fabs(v3_len(n) - 1.0) < 1e-12, "%s: normal not unit", name);
            CHECK(p.x >= lo.x - e && p.y >= lo.y - e && p.z >= lo.z - e && p.x <= hi.x + e && p.y <= hi.y + e &&
                      p.z <= hi.z + e,
                  "%s: hit outside sor_bounds", name);
            CHECK(v3_len(v3_sub(p, ray3_at(ray, h.t))) <= e, "%s: p is not the ray at t", name);
            /* phi and the texture convention of docs/conventions.md. */
            double rho = sqrt(p.x * p.x + p.z * p.z);
            CHECK(h.phi >= 0.0 && h.phi < 2.0 * M_PI, "%s: phi %g", name, h.phi);
            if (rho > 1e-6) {
                CHECK(fabs(p.x - rho * cos(h.phi)) < 1e-9 && fabs(p.z - rho * sin(h.phi)) < 1e-9, "%s: phi", name);
                double tu = h.phi <= M_PI ? 1.0 - h.phi / M_PI : h.phi / M_PI - 1.0;
                CHECK(fabs(h.uv.x - tu) < 1e-12, "%s: texture u %g vs %g", name, h.uv.x, tu);
            }
            CHECK(h.uv.x >= 0.0 && h.uv.x <= 1.0 && h.uv.y >= 0.0 && h.uv.y <= 1.0, "%s: uv (%g,%g)", name, h.uv.x,
                  h.uv.y);
            CHECK(fabs(h.uv.y - fmin(1.0, fmax(0.0, p.y))) < 1e-12, "%s: v is the height", name);
            CHECK(h.u >= 0.0 && h.u <= 1.0, "%s: u %g", name, h.u);
            /* Orthonormal shading frame, n = ng, s along dP/dphi. */
            frame3 f = h.shading;
            CHECK(v3_len(v3_sub(f.n, n)) < 1e-15, "%s: shading n", name);
            CHECK(fabs(v3_dot(f.s, f.t)) < 1e-12 && fabs(v3_dot(f.s, f.n)) < 1e-12 && fabs(v3_dot(f.t, f.n)) < 1e-12 &&
                      fabs(v3_len(f.s) - 1.0) < 1e-12 && fabs(v3_len(f.t) - 1.0) < 1e-12,
                  "%s: frame not orthonormal", name);
            if (rho > 1e-6)
                CHECK(v3_len(v3_sub(f.s, v3(-p.z / rho, 0.0, p.x / rho))) < 1e-9, "%s: s is not dP/dphi", name);
            /* Outward: the analytic wall normal, the caps' axis direction. */
            if (h.part == SOR_PART_WALL) {
                vec3 nr = v3_norm(sor_ref_wall_normal(ref, h.u, h.phi));
                CHECK(v3_dot(nr, n) > 1.0 - 1e-6, "%s: normal at u=%.17g differs from the profile's", name, h.u);
                vec3 wp = sor_ref_wall_point(ref, h.u, h.phi);
                CHECK(v3_len(v3_sub(wp, p)) <= 1e-9 * size, "%s: u=%.17g does not name the hit point", name, h.u);
            } else {
                CHECK(n.y == (h.part == SOR_PART_BASE ? -1.0 : 1.0), "%s: cap normal", name);
            }
            if (k % 8 == 0) {
                vec3 out = v3_add(p, v3_scale(n, 1e-6 * size)), in = v3_sub(p, v3_scale(n, 1e-6 * size));
                int io = sor_ref_inside(ref, out), ii = sor_ref_inside(ref, in);
                CHECK(io != 1 && ii != 0, "%s: normal not outward at (%g,%g,%g) part %d", name, p.x, p.y, p.z, h.part);
            }
        }
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
    cr_assert_eq(failures, 0, "%d failures (first ones printed above)", failures);
}

Test(sor_consistency, parameters_continuous_across_joints)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        for (int j = 0; j < sor_ref_joint_count(ref); j++) {
            double uj = sor_ref_joint(ref, j), phi = 0.3 + j;
            sor_hit h[2];
            for (int side = 0; side < 2; side++) {
                double u = uj + (side ? 1e-7 : -1e-7);
                vec3 p = sor_ref_wall_point(ref, u, phi), n = v3_norm(sor_ref_wall_normal(ref, u, phi));
                ray3 ray = {v3_add(p, v3_scale(n, 0.5)), v3_neg(n)}; /* straight down the normal */
                cr_assert(sor_intersect(s, &ray, 0.0, INFINITY, &h[side]));
                cr_assert_float_eq(h[side].t, 0.5, 1e-9, "%s joint %d", sor_test_profile_name(i), j);
                cr_assert_float_eq(h[side].u, u, 1e-9, "%s joint %d: u %.17g vs %.17g", sor_test_profile_name(i), j,
                                   h[side].u, u);
            }
            cr_assert_lt(fabs(h[0].uv.x - h[1].uv.x) + fabs(h[0].uv.y - h[1].uv.y), 1e-5, "%s joint %d: uv jumps",
                         sor_test_profile_name(i), j);
        }
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}

Test(sor_consistency, ray_interval_is_respected)
{
    sor_t *s = sor_test_create(1, SOR_CAPS_ALL);
    ray3 ray = {{-3.0, 0.5, 0.01}, {1.0, 0.0, 0.0}};
    sor_hit a, b;
    cr_assert(sor_intersect(s, &ray, 0.0, INFINITY, &a));
    cr_assert(sor_intersect(s, &ray, a.t + 1e-6, INFINITY, &b), "the exit on the far side");
    cr_assert_gt(b.t, a.t + 0.4, "the neck is about 0.48 wide at y = 0.5");
    cr_assert_lt(v3_dot(a.ng, ray.d), 0.0);
    cr_assert_gt(v3_dot(b.ng, ray.d), 0.0);
    cr_assert_not(sor_intersect(s, &ray, 0.0, a.t * 0.999, &b));
    cr_assert_not(sor_intersect(s, &ray, b.t + 1e-6, INFINITY, &b));
    sor_destroy(s);
}
