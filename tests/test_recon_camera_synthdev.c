/* recon_camera_meridian on the rendered synth-dev photographs (exact cameras
 * and profiles; skipped when ../shared/data/synth-dev is absent): after
 * recon_extract, the recovered elevation within 0.5 degrees of camera.json
 * and the meridian, scaled to the true height, within 0.3% of the height on
 * average and 1.0% at worst from profile.csv over 3-97% of the height, on
 * the PNG and the JPEG of each photo. bench/bench_perspective prints the
 * same comparison as a table. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "celadon/recon_camera.h"
#include "support/synthdev_truth.h"

static void run_all(const char *file)
{
    char dir[900];
    if (!synthdev_dir(dir, sizeof dir))
        cr_skip_test("synth-dev data not found at %s (set CELADON_SHARED)", dir);
    for (int c = 0; c < SYNTHDEV_NCASES; c++) {
        const char *name = SYNTHDEV_CASES[c];
        char path[1200], err[512];
        synthdev_truth t;
        cr_assert_eq(synthdev_truth_load(dir, name, &t, err, sizeof err), 0, "%s", err);
        snprintf(path, sizeof path, "%s/%s/%s", dir, name, file);
        image_t img;
        recon_result res;
        cr_assert_eq(image_read(path, &img, err, sizeof err), 0, "%s: %s", path, err);
        cr_assert_eq(recon_extract(&img, NULL, &res, err, sizeof err), RECON_OK, "%s: %s", path, err);
        recon_camera cam;
        recon_meridian mer;
        int rc = recon_camera_meridian(&img, &res, NULL, &cam, &mer, err, sizeof err);
        cr_expect_eq(rc, 0, "%s: %s", path, err);
        if (rc == 0) {
            double mean, max;
            synthdev_profile_error(&t, &mer.curve, 0.03, 0.97, &mean, &max);
            cr_log_info("%-27s %s elevation %6.2f (true %4.1f), f %5.0f (true %5.0f), meridian %.3f%% / %.3f%%", name,
                        file, cam.elevation_deg, t.elevation_deg, cam.focal_px, t.focal_px, 100 * mean, 100 * max);
            cr_expect_leq(fabs(cam.elevation_deg - t.elevation_deg), 0.5, "%s/%s: elevation %.3f, true %.1f", name,
                          file, cam.elevation_deg, t.elevation_deg);
            cr_expect_leq(mean, 0.003, "%s/%s: meridian mean %.3f%% of the height", name, file, 100 * mean);
            cr_expect_leq(max, 0.010, "%s/%s: meridian max %.3f%% of the height", name, file, 100 * max);
            recon_meridian_free(&mer);
        }
        recon_result_free(&res);
        image_free(&img);
        synthdev_truth_free(&t);
    }
}

Test(recon_camera_synthdev, png, .timeout = 180) { run_all("photo.png"); }
Test(recon_camera_synthdev, jpeg, .timeout = 180) { run_all("photo.jpg"); }
