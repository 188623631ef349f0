/* The perspective overlay layers on a vase drawn through a pinhole from 10
 * degrees above: the fitted ellipses lie on the true base and rim circles'
 * images, the drawn cross-sections on the images of the true circles at
 * their heights, and nothing is drawn far from them. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/overlay.h"
#include "celadon/recon_camera.h"
#include "support/pinhole_vessel.h"

/* 1 when a pixel within `reach` of p has the colour c. */
static int coloured_near(const uint8_t *rgb, int w, int h, vec2 p, double reach, const uint8_t c[3])
{
    for (int j = (int)floor(p.y - reach); j <= (int)floor(p.y + reach); j++)
        for (int i = (int)floor(p.x - reach); i <= (int)floor(p.x + reach); i++) {
            if (i < 0 || j < 0 || i >= w || j >= h)
                continue;
            const uint8_t *q = rgb + 3 * ((size_t)j * w + i);
            if (abs(q[0] - c[0]) + abs(q[1] - c[1]) + abs(q[2] - c[2]) < 12)
                return 1;
        }
    return 0;
}

Test(overlay_camera, ellipses_and_sections_where_the_circles_are, .timeout = 60)
{
    pinhole_params p = pinhole_defaults(SYNTH_VASE, 10);
    pinhole_shot sh;
    char err[256];
    cr_assert_eq(pinhole_camera(&p, &sh, err, sizeof err), 0, "%s", err);
    int W = p.width, H = p.height;
    uint8_t *rgb = malloc((size_t)W * H * 3);
    memset(rgb, 128, (size_t)W * H * 3);
    cr_assert_eq(overlay_draw_camera(rgb, W, H, &sh.cam, &sh.mer, 3), 0);
    double reach = 1.5; /* the line's half width is 1 px on a photo this size */
    const uint8_t *green = overlay_camera_colours[OVERLAY_CAMERA_ELLIPSES];
    const uint8_t *blue = overlay_camera_colours[OVERLAY_CAMERA_SECTIONS];
    int misses = 0, total = 0;
    for (int k = 0; k < 72; k++) {
        double phi = 2 * M_PI * k / 72;
        for (int c = 0; c < 2; c++) { /* base and rim, all round */
            double R = pinhole_radius(&p, c);
            vec2 q = pinhole_project(&p, v3(R * cos(phi), c, -R * sin(phi)));
            misses += !coloured_near(rgb, W, H, q, reach, green);
            total++;
        }
        if (phi > 0.1 && phi < M_PI - 0.1) { /* the near half of the section at mid-height, solid */
            double R = pinhole_radius(&p, 0.5);
            vec2 q = pinhole_project(&p, v3(R * cos(phi), 0.5, -R * sin(phi)));
            misses += !coloured_near(rgb, W, H, q, reach, blue);
            total++;
        }
    }
    cr_expect_leq(misses, total / 50, "%d of %d points of the true circles have no line within %.1f px", misses,
                  total, reach);
    /* Far from every circle (the image corners) the picture is untouched. */
    cr_expect_eq(rgb[0], 128);
    cr_expect_eq(rgb[3 * ((size_t)H * W - 1)], 128);
    free(rgb);
    pinhole_shot_free(&sh);
}
