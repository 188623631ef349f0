/* One case of the rendered grid (docs/algorithms-recon.md 13.8, `make
 * check-rendered-grid`): a photo rendered by POV-Ray, an independent
 * renderer (tests/support/pov_vessel.c: an open thin-walled vessel on a
 * sweep, soft light and shadow, anti-aliased), through the exact pinhole
 * camera of tests/support/pinhole_vessel at 300 x 400 px, reconstructed as
 * `celadon reconstruct` runs it by default. The wide-mouthed vase from 8
 * degrees above at 85 mm (35 mm equivalent), issue 25's case, must pass
 * the quality gate with the perspective camera from the ellipses, the axis
 * within 0.05 degree and the profile within 0.3% of the height on average
 * and 1% at worst. Skipped (one line) without povray. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "celadon/reconstruct.h"
#include "support/drawn_silhouettes.h"
#include "support/pinhole_vessel.h"
#include "support/pov_vessel.h"
#include "support/scratch_dir.h"

Test(recon_rendered, wide_mouthed_vase_8_degrees_above_at_85mm, .timeout = 120)
{
    if (!pov_available())
        cr_skip_test("povray not found (make deps installs it)");
    pinhole_params p = drawn_grid_vessel(DRAWN_GRID_WIDE_MOUTH, 8, 85, 300, 400);
    char dir[64], pov[128], png[128], err[512] = "";
    scratch_dir_make(dir, sizeof dir, "rendered");
    snprintf(pov, sizeof pov, "%s/vase.pov", dir);
    snprintf(png, sizeof png, "%s/vase.png", dir);
    int rendered = pov_vessel_render(&p, 1, pov, png, 1, err, sizeof err);
    reconstruct_options opt = reconstruct_options_default();
    reconstruction r;
    int rc = rendered == 0 ? reconstruct_photo(png, &opt, &r, err, sizeof err) : -1;
    scratch_dir_remove(dir);
    cr_assert_eq(rendered, 0, "%s", err);
    cr_assert_eq(rc, 0, "refused: %s", err);
    cr_assert(r.has_camera, "no camera: %s", r.camera_note);
    double mean, max;
    pinhole_profile_error(&p, &r.meridian.curve, &mean, &max);
    double axis = fmax(fabs(r.extract.tilt_deg), fabs(r.camera.roll_deg));
    cr_log_info("rendered wide-mouthed vase, 8 deg, 85 mm: camera %d, f %.0f (true %.0f), elevation %.3f (true %.3f), "
                "profile %.3f%% / %.3f%%, axis %.4f",
                r.camera.method, r.camera.focal_px, p.focal_px, r.camera.elevation_deg, pinhole_elevation(&p),
                100 * mean, 100 * max, axis);
    cr_expect(r.quality.passed, "quality gate: %s", r.quality.failed);
    cr_expect_eq(r.camera.method, RECON_CAMERA_ELLIPSES, "not the perspective camera: %s", r.camera.note);
    cr_expect_leq(axis, 0.05, "axis %.4f deg off", axis);
    cr_expect_leq(mean, 0.003, "profile mean %.3f%% of the height", 100 * mean);
    cr_expect_leq(max, 0.010, "profile max %.3f%% of the height", 100 * max);
    reconstruction_free(&r);
}
