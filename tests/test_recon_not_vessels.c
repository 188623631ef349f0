/* recon_extract refuses outlines that are not a vessel's (a flat rim and a
 * flat base joined by side walls): discs, ellipses, diamonds, triangles and
 * boxes with large rounded corners, drawn anti-aliased here; every drawn
 * vessel shape, also small, is still accepted. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "celadon/recon.h"
#include "support/synth_vessel.h"

/* Inside tests in a frame centred on (cx, cy) with half sizes (a, b). */
typedef int (*inside_fn)(double x, double y, double a, double b, double extra);

static int in_ellipse(double x, double y, double a, double b, double extra)
{
    (void)extra;
    return (x / a) * (x / a) + (y / b) * (y / b) < 1;
}

static int in_diamond(double x, double y, double a, double b, double extra)
{
    (void)extra;
    return fabs(x) / a + fabs(y) / b < 1;
}

/* Apex up, base down. */
static int in_triangle(double x, double y, double a, double b, double extra)
{
    (void)extra;
    double t = (y + b) / (2 * b);
    return t >= 0 && t <= 1 && fabs(x) < t * a;
}

/* Box with corners rounded to radius `extra`. */
static int in_rounded_box(double x, double y, double a, double b, double rad)
{
    double dx = fabs(x) - (a - rad), dy = fabs(y) - (b - rad);
    if (dx <= 0 || dy <= 0)
        return fabs(x) < a && fabs(y) < b;
    return hypot(dx, dy) < rad;
}

/* Dark shape on a light backdrop, 4x4 supersampled; rotated by rot_deg. */
static image_t draw(int w, int h, inside_fn f, double a, double b, double extra, double rot_deg)
{
    image_t img = image_alloc(w, h, 3);
    double c = cos(rot_deg * M_PI / 180), s = sin(rot_deg * M_PI / 180);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int hits = 0;
            for (int sy = 0; sy < 4; sy++)
                for (int sx = 0; sx < 4; sx++) {
                    double x = i + (sx + 0.5) / 4 - 0.5 * w, y = j + (sy + 0.5) / 4 - 0.5 * h;
                    hits += f(c * x + s * y, -s * x + c * y, a, b, extra);
                }
            float v = 0.94f - 0.7f * hits / 16.0f;
            for (int k = 0; k < 3; k++)
                img.data[((size_t)j * w + i) * 3 + k] = v;
        }
    return img;
}

static void expect_refused(const char *what, image_t img)
{
    recon_options opt = {-1, RECON_SIDE_AUTO};
    recon_result r;
    char err[256] = "";
    recon_status st = recon_extract(&img, &opt, &r, err, sizeof err);
    cr_log_info("%-22s -> %d %s", what, st, err);
    cr_expect_eq(st, RECON_ERR_CORNERS, "%s accepted as a vessel (tilt %.2f°)", what, r.tilt_deg);
    cr_expect_gt(strlen(err), 0, "%s: a refusal says why", what);
    cr_expect_null(r.mask, "%s: a refusal leaves no arrays", what);
    recon_result_free(&r);
    image_free(&img);
}

Test(recon_not_vessels, discs_and_ellipses)
{
    expect_refused("disc r12", draw(100, 100, in_ellipse, 12, 12, 0, 0));
    expect_refused("disc r20", draw(120, 120, in_ellipse, 20, 20, 0, 0));
    expect_refused("disc r75", draw(200, 200, in_ellipse, 75, 75, 0, 0));
    expect_refused("ellipse wide", draw(240, 200, in_ellipse, 80, 40, 0, 0));
    expect_refused("ellipse tall", draw(200, 240, in_ellipse, 40, 80, 0, 0));
    expect_refused("ellipse tilted 10", draw(240, 240, in_ellipse, 45, 85, 0, 10));
}

Test(recon_not_vessels, diamonds_and_triangles)
{
    expect_refused("diamond square", draw(200, 200, in_diamond, 60, 60, 0, 0));
    expect_refused("diamond tall", draw(200, 240, in_diamond, 50, 80, 0, 0));
    expect_refused("diamond wide", draw(240, 200, in_diamond, 80, 50, 0, 0));
    expect_refused("triangle", draw(200, 220, in_triangle, 60, 70, 0, 0));
    expect_refused("triangle upside down", draw(200, 220, in_triangle, 60, 70, 0, 180));
}

Test(recon_not_vessels, rounded_boxes)
{
    expect_refused("box 120x160 r25", draw(200, 240, in_rounded_box, 60, 80, 25, 0));
    expect_refused("box 160x120 r40", draw(240, 200, in_rounded_box, 80, 60, 40, 0));
    expect_refused("box 120x160 r30 tilted", draw(220, 240, in_rounded_box, 60, 80, 30, 4));
}

/* The refusals must not catch vessels: every drawn shape, tilted both ways
 * and small, is accepted with its tilt. */
Test(recon_not_vessels, drawn_vessels_still_accepted)
{
    for (int shape = 0; shape < SYNTH_SHAPE_COUNT; shape++)
        for (int t = -1; t <= 1; t++) {
            synth_params p = synth_defaults((synth_shape)shape, t ? 200 : 120, t ? 240 : 150);
            p.tilt_deg = 3 * t;
            image_t img;
            cr_assert_eq(synth_draw(&p, &img), 0);
            recon_options opt = {-1, RECON_SIDE_AUTO};
            recon_result r;
            char err[256] = "";
            recon_status st = recon_extract(&img, &opt, &r, err, sizeof err);
            cr_expect_eq(st, RECON_OK, "shape %d tilt %d: %s", shape, 3 * t, err);
            if (st == RECON_OK)
                cr_expect_lt(fabs(r.tilt_deg - p.tilt_deg), 0.1, "shape %d: tilt %.3f", shape, r.tilt_deg);
            recon_result_free(&r);
            image_free(&img);
        }
}
