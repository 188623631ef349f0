/* The closed SOR (wall + caps) lets no ray through: rays from inside always
 * leave through the surface, and rays aimed at surface points, joints and
 * corners from outside reach them (or an earlier surface point). */
#include <criterion/criterion.h>
#include <stdio.h>

#include "celadon/sor.h"
#include "support/counted_check.h"
#include "support/sor_profiles.h"
#include "support/sor_reference.h"

#define INSIDE_RAYS_TOTAL 1000000
#define DIRS_PER_POINT 8

static vec3 random_dir(sor_rng *g)
{
    double y = 2.0 * sor_rng_uniform(g) - 1.0, phi = 2.0 * M_PI * sor_rng_uniform(g), s = sqrt(1.0 - y * y);
    return v3(s * cos(phi), y, s * sin(phi));
}

/* A point inside the closed surface: uniform in the bounding cylinder, or just
 * inside the wall (1e-7 to 1e-2 of the size), checked by the reference. */
static vec3 random_inside(const sor_ref *ref, sor_rng *g)
{
    double R = sor_ref_rmax(ref), h0 = sor_ref_hmin(ref), h1 = sor_ref_hmax(ref), size = sor_ref_size(ref);
    for (;;) {
        vec3 p;
        if (sor_rng_uniform(g) < 0.5) {
            p = v3(R * (2.0 * sor_rng_uniform(g) - 1.0), h0 + (h1 - h0) * sor_rng_uniform(g),
                   R * (2.0 * sor_rng_uniform(g) - 1.0));
        } else {
            double u = sor_rng_uniform(g), phi = 2.0 * M_PI * sor_rng_uniform(g);
            vec3 n = v3_norm(sor_ref_wall_normal(ref, u, phi));
            double depth = size * pow(10.0, -7.0 + 5.0 * sor_rng_uniform(g));
            p = v3_sub(sor_ref_wall_point(ref, u, phi), v3_scale(n, depth));
        }
        if (sor_ref_inside(ref, p) == 1)
            return p;
    }
}

Test(sor_watertight, rays_from_inside_always_exit, .timeout = 300)
{
    int n_prof = sor_test_profile_count();
    int points_per_profile = INSIDE_RAYS_TOTAL / (n_prof * DIRS_PER_POINT) + 1;
    long total = 0;
    for (int i = 0; i < n_prof; i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        double size = sor_ref_size(ref);
        sor_rng g = {1000u + (uint64_t)i};
        for (int k = 0; k < points_per_profile; k++) {
            vec3 o = random_inside(ref, &g);
            for (int j = 0; j < DIRS_PER_POINT; j++, total++) {
                ray3 ray = {o, random_dir(&g)};
                sor_hit h;
                int hit = sor_intersect(s, &ray, 0.0, INFINITY, &h);
                CHECK(hit, "%s: ray from inside escaped: o=(%.17g,%.17g,%.17g) d=(%.17g,%.17g,%.17g)",
                      sor_test_profile_name(i), o.x, o.y, o.z, ray.d.x, ray.d.y, ray.d.z);
                if (!hit)
                    continue;
                CHECK(v3_dot(h.ng, ray.d) > 0.0, "%s: exit normal must face along the ray (outward)",
                      sor_test_profile_name(i));
                CHECK(sor_occluded(s, &ray, 0.0, INFINITY), "%s: occluded disagrees", sor_test_profile_name(i));
                if (j == 0 && k % 16 == 0)
                    CHECK(sor_ref_surface_distance(ref, h.p) <= 1e-9 * size, "%s: exit point off the surface",
                          sor_test_profile_name(i));
            }
        }
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
    cr_assert_geq(total, INSIDE_RAYS_TOTAL);
    cr_assert_eq(failures, 0, "%d failures (first ones printed above)", failures);
}

/* Shoots from a random far point at target p (tmax just past it). The hit
 * must be p itself, or an earlier point of the surface. Rays within 1e-6 rad
 * of tangent to the surface at p are skipped (touching is ill-posed there);
 * returns 1 when the ray was used. */
static int shoot_at(const sor_t *s, const sor_ref *ref, vec3 p, vec3 normal, sor_rng *g, const char *what)
{
    double size = sor_ref_size(ref);
    vec3 o = v3_add(v3(0.0, 0.5, 0.0), v3_scale(random_dir(g), 3.0 * size));
    ray3 ray = {o, v3_sub(p, o)};
    double len = v3_len(ray.d);
    if (normal.x != 0.0 || normal.y != 0.0 || normal.z != 0.0) {
        if (fabs(v3_dot(v3_norm(normal), v3_scale(ray.d, 1.0 / len))) < 1e-6)
            return 0;
    }
    sor_hit h;
    int hit = sor_intersect(s, &ray, 0.0, 1.0 + 1e-6, &h);
    CHECK(hit, "%s: ray aimed at (%.17g,%.17g,%.17g) from (%.17g,%.17g,%.17g) passed through", what, p.x, p.y, p.z, o.x,
          o.y, o.z);
    if (hit && v3_len(v3_sub(h.p, p)) > 1e-9 * size) {
        CHECK(h.t < 1.0, "%s: hit beyond the aimed point", what);
        CHECK(sor_ref_surface_distance(ref, h.p) <= 1e-9 * size, "%s: earlier hit at t=%.17g off the surface", what, h.t);
    }
    return 1;
}

Test(sor_watertight, rays_aimed_at_surface_points_reach_them, .timeout = 300)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        sor_t *s = sor_test_create(i, SOR_CAPS_ALL);
        sor_ref *ref = sor_ref_create_profile(i, SOR_CAPS_ALL);
        sor_rng g = {2000u + (uint64_t)i};
        const char *name = sor_test_profile_name(i);
        int used = 0, tried = 0;
        for (int k = 0; k < 20000; k++, tried++) {
            double phi = 2.0 * M_PI * sor_rng_uniform(&g), u;
            int kind = k % 5;
            if (kind == 0 || kind == 1) /* anywhere on the wall */
                u = sor_rng_uniform(&g);
            else if (kind == 2) /* exactly at a Bézier joint */
                u = sor_ref_joint_count(ref) ? sor_ref_joint(ref, k % sor_ref_joint_count(ref)) : 0.5;
            else /* the base and rim corners */
                u = kind == 3 ? 0.0 : 1.0;
            used += shoot_at(s, ref, sor_ref_wall_point(ref, u, phi), sor_ref_wall_normal(ref, u, phi), &g, name);
            /* A cap point: inside the disc or on its rim. */
            int mouth = k & 1;
            double R = sor_ref_cap_radius(ref, mouth), rr = (k % 3 == 0) ? R : R * sqrt(sor_rng_uniform(&g));
            vec3 cp = v3(rr * cos(phi), mouth ? 1.0 : 0.0, rr * sin(phi));
            used += shoot_at(s, ref, cp, v3(0.0, 1.0, 0.0), &g, name);
            tried++;
        }
        fprintf(stderr, "sor_watertight %-8s: %d of %d aimed rays used (rest within 1e-6 rad of tangent)\n", name, used,
                tried);
        cr_assert_geq(used, tried * 99 / 100, "%s: too many tangent rays skipped", name);
        cr_assert_eq(failures, 0, "%d failures (first ones printed above)", failures);
        sor_ref_destroy(ref);
        sor_destroy(s);
    }
}
