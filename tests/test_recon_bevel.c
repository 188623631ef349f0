/* The base corners of a vessel whose base edge is chamfered (a cone 12 px
 * tall that takes 8 px off the radius, the proportions of synth-dev's
 * brush pot), drawn by the test through a known pinhole
 * (tests/support/pinhole_vessel) from a level camera and from 2 degrees
 * above. The outline turns twice there: from the wall onto the chamfer, and
 * from the chamfer onto the base's ellipse. The base is where it meets the
 * ellipse, the chamfer's foot (the truth's corner: where the chamfer's
 * apparent contour meets the base circle), not its top; the upper turn is
 * the sharper one, so taking the sharpest turn of the end zone put the
 * corner at the top, 14 and 17 px off; the first run of turns from the end
 * finds the foot's pixel, and the sub-pixel outline the foot itself
 * (docs/algorithms-recon.md, section 6). */
#include <criterion/criterion.h>
#include <math.h>

#include "celadon/recon.h"
#include "support/pinhole_vessel.h"

/* The profile, in heights: a wall of radius WALL_R with a shallow waist, on
 * a chamfer BEVEL_H tall that takes BEVEL_IN off the radius at the base. */
#define WALL_R 0.713
#define BEVEL_H 0.026
#define BEVEL_IN 0.0174

static double chamfered(double t)
{
    if (t < BEVEL_H)
        return WALL_R - BEVEL_IN * (1 - t / BEVEL_H);
    return WALL_R - 0.03 * sin(M_PI * (t - BEVEL_H) / (1 - BEVEL_H));
}

/* The photo as synth-dev's brush pot was taken: 900 x 1200 px, 12 degrees
 * across, the pot 75% of the width, looking at mid-height. */
static void expect_base_at_the_foot(double elevation_deg, double tol_px)
{
    pinhole_params p = pinhole_defaults(SYNTH_JAR, elevation_deg);
    p.radius = chamfered;
    p.width = 900, p.height = 1200, p.focal_px = 4281;
    p.distance = 2 * WALL_R * p.focal_px / (0.75 * p.width);
    image_t img;
    recon_result truth, res;
    char err[256];
    cr_assert_eq(pinhole_photo(&p, &img, &truth), 0);
    cr_assert_eq(recon_extract(&img, NULL, &res, err, sizeof err), RECON_OK, "at %g deg: %s", elevation_deg, err);
    const int q[2] = {CORNER_BASE_LEFT, CORNER_BASE_RIGHT};
    for (int s = 0; s < 2; s++) {
        vec2 got = res.corners[q[s]], foot = truth.corners[q[s]];
        double off = v2_len(v2_sub(got, foot));
        cr_log_info("chamfer at %g deg: base %s corner (%.1f, %.1f), the foot (%.1f, %.1f): %.2f px off", elevation_deg,
                    s ? "right" : "left", got.x, got.y, foot.x, foot.y, off);
        cr_expect_leq(off, tol_px, "chamfer at %g deg: base %s corner %.2f px from the chamfer's foot", elevation_deg,
                      s ? "right" : "left", off);
    }
    recon_result_free(&res);
    recon_result_free(&truth);
    image_free(&img);
}

/* From a level camera the pixel contour's corner is 3.05 px from the foot
 * (the sharpest turn gave 14 px): a pixel centre past the junction, on the
 * base's ellipse, which the mask's mixed pixels move. Found again on the
 * sub-pixel outline, as the knot where the chamfer's line leaves onto the
 * ellipse (caps.c, corner_knot.c), it is 0.20 px from the foot. */
Test(recon_bevel, chamfer_level, .timeout = 60) { expect_base_at_the_foot(0, 0.5); }

/* Seen from 2 degrees above (5 degrees above the base), the chamfer meets
 * the base's ellipse below the ellipse's end, and the turn the chords
 * measure peaks on the end itself: the pixel contour's corner is 3.4 px from
 * the foot (17 px with the sharpest turn), the knot 0.16 px. */
Test(recon_bevel, chamfer_from_above, .timeout = 60) { expect_base_at_the_foot(2, 0.5); }
