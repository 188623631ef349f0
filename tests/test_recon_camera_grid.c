/* Two cases of the perspective grid (docs/algorithms-recon.md 13.7, `make
 * check-perspective-grid`) through reconstruct_image as `celadon
 * reconstruct` runs it, drawn through an exact pinhole
 * (tests/support/pinhole_vessel) at 300 x 400 px: the wide-mouthed vase
 * from 8 degrees above at 85 mm (35 mm equivalent), which issue 25 saw read
 * as orthographic from 15.9 degrees (the base's ellipse alone gives that:
 * the base is seen from 15.9 degrees, the rim from 0), and a strongly
 * foreshortened close-up, the vase from 10 degrees above at 35 mm. Each
 * must get the perspective camera from the ellipses, the elevation within
 * 0.1 degree, the axis within 0.05 degree, and the profile within 0.3% of
 * the height on average and 1% at worst. */
#include <criterion/criterion.h>
#include <math.h>

#include "celadon/reconstruct.h"
#include "support/drawn_silhouettes.h"
#include "support/pinhole_vessel.h"

static void expect_grid_case(const char *what, double (*radius)(double), double elevation_deg, double focal_35mm)
{
    pinhole_params p = pinhole_defaults(SYNTH_VASE, elevation_deg);
    p.radius = radius;
    p.width = 300;
    p.height = 400;
    p.subrows = 12;
    p.focal_px = recon_focal_from_35mm(p.width, p.height, focal_35mm);
    pinhole_frame(&p);
    image_t img;
    cr_assert_eq(pinhole_draw(&p, &img, NULL), 0);
    reconstruct_options opt = reconstruct_options_default();
    opt.segmenter = RECONSTRUCT_SEGMENTER_CLASSIC;
    reconstruction r;
    char err[512] = "";
    cr_assert_eq(reconstruct_image(&img, &opt, &r, err, sizeof err), 0, "%s: refused: %s", what, err);
    cr_assert(r.has_camera, "%s: no camera: %s", what, r.camera_note);
    double mean, max;
    pinhole_profile_error(&p, &r.meridian.curve, &mean, &max);
    double axis = fmax(fabs(r.extract.tilt_deg), fabs(r.camera.roll_deg));
    cr_log_info("%s: camera %d, f %.0f (true %.0f), elevation %.3f (true %.3f), profile %.3f%% / %.3f%%, axis %.4f",
                what, r.camera.method, r.camera.focal_px, p.focal_px, r.camera.elevation_deg, pinhole_elevation(&p),
                100 * mean, 100 * max, axis);
    cr_expect_eq(r.camera.method, RECON_CAMERA_ELLIPSES, "%s: not the perspective camera: %s", what, r.camera.note);
    cr_expect_leq(fabs(r.camera.elevation_deg - pinhole_elevation(&p)), 0.1, "%s: elevation %.3f", what,
                  r.camera.elevation_deg);
    cr_expect_leq(axis, 0.05, "%s: axis %.4f deg off", what, axis);
    cr_expect_leq(mean, 0.003, "%s: profile mean %.3f%% of the height", what, 100 * mean);
    cr_expect_leq(max, 0.010, "%s: profile max %.3f%% of the height", what, 100 * max);
    reconstruction_free(&r);
    image_free(&img);
}

static double vase_radius(double t)
{
    pinhole_params p = {.shape = SYNTH_VASE};
    return pinhole_radius(&p, t);
}

Test(recon_camera_grid, wide_mouthed_vase_8_degrees_above_at_85mm, .timeout = 60)
{
    expect_grid_case("wide-mouthed vase, 8 deg, 85 mm", drawn_wide_mouth_vase_radius, 8, 85);
}

Test(recon_camera_grid, close_up_10_degrees_above_at_35mm, .timeout = 60)
{
    expect_grid_case("vase, 10 deg, 35 mm", vase_radius, 10, 35);
}
