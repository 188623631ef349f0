/* Photos rendered by POV-Ray, an independent renderer
 * (tests/support/pov_vessel.c: an open thin-walled vessel on a sweep, soft
 * light and shadow, anti-aliased), through the exact pinhole camera of
 * tests/support/pinhole_vessel at 300 x 400 px, reconstructed as `celadon
 * reconstruct` runs it by default: one case of the rendered grid
 * (docs/algorithms-recon.md 13.8, `make check-rendered-grid`) and a moon
 * jar on the sweep. Skipped (one line) without povray. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>

#include "celadon/reconstruct.h"
#include "support/drawn_silhouettes.h"
#include "support/pinhole_vessel.h"
#include "support/pov_vessel.h"
#include "support/scratch_dir.h"

/* Renders p with POV-Ray and reconstructs the photo as `celadon
 * reconstruct` does by default, into r (asserts both worked). */
static void render_and_reconstruct(const char *name, const pinhole_params *p, reconstruction *r)
{
    char dir[64], pov[128], png[128], err[512] = "";
    scratch_dir_make(dir, sizeof dir, "rendered");
    snprintf(pov, sizeof pov, "%s/vessel.pov", dir);
    snprintf(png, sizeof png, "%s/vessel.png", dir);
    int rendered = pov_vessel_render(p, 1, pov, png, 1, err, sizeof err);
    reconstruct_options opt = reconstruct_options_default();
    int rc = rendered == 0 ? reconstruct_photo(png, &opt, r, err, sizeof err) : -1;
    scratch_dir_remove(dir);
    cr_assert_eq(rendered, 0, "%s", err);
    cr_assert_eq(rc, 0, "%s refused: %s", name, err);
}

/* Issue 25's case: the wide-mouthed vase from 8 degrees above at 85 mm (35
 * mm equivalent) was read as an orthographic view from 15.9 degrees; it
 * must get the perspective camera from the ellipses. */
Test(recon_rendered, wide_mouthed_vase_8_degrees_above_at_85mm, .timeout = 120)
{
    if (!pov_available())
        cr_skip_test("povray not found (make deps installs it)");
    pinhole_params pp = drawn_grid_vessel(DRAWN_GRID_WIDE_MOUTH, 8, 85, 300, 400), *p = &pp;
    const char *name = "wide-mouthed vase, 8 deg, 85 mm";
    reconstruction r;
    render_and_reconstruct(name, p, &r);
    cr_assert(r.has_camera, "%s: no camera: %s", name, r.camera_note);
    double mean, max;
    pinhole_profile_error(p, &r.meridian.curve, &mean, &max);
    double axis = fmax(fabs(r.extract.tilt_deg), fabs(r.camera.roll_deg));
    cr_log_info("rendered %s: camera %d, f %.0f (true %.0f), elevation %.3f (true %.3f), profile %.3f%% / %.3f%%, "
                "axis %.4f",
                name, r.camera.method, r.camera.focal_px, p->focal_px, r.camera.elevation_deg, pinhole_elevation(p),
                100 * mean, 100 * max, axis);
    cr_expect(r.quality.passed, "%s: quality gate: %s", name, r.quality.failed);
    cr_expect_eq(r.camera.method, RECON_CAMERA_ELLIPSES, "%s: not the perspective camera: %s", name, r.camera.note);
    cr_expect_leq(axis, 0.05, "%s: axis %.4f deg off", name, axis);
    cr_expect_leq(mean, 0.003, "%s: profile mean %.3f%% of the height", name, 100 * mean);
    cr_expect_leq(max, 0.010, "%s: profile max %.3f%% of the height", name, 100 * max);
    reconstruction_free(&r);
}

/* The photo's sub-pixel outline (both sides) against the solid's exact
 * extent on each row: the mean distance over the rows it covers, in units
 * of the height, and the share of the body's image height it covers. */
static void outline_error(const pinhole_params *p, const recon_result *x, double *mean, double *cover)
{
    double top = INFINITY, bottom = -INFINITY, sum = 0, xl, xr;
    for (double y = 0.5; y < p->height; y += 1)
        if (pinhole_line_extent(p, y, &xl, &xr))
            top = fmin(top, y), bottom = fmax(bottom, y);
    int n = 0, rows = 0;
    for (int s = 0; s < 2; s++)
        for (int i = 0; i < x->n_silhouette[s]; i++) {
            vec2 q = x->silhouette[s][i];
            if (!pinhole_line_extent(p, q.y, &xl, &xr))
                continue;
            sum += fabs(q.x - (s ? xr : xl));
            n++;
            rows += s;
        }
    *mean = n ? sum / n / (bottom - top + 1) : INFINITY;
    *cover = rows / (bottom - top + 1);
}

/* Issue 25's border case: a clean moon jar on a gradient sweep (the floor
 * curving into the wall behind it, darker toward the top, its soft shadow
 * on the floor) was refused as "touches the border" once, its mask run
 * into the sweep. From 5 degrees above at 85 mm (the catalogue view): the
 * photo is accepted and its outline lies on the solid's (the issue's
 * measure: mean distance at most 0.5% of the height over at least 80% of
 * it; a clean render gives a tenth of that). What this does not hold is
 * the 3D profile: the camera read from the dark, tangentially-left base
 * is wrong (docs/algorithms-recon.md 13.9). */
Test(recon_rendered, a_moon_jar_on_a_sweep_is_not_refused, .timeout = 120)
{
    if (!pov_available())
        cr_skip_test("povray not found (make deps installs it)");
    pinhole_params p = drawn_grid_vessel(DRAWN_GRID_MOON_JAR, 5, 85, 300, 400);
    reconstruction r;
    render_and_reconstruct("moon jar, 5 deg, 85 mm", &p, &r);
    double mean, cover;
    outline_error(&p, &r.extract, &mean, &cover);
    cr_log_info("rendered moon jar, 5 deg, 85 mm: outline %.3f%% of the height over %.0f%% of it", 100 * mean,
                100 * cover);
    cr_expect(r.quality.passed, "moon jar: quality gate: %s", r.quality.failed);
    cr_expect_leq(mean, 0.005, "moon jar: outline %.3f%% of the height off", 100 * mean);
    cr_expect_geq(cover, 0.8, "moon jar: outline over %.0f%% of the height", 100 * cover);
    reconstruction_free(&r);
}
