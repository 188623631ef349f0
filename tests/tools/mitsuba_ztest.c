/* Judges one render against a Mitsuba 3 reference image by Mitsuba's own
 * render test (include/celadon/ztest.h); tools/check-mitsuba.sh runs it on
 * every reference scene of mitsuba-data.
 *
 *   mitsuba_ztest --size REF.exr
 *       prints "WIDTH HEIGHT" of the reference;
 *   mitsuba_ztest IMG.exr REF.exr VAR.exr SPP [SIDE.png]
 *       prints "pass|FAIL FAILED_PIXELS PIXELS MIN_P ALPHA MEAN_Y_RATIO" and,
 *       when the image fails and SIDE.png is given, writes celadon | Mitsuba |
 *       z map side by side (sRGB, clamped; the z map grey by -log10 p up to
 *       the Sidak level, the failing pixels red).
 *
 * Exit status 0 (whatever the verdict), 2 on a bad file or argument. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/image.h"
#include "celadon/ztest.h"

static void die(const char *file, const char *problem)
{
    fprintf(stderr, "celadon: %s: %s\n", file, problem);
    exit(2);
}

/* The first three channels of an image, as packed RGB. */
static float *read_rgb(const char *path, int *w, int *h)
{
    image_t img;
    char err[256];
    if (image_read(path, &img, err, sizeof err) != 0)
        die(path, err);
    if (img.channels < 3)
        die(path, "fewer than 3 channels");
    float *rgb = malloc(sizeof(float) * 3 * (size_t)img.width * img.height);
    for (size_t i = 0; i < (size_t)img.width * img.height; i++)
        memcpy(rgb + 3 * i, img.data + img.channels * i, 3 * sizeof(float));
    *w = img.width, *h = img.height;
    image_free(&img);
    return rgb;
}

static uint8_t srgb8(float v)
{
    v = v > 0.0f ? v : 0.0f;
    v = v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)lrintf(255.0f * (v < 1.0f ? v : 1.0f));
}

/* Three panels of w x h, each magnified s times, 4 px apart. */
static void write_side_by_side(const char *path, const float *img, const float *ref, const float *p, int w,
                               int h, double alpha)
{
    int s = w < 256 ? (256 + w - 1) / w : 1, gap = 4, W = 3 * w * s + 2 * gap, H = h * s;
    uint8_t *px = calloc((size_t)W * H * 3, 1);
    double lmax = -log10(alpha);
    for (int y = 0; y < H; y++)
        for (int panel = 0; panel < 3; panel++)
            for (int x = 0; x < w * s; x++) {
                size_t i = (size_t)(y / s) * w + x / s;
                uint8_t *o = px + 3 * ((size_t)y * W + panel * (w * s + gap) + x);
                if (panel < 2) {
                    const float *src = panel == 0 ? img : ref;
                    for (int c = 0; c < 3; c++)
                        o[c] = srgb8(src[3 * i + c]);
                    continue;
                }
                float pmin = fminf(fminf(p[3 * i], p[3 * i + 1]), p[3 * i + 2]);
                if (!(pmin > alpha)) {
                    o[0] = 255, o[1] = o[2] = 0;
                } else {
                    double l = -log10(fmax(pmin, 1e-300)) / lmax;
                    o[0] = o[1] = o[2] = (uint8_t)lrint(200.0 * (l < 1.0 ? l : 1.0));
                }
            }
    char err[256];
    if (image_write_u8(path, W, H, 3, px, err, sizeof err) != 0)
        die(path, err);
    free(px);
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--size") == 0) {
        int w, h;
        free(read_rgb(argv[2], &w, &h));
        printf("%d %d\n", w, h);
        return 0;
    }
    if (argc != 5 && argc != 6) {
        fprintf(stderr, "usage: mitsuba_ztest IMG.exr REF.exr VAR.exr SPP [SIDE.png] | --size REF.exr\n");
        return 2;
    }
    char *end;
    long spp = strtol(argv[4], &end, 10);
    if (*end || spp < 1 || spp > 1000000000)
        die(argv[4], "SPP is not a positive integer");
    int w, h, wr, hr, wv, hv;
    float *img = read_rgb(argv[1], &w, &h), *ref = read_rgb(argv[2], &wr, &hr), *var = read_rgb(argv[3], &wv, &hv);
    if (w != wr || h != hr || wv != wr || hv != hr)
        die(argv[1], "the image, the reference and the variance differ in size");
    int n = w * h;
    float *p = malloc(sizeof(float) * 3 * n);
    ztest_result r = ztest_run(img, ref, var, n, (int)spp, p);
    double yi = 0.0, yr = 0.0;
    for (int i = 0; i < n; i++) {
        float a[3] = {img[3 * i], img[3 * i + 1], img[3 * i + 2]}, b[3] = {ref[3 * i], ref[3 * i + 1], ref[3 * i + 2]};
        ztest_rgb_to_xyz(a), ztest_rgb_to_xyz(b);
        yi += a[1], yr += b[1];
    }
    printf("%s %ld %d %.3g %.3g %.4f\n", r.pass ? "pass" : "FAIL", r.failed_pixels, n, (double)r.min_p, r.alpha,
           yr != 0.0 ? yi / yr : 0.0);
    if (!r.pass && argc == 6)
        write_side_by_side(argv[5], img, ref, p, w, h, r.alpha);
    free(img), free(ref), free(var), free(p);
    return 0;
}
