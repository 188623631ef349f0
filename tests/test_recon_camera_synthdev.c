/* The camera model through the pipeline (reconstruct_photo) on the rendered
 * synth-dev photographs (exact cameras and profiles; skipped when
 * ../shared/data/synth-dev is absent): the profile's shape that mesh, render
 * and the museum revolve (profile_shape of the profile.json view) is the
 * meridian, within 0.3% of the height on average and 1.0% at worst from
 * profile.csv over 3-97% of the height, scaled to the true height, and the
 * recovered elevation within 0.5 degrees of camera.json, on the PNG and the
 * JPEG of each photo, the melon vase with its washed-out side included (its
 * axis from the limb, docs/algorithms-recon.md section 5). The image
 * outline's B-spline (the profile before the camera model) is logged beside
 * it. bench/bench_perspective prints the stage alone as a table. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "celadon/reconstruct.h"
#include "support/synthdev_truth.h"
#include "support/test_build.h"

/* Every photo in the optimised build; the sanitized one takes every other
 * photo from `first`, so that its PNG and JPEG runs together cover each
 * photo once (support/test_build.h). */
static void run_all(const char *file, int first)
{
    char dir[900];
    if (!synthdev_dir(dir, sizeof dir))
        cr_skip_test("synth-dev data not found at %s (set CELADON_SHARED)", dir);
    int step = test_build_case_step(2);
    for (int c = step > 1 ? first : 0; c < SYNTHDEV_NCASES; c += step) {
        const char *name = SYNTHDEV_CASES[c];
        char path[1200], err[512];
        synthdev_truth t;
        cr_assert_eq(synthdev_truth_load(dir, name, &t, err, sizeof err), 0, "%s", err);
        snprintf(path, sizeof path, "%s/%s/%s", dir, name, file);
        reconstruct_options opt = reconstruct_options_default();
        reconstruction r;
        cr_assert_eq(reconstruct_photo(path, &opt, &r, err, sizeof err), 0, "%s: %s", path, err);
        profile_t p;
        reconstruction_profile(&r, path, &p);
        const double *domains;
        int n_domains;
        const bspline_t *shape = profile_shape(&p, &domains, &n_domains);
        double before_mean, before_max, mean, max;
        synthdev_profile_error(&t, &r.curve, 0.03, 0.97, &before_mean, &before_max);
        synthdev_profile_error(&t, shape, 0.03, 0.97, &mean, &max);
        cr_log_info("%-27s %s %s elevation %6.2f (true %4.1f), f %5.0f (true %5.0f); outline %.3f%% / %.3f%%, "
                    "profile %.3f%% / %.3f%%",
                    name, file, reconstruction_is_perspective(&r) ? "perspective " : "orthographic",
                    r.camera.elevation_deg, t.elevation_deg, r.camera.focal_px, t.focal_px, 100 * before_mean,
                    100 * before_max, 100 * mean, 100 * max);
        cr_expect(reconstruction_is_perspective(&r), "%s/%s: no perspective camera (%s)", name, file,
                  r.has_camera ? r.camera.note : r.camera_note);
        cr_expect(shape == &p.meridian, "%s/%s: the shape is not the meridian", name, file);
        cr_expect_leq(fabs(r.camera.elevation_deg - t.elevation_deg), 0.5, "%s/%s: elevation %.3f, true %.1f", name,
                      file, r.camera.elevation_deg, t.elevation_deg);
        cr_expect_leq(mean, 0.003, "%s/%s: profile mean %.3f%% of the height", name, file, 100 * mean);
        cr_expect_leq(max, 0.010, "%s/%s: profile max %.3f%% of the height", name, file, 100 * max);
        reconstruction_free(&r);
        synthdev_truth_free(&t);
    }
}

Test(recon_camera_synthdev, png, .timeout = 300) { run_all("photo.png", 0); }
Test(recon_camera_synthdev, jpeg, .timeout = 300) { run_all("photo.jpg", 1); }
