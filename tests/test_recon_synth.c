/* The synthetic vessel drawer against independent truth: the drawn coverage
 * integrates to the analytic area, the outline lies at r(h) from the axis,
 * and files round-trip through the image shim. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "support/synth_vessel.h"

/* Area of the vessel's image, by Simpson's rule on 2 r(h). */
static double analytic_area(const synth_params *p)
{
    const int n = 2000;
    double H = p->height_px, s = 0;
    for (int k = 0; k <= n; k++) {
        double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
        s += w * 2 * synth_radius(p, H * k / n);
    }
    return s * H / n / 3;
}

Test(recon_synth, coverage_integrates_to_area)
{
    for (int shape = 0; shape < SYNTH_SHAPE_COUNT; shape++) {
        synth_params p = synth_defaults(shape, 200, 260);
        p.tilt_deg = shape * 1.5 - 2;
        p.rgba = 1;
        image_t img;
        cr_assert_eq(synth_draw(&p, &img), 0);
        double a = 0;
        for (int i = 0; i < img.width * img.height; i++)
            a += img.data[4 * i + 3];
        double ref = analytic_area(&p);
        cr_assert_float_eq(a, ref, 2e-4 * ref, "shape %d: drawn area %g, analytic %g", shape, a, ref);
        image_free(&img);
    }
}

Test(recon_synth, outline_is_at_profile_radius)
{
    synth_params p = synth_defaults(SYNTH_VASE, 200, 260);
    p.tilt_deg = 3;
    synth_truth t = synth_truth_of(&p);
    cr_assert_float_eq(v2_len(t.axis_direction), 1, 1e-12);
    cr_assert_gt(t.axis_direction.x, 0, "positive tilt leans the rim right");
    /* Mid-height: the outline on the axis-perpendicular line is r(h) away. */
    double h = 0.4 * p.height_px, xl, xr;
    vec2 c = v2_add(t.axis_origin, v2_scale(t.axis_direction, h));
    cr_assert(synth_silhouette_x(&p, c.y, &xl, &xr));
    /* The row is not perpendicular to the axis: compare the distance of the
     * outline point to the axis with r at its own height (fixed point). */
    vec2 n = v2(-t.axis_direction.y, t.axis_direction.x);
    vec2 q = v2_sub(v2(xr, c.y), t.axis_origin);
    cr_assert_float_eq(v2_dot(q, n), synth_radius(&p, v2_dot(q, t.axis_direction)), 1e-7);
}

Test(recon_synth, files_round_trip)
{
    synth_params p = synth_defaults(SYNTH_JAR, 64, 80);
    p.textured = 1;
    image_t img, back;
    cr_assert_eq(synth_draw(&p, &img), 0);
    char path[] = "/tmp/celadon_synth_XXXXXX.png", err[256];
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    cr_assert_eq(synth_write(path, &img, 16, err, sizeof err), 0, "%s", err);
    cr_assert_eq(image_read(path, &back, err, sizeof err), 0, "%s", err);
    cr_assert_eq(back.bits, 16);
    cr_assert_eq(back.width, 64);
    double maxd = 0;
    for (int i = 0; i < 64 * 80 * 3; i++)
        maxd = fmax(maxd, fabs(back.data[i] - img.data[i]));
    cr_assert_lt(maxd, 1.0 / 65535 + 1e-6);
    unlink(path);
    image_free(&img);
    image_free(&back);
}
