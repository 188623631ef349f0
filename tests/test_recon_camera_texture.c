/* The texture by the camera on a checkerboard-textured vessel photographed
 * from 10 degrees above (tests/support/pinhole_vessel): 8 height bands x 16
 * sectors of 22.5 degrees on the wall must unroll to straight, evenly
 * spaced lines: band boundaries at rows (1 - k/8) H, sector boundaries at
 * columns (1 - m/8) W. The scanline texture of the same photo is measured
 * too: its band boundaries follow the imaged circles and bend by several
 * texels, so the measure can tell. Texels the camera saw at a grazing angle
 * (within a fifth of the width of the outline) are left out of the
 * measure, and so are the lines next to a boundary of the other kind. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "celadon/recon_camera.h"
#include "celadon/recon_texture.h"
#include "celadon/reconstruct.h"
#include "support/pinhole_vessel.h"
#include "support/scratch_dir.h"

enum { BANDS = 8, SECTORS = 16 };

typedef struct {
    double worst_row_dev;  /* largest distance of a band boundary crossing from its boundary's mean row */
    double worst_spacing;  /* largest departure of the boundaries' mean rows from (1 - k/8) H */
    double worst_col_dev;  /* the same for sector boundaries, columns */
    double worst_col_spacing;
    int crossings;
} straightness;

static double luma(const uint8_t *p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }

/* Where the luminance crosses the mid level between i and i + 1 along a
 * line of texels (stride apart), near `expect` (within `reach`); NAN when it
 * does not. */
static double crossing(const uint8_t *rgb, int n, int stride, double expect, double reach, double mid)
{
    double best = NAN;
    for (int i = (int)fmax(0, expect - reach); i + 1 < n && i <= expect + reach; i++) {
        double a = luma(rgb + 3 * (size_t)i * stride) - mid, b = luma(rgb + 3 * (size_t)(i + 1) * stride) - mid;
        if (a * b < 0) {
            double x = i + 0.5 + a / (a - b); /* texel centres are at i + 0.5 */
            if (isnan(best) || fabs(x - expect) < fabs(best - expect))
                best = x;
        }
    }
    return best;
}

/* One boundary, expected at `expect` texels along the lines of one family
 * (columns for a band boundary, rows for a sector boundary), lines first..last:
 * its crossing on each line, except on the lines next to a boundary of the
 * other family (the fraction `other` of the way through its period within
 * 0.1 of a whole number: the colours swap there). *dev: the largest distance
 * of a crossing from their mean, *off: the mean's distance from `expect`;
 * missing on more than a tenth of the lines: both infinite. Returns the
 * number found. */
static int boundary(const recon_texture_t *t, int columns, int first, int last, double periods, double expect,
                    double reach, double mid, double *dev, double *off)
{
    int W = t->width, H = t->height, n = 0, tried = 0;
    double sum = 0, *x = malloc((size_t)(last - first + 1) * sizeof *x);
    for (int k = first; k <= last; k++) {
        double f = fmod((1.0 - (k + 0.5) / (columns ? W : H)) * periods, 1.0);
        if (f < 0.1 || f > 0.9)
            continue;
        tried++;
        x[n] = columns ? crossing(t->rgb + 3 * (size_t)k, H, W, expect, reach, mid)
                       : crossing(t->rgb + 3 * (size_t)k * W, W, 1, expect, reach, mid);
        if (!isnan(x[n]))
            sum += x[n++];
    }
    *dev = *off = INFINITY;
    if (n >= tried * 9 / 10 && n > 0) {
        double mean = sum / n;
        *dev = 0;
        for (int q = 0; q < n; q++)
            *dev = fmax(*dev, fabs(x[q] - mean));
        *off = fabs(mean - expect);
    }
    free(x);
    return n;
}

/* Measures a texture: band boundaries along the columns of the middle
 * u in [0.2, 0.8], sector boundaries (u = 0.25, 0.5, 0.75) along the rows
 * of v in [0.1, 0.9]. reach: how far from its ideal place a boundary is
 * looked for. */
static straightness measure(const recon_texture_t *t, double mid, double reach)
{
    straightness s = {0};
    int W = t->width, H = t->height;
    for (int k = 1; k < BANDS; k++) {
        double dev, off;
        s.crossings += boundary(t, 1, (int)(0.2 * W), (int)(0.8 * W), SECTORS / 2.0, (1.0 - (double)k / BANDS) * H,
                                reach, mid, &dev, &off);
        s.worst_row_dev = fmax(s.worst_row_dev, dev);
        s.worst_spacing = fmax(s.worst_spacing, off);
    }
    for (int m = 3; m <= 5; m++) {
        double dev, off;
        s.crossings += boundary(t, 0, (int)(0.1 * H), (int)(0.9 * H), BANDS, (1.0 - 2.0 * m / SECTORS) * W, reach,
                                mid, &dev, &off);
        s.worst_col_dev = fmax(s.worst_col_dev, dev);
        s.worst_col_spacing = fmax(s.worst_col_spacing, off);
    }
    return s;
}

