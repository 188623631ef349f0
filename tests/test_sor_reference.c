/* sor_intersect against the brute-force reference on every test profile. */
#include <criterion/criterion.h>
#include <stdio.h>

#include "celadon/sor.h"
#include "support/sor_profiles.h"
#include "support/sor_reference.h"
#include "support/test_build.h"

/* The sanitized build sends a quarter of them (support/test_build.h). */
#define RAYS_PER_PROFILE 100000

Test(sor_reference, random_rays_agree_with_brute_force, .timeout = 300)
{
    int rays = test_build_share(RAYS_PER_PROFILE, 4);
    for (int i = 0; i < sor_test_profile_count(); i++) {
        bspline_t c;
        sor_test_profile(i, &c);
        char err[128];
        sor_t *s = sor_create(&c, 1.0, SOR_CAPS_ALL, err, sizeof err);
        cr_assert_not_null(s, "%s", err);
        sor_ref *ref = sor_ref_create(&c, 1.0, SOR_CAPS_ALL);
        double size = sor_ref_size(ref);
        sor_rng g = {(uint64_t)i * 7919u + 1u};
        int ambiguous = 0, hits = 0, bad = 0;
        double worst = 0.0;
        for (int k = 0; k < rays; k++) {
            ray3 ray = sor_ref_random_ray(ref, &g);
            long double tr;
            int rr = sor_ref_intersect(ref, &ray, 0.0, INFINITY, &tr);
            if (rr == SOR_REF_AMBIGUOUS) {
                ambiguous++;
                continue;
            }
            sor_hit h;
            int rs = sor_intersect(s, &ray, 0.0, INFINITY, &h);
            double dt = rs && rr ? fabs((double)(h.t - tr)) * v3_len(ray.d) : 0.0;
            if (rs != rr || dt > 1e-9 * size) {
                if (bad++ < 5)
                    fprintf(stderr, "%s ray %d: o=(%.17g,%.17g,%.17g) d=(%.17g,%.17g,%.17g) sor=%d t=%.17g ref=%d t=%.17Lg\n",
                            sor_test_profile_name(i), k, ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z, rs,
                            rs ? h.t : 0.0, rr, rr == 1 ? tr : 0.0L);
            }
            hits += rr;
            worst = fmax(worst, dt);
        }
        fprintf(stderr, "sor_reference %-8s: %d rays, %d hits, %d ambiguous, %d disagree, worst |dt| %.3g\n",
                sor_test_profile_name(i), rays, hits, ambiguous, bad, worst / size);
        cr_expect_eq(bad, 0, "%s: %d rays disagree", sor_test_profile_name(i), bad);
        cr_expect_leq(ambiguous, 5, "%s: %d ambiguous rays", sor_test_profile_name(i), ambiguous);
        sor_ref_destroy(ref);
        sor_destroy(s);
        bspline_free(&c);
    }
}

/* Profiles come in pixels: a profile 700 times larger, at height 3, must give
 * the same answers as its reference (tolerances scale with the object). */
Test(sor_reference, pixel_scale_profile_and_other_height)
{
    for (int i = 0; i < sor_test_profile_count(); i++) {
        bspline_t c;
        sor_test_profile(i, &c);
        double h1 = c.ctrl[c.n_ctrl - 1].y * 700.0;
        for (int k = 0; k < c.n_ctrl; k++)
            c.ctrl[k] = v2_scale(c.ctrl[k], 700.0);
        char err[128];
        sor_t *s = sor_create(&c, 3.0, SOR_CAPS_ALL, err, sizeof err);
        cr_assert_not_null(s, "%s", err);
        cr_assert_float_eq(sor_profile_scale(s), 3.0 / h1, 1e-15);
        sor_ref *ref = sor_ref_create(&c, 3.0, SOR_CAPS_ALL);
        double size = sor_ref_size(ref);
        sor_rng g = {(uint64_t)i + 99u};
        int bad = 0, amb = 0;
        for (int k = 0; k < 5000; k++) {
            ray3 ray = sor_ref_random_ray(ref, &g);
            long double tr;
            int rr = sor_ref_intersect(ref, &ray, 0.0, INFINITY, &tr);
            if (rr == SOR_REF_AMBIGUOUS) {
                amb++;
                continue;
            }
            sor_hit h;
            int rs = sor_intersect(s, &ray, 0.0, INFINITY, &h);
            bad += rs != rr || (rs && fabs((double)(h.t - tr)) * v3_len(ray.d) > 1e-9 * size);
        }
        cr_expect_eq(bad, 0, "%s: %d rays disagree", sor_test_profile_name(i), bad);
        cr_expect_leq(amb, 2, "%s: %d ambiguous", sor_test_profile_name(i), amb);
        sor_ref_destroy(ref);
        sor_destroy(s);
        bspline_free(&c);
    }
}
