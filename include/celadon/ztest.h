/* Mitsuba 3's render test (its src/render/tests/test_renders.py), the
 * statistic by which a render is judged against a reference image of known
 * per-sample variance (docs/validation.md):
 *
 *  1. image, reference and variance go from linear sRGB to CIE XYZ (the
 *     variance by the same matrix, as Mitsuba's Bitmap::convert does);
 *  2. per pixel and channel, z = |mean - ref| * sqrt(spp / max(var, 1e-4)) and
 *     the two-sided p-value p = 2 (1 - Phi(z)), in float32 as Mitsuba does
 *     (so p rounds to 0 beyond z ~ 5.3);
 *  3. the Sidak level alpha = 1 - (1 - 0.01)^(1 / pixel_count);
 *  4. the image passes when (number of channels with p > alpha) / 3 >=
 *     0.9975 * pixel_count. A NaN in the image fails its channel.
 *
 * Images are row-major RGB float triples, pixel_count pixels each. */
#ifndef CELADON_ZTEST_H
#define CELADON_ZTEST_H

#include <stdbool.h>

typedef struct {
    int pixel_count;
    int spp;
    double alpha;          /* Sidak-corrected significance level */
    long passed_channels;  /* channels (of 3 * pixel_count) with p > alpha */
    long failed_pixels;    /* pixels with at least one channel p <= alpha */
    float min_p;           /* smallest p over every channel */
    bool pass;
} ztest_result;

/* Mitsuba's linear sRGB (D65) -> XYZ, one pixel in place. */
void ztest_rgb_to_xyz(float rgb[3]);

/* Runs the test on image `mean` (spp samples per pixel) against `ref` and its
 * per-sample variance `var`, all linear sRGB. When `p_out` is not NULL it
 * receives each channel's p-value (3 * pixel_count floats, XYZ order).
 * pixel_count >= 1, spp >= 1. */
ztest_result ztest_run(const float *mean, const float *ref, const float *var, int pixel_count, int spp,
                       float *p_out);

#endif