Test(recon_camera_texture, checkerboard_unrolls_straight, .timeout = 180)
{
    pinhole_params p = pinhole_defaults(SYNTH_JAR, 10);
    p.checker_bands = BANDS;
    p.checker_sectors = SECTORS;
    pinhole_shot sh;
    char err[256];
    cr_assert_eq(pinhole_camera(&p, &sh, err, sizeof err), 0, "%s", err);
    recon_texture_t ours, scan;
    cr_assert_eq(recon_texture_from_camera(&sh.img, &sh.cam, &sh.mer, NULL, &ours, err, sizeof err), 0, "%s", err);
    cr_assert_eq(recon_texture_from_photo(&sh.img, &sh.res, &scan, err, sizeof err), 0, "%s", err);
    double mid = 255 * 0.5 * (0.299 * (p.fg[0] + p.fg2[0]) + 0.587 * (p.fg[1] + p.fg2[1]) +
                              0.114 * (p.fg[2] + p.fg2[2]));

    /* Ours: straight and evenly spaced within a texel. */
    straightness s = measure(&ours, mid, 0.4 * ours.height / BANDS);
    cr_log_info("camera texture %dx%d: band rows within %.2f of straight, %.2f of evenly spaced; sector columns "
                "within %.2f, %.2f (%d crossings)",
                ours.width, ours.height, s.worst_row_dev, s.worst_spacing, s.worst_col_dev, s.worst_col_spacing,
                s.crossings);
    cr_expect_leq(s.worst_row_dev, 1.0, "a band boundary bends by %.2f texels", s.worst_row_dev);
    cr_expect_leq(s.worst_spacing, 1.0, "a band boundary is %.2f texels from its place", s.worst_spacing);
    cr_expect_leq(s.worst_col_dev, 1.0, "a sector boundary bends by %.2f texels", s.worst_col_dev);
    cr_expect_leq(s.worst_col_spacing, 1.0, "a sector boundary is %.2f texels from its place", s.worst_col_spacing);

    /* The texels near the outline are marked unseen, those facing the
     * camera seen. */
    int W = ours.width, H = ours.height;
    cr_expect_eq(ours.seen[(size_t)(H / 2) * W + W / 2], 1);
    cr_expect_eq(ours.seen[(size_t)(H / 2) * W], 0, "the texel at the left outline is grazing");
    cr_expect_null(scan.seen);

    /* Scanlines: the band boundaries bend with the imaged circles. */
    straightness t = measure(&scan, mid, 0.45 * scan.height / BANDS);
    cr_log_info("scanline texture %dx%d: band rows within %.2f of straight", scan.width, scan.height,
                t.worst_row_dev);
    cr_expect_gt(t.worst_row_dev, 4.0, "the scanline texture is nearly straight too (%.2f): the test would not "
                                        "tell", t.worst_row_dev);
    recon_texture_free(&ours);
    recon_texture_free(&scan);
    pinhole_shot_free(&sh);
}

Test(recon_camera_texture, reconstruct_writes_what_the_camera_saw, .timeout = 180)
{
    /* Through the pipeline: texture_seen.png beside texture.png, the same
     * size, 255 where the camera saw the texel and 0 where it did not: the
     * texels at both outlines (grazing) unseen, the front meridian seen. */
    pinhole_params p = pinhole_defaults(SYNTH_JAR, 10);
    image_t img;
    cr_assert_eq(pinhole_draw(&p, &img, NULL), 0);
    char dir[64], path[128], err[256];
    scratch_dir_make(dir, sizeof dir, "seen");
    snprintf(path, sizeof path, "%s/jar.png", dir);
    size_t n = (size_t)img.width * img.height * 3;
    uint8_t *u8 = malloc(n);
    for (size_t i = 0; i < n; i++)
        u8[i] = (uint8_t)lround(255 * fmin(fmax(img.data[i], 0), 1));
    cr_assert_eq(image_write_u8(path, img.width, img.height, 3, u8, err, sizeof err), 0, "%s", err);
    free(u8);
    image_free(&img);
    reconstruct_options opt = reconstruct_options_default();
    reconstruction r;
    cr_assert_eq(reconstruct_photo(path, &opt, &r, err, sizeof err), 0, "%s", err);
    cr_assert(reconstruction_is_perspective(&r), "no perspective camera");
    snprintf(path, sizeof path, "%s/out", dir);
    cr_assert_eq(reconstruct_write(&r, "jar.png", path, &opt, err, sizeof err), 0, "%s", err);
    reconstruction_free(&r);
    image_t tex, seen;
    snprintf(path, sizeof path, "%s/out/texture.png", dir);
    cr_assert_eq(image_read(path, &tex, err, sizeof err), 0, "%s", err);
    snprintf(path, sizeof path, "%s/out/texture_seen.png", dir);
    cr_assert_eq(image_read(path, &seen, err, sizeof err), 0, "%s", err);
    cr_assert(seen.width == tex.width && seen.height == tex.height && seen.channels == 1, "%dx%dx%d for %dx%d",
              seen.width, seen.height, seen.channels, tex.width, tex.height);
    int W = seen.width, H = seen.height, unseen = 0;
    for (int i = 0; i < W * H; i++)
        unseen += seen.data[i] < 0.5f;
    cr_expect_gt(seen.data[(size_t)(H / 2) * W + W / 2], 0.5f, "the front meridian is seen");
    cr_expect_lt(seen.data[(size_t)(H / 2) * W], 0.5f, "the left outline is grazing");
    cr_expect_lt(seen.data[(size_t)(H / 2) * W + W - 1], 0.5f, "the right outline is grazing");
    cr_expect(unseen > 0 && unseen < W * H / 4, "%d of %d texels unseen", unseen, W * H);
    image_free(&tex);
    image_free(&seen);
    scratch_dir_remove(dir);
}
