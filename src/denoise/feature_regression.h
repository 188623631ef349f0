/* The denoiser's filter for one buffer (feature_regression.c); the
 * public entry points are in celadon/denoise.h. */
#ifndef CELADON_DENOISE_FEATURE_REGRESSION_H
#define CELADON_DENOISE_FEATURE_REGRESSION_H

#include "celadon/denoise.h"

/* Where each channel of denoise_channel_names lies in a pixel of the
 * denoiser's input (the first DENOISE_CHANNELS for denoise_image, all
 * DENOISE_HALF_CHANNELS for denoise_image_halves; colour at 0). */
enum {
    DENOISE_CH_ALBEDO = 3,
    DENOISE_CH_NORMAL = 6,
    DENOISE_CH_DEPTH = 9,
    DENOISE_CH_VARIANCE = 10,
    DENOISE_CH_HALF = 11,
    DENOISE_CH_SPECULAR = 15,
    DENOISE_CH_SPECULAR_HALF = 18,
    DENOISE_CH_MIRROR = 21
};

/* The features of feature_regression_halves, per pixel: those of
 * denoise_image's input (DENOISE_CHANNELS), then at FEATURE_MIRROR the
 * luminance of the light seen in the mirror direction (render --aov
 * specular, Denoising Mirror), or 0 where it does not count. */
enum { FEATURE_MIRROR = DENOISE_CHANNELS, FEATURE_STRIDE = DENOISE_CHANNELS + 1 };

/* Denoises one buffer given as two independent half-sample renders a and
 * b (3 floats a pixel each), guided by feat (FEATURE_STRIDE floats a
 * pixel: only the albedo, normal, depth and mirror light are read) and by sample_variance (a pixel's sample variance, of the whole:
 * only its shape over the image counts, the halves' difference sets its
 * level): cross-filtered at each of the nk bandwidths ks of the NL-means
 * colour weights (0.45: a pixel's neighbours within about half a standard
 * deviation count), chosen per pixel, the filtered halves averaged into
 * out (3 floats a pixel). Returns 0, or -1 when out of memory (out then
 * undefined). */
int feature_regression_halves(int width, int height, const float *feat, const float *a, const float *b,
                              const double *sample_variance, const double *ks, int nk, float *out);

#endif
