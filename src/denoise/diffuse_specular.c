/* denoise_image_halves (celadon/denoise.h): the colour split into its
 * diffuse and specular parts (render --aov specular), each denoised on its
 * own (feature_regression.h) and summed, as production denoisers do
 * (Cycles, OIDN; Zimmer et al. 2015 "Path-space motion estimation and
 * decomposition", Bako et al. 2017 "Kernel-predicting convolutional
 * networks" split diffuse from specular and divide the diffuse part by
 * the albedo). The diffuse part is demodulated: divided by the first
 * rough vertex's albedo, what is left is the light falling there, smooth
 * across a texture's edges, then multiplied back. The specular part has
 * one more feature: the light seen in the mirror direction at the first
 * rough vertex (Denoising Mirror), which says where a coat's highlights
 * are in every pixel, while only the few samples that chose the coat's
 * delta lobe carry them.
 *
 * Fireflies (a rare path of high weight: a caustic through glass, light
 * off a glossy lobe) are clamped first, within the denoiser only: a
 * half's pixel is cut down to FIREFLY times the brightest pixel of the
 * other half around it. A feature that is really there shows in both
 * independent halves and passes; a sample that one half alone drew is cut.
 * This loses energy (a bias) but less and less as the samples grow, both
 * halves nearing the same image (consistent), as outlier rejection does
 * (DeCoro et al. 2010 "Density-based outlier rejection in Monte Carlo
 * rendering"; Zirr et al. 2018 "Re-weighting firefly samples"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "denoise/feature_regression.h"

const char *const denoise_channel_names[DENOISE_HALF_CHANNELS] = {
    "R",          "G",          "B",          "Denoising Albedo.R", "Denoising Albedo.G", "Denoising Albedo.B",
    "Denoising Normal.X",       "Denoising Normal.Y",       "Denoising Normal.Z", "Denoising Depth.Z",
    "variance.X", "half.R",     "half.G",     "half.B",     "half.A",     "specular.R", "specular.G", "specular.B",
    "specular half.R",          "specular half.G",          "specular half.B",          "Denoising Mirror.R",
    "Denoising Mirror.G",       "Denoising Mirror.B"};

/* A half whose share of the pixel's weight is outside [MIN_SHARE, 1 -
 * MIN_SHARE] (an interrupted render) tells too little: both halves are
 * then taken as the whole. */
static const double MIN_SHARE = 0.05;
/* The diffuse part is divided by the albedo, but by no less than this: a
 * black albedo (or none: the path escaped) leaves little to demodulate. */
static const double MIN_ALBEDO = 0.02;
/* A half's pixel (the sum of its channels) is clamped to this times the
 * largest of the other half's over its 3x3 neighbourhood. */
static const double FIREFLY = 2.0;
/* The NL-means bandwidths each part's filter chooses among per pixel:
 * where the halves' error estimate says so, a part takes the wide filter
 * (k = 2: the demodulated diffuse part is smooth, light falling on
 * surfaces). Without the mirror light, k = 2 blurred the specular part's
 * highlights (studio's relMSE 0.000125 with {0.45, 1} for the specular
 * part, 0.000143 with {0.45, 1, 2}); with it, {0.45, 1, 2} gives 0.000072,
 * {0.45, 1} 0.000091. */
static const double K_PARTS[] = {0.45, 1.0, 2.0};

/* What the diffuse part of pixel v is divided by, channel c. */
static double demodulation(const float *v, int c)
{
    double a = v[DENOISE_CH_ALBEDO + c];
    return isfinite(a) && a > MIN_ALBEDO ? a : MIN_ALBEDO;
}

/* The two halves of a part of each pixel, each divided by d: a =
 * half / A, b = (whole - half) / (1 - A), where whole and half are the
 * specular channels, or the colour less them (diffuse); and the sample
 * variance over the mean d^2. */
static void split_part(int w, int h, const float *in, int specular, float *a, float *b, double *sample)
{
    for (size_t p = 0; p < (size_t)w * h; p++) {
        const float *v = in + p * DENOISE_HALF_CHANNELS;
        double share = v[DENOISE_CH_HALF + 3], d2 = 0;
        int both = isfinite(share) && share >= MIN_SHARE && share <= 1.0 - MIN_SHARE;
        for (int c = 0; c < 3; c++) {
            double whole = specular ? v[DENOISE_CH_SPECULAR + c] : (double)v[c] - v[DENOISE_CH_SPECULAR + c];
            double half = specular ? v[DENOISE_CH_SPECULAR_HALF + c]
                                   : (double)v[DENOISE_CH_HALF + c] - v[DENOISE_CH_SPECULAR_HALF + c];
            double d = specular ? 1.0 : demodulation(v, c);
            a[3 * p + c] = (float)((both ? half / share : whole) / d);
            b[3 * p + c] = (float)((both ? (whole - half) / (1.0 - share) : whole) / d);
            d2 += d * d / 3;
        }
        double s = v[DENOISE_CH_VARIANCE];
        sample[p] = isfinite(s) && s > 0 ? s / d2 : 0.0;
    }
}

/* FIREFLY times the largest sum of channels of b over each pixel's 3x3
 * neighbourhood, into bound. */
static void firefly_bound(int w, int h, const float *b, double *bound)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double m = 0;
            for (int yy = y > 0 ? y - 1 : 0; yy <= y + 1 && yy < h; yy++)
                for (int xx = x > 0 ? x - 1 : 0; xx <= x + 1 && xx < w; xx++) {
                    const float *q = b + 3 * ((size_t)yy * w + xx);
                    double s = (double)q[0] + q[1] + q[2];
                    m = s > m ? s : m; /* NaN stays out */
                }
            bound[(size_t)y * w + x] = FIREFLY * m;
        }
}

/* Each pixel of a whose sum of channels passes its bound, scaled down to
 * it. */
static void clamp_to(size_t n, float *a, const double *bound)
{
    for (size_t p = 0; p < n; p++) {
        double s = (double)a[3 * p] + a[3 * p + 1] + a[3 * p + 2];
        if (s > bound[p])
            for (int c = 0; c < 3; c++)
                a[3 * p + c] = (float)(a[3 * p + c] * (bound[p] / s));
    }
}

int denoise_image_halves(int width, int height, const float *in, float *out)
{
    size_t n = (size_t)width * height;
    float *feat = malloc(sizeof *feat * n * FEATURE_STRIDE), *a = malloc(sizeof *a * n * 3),
          *b = malloc(sizeof *b * n * 3), *part = malloc(sizeof *part * n * 3);
    double *sample = malloc(sizeof *sample * n), *bound_a = malloc(sizeof *bound_a * n),
           *bound_b = malloc(sizeof *bound_b * n);
    int rc = feat && a && b && part && sample && bound_a && bound_b ? 0 : -1;
    for (int specular = 0; specular < 2 && rc == 0; specular++) {
        /* The light seen in the mirror direction explains where a coat's
         * highlight is: a feature of the specular part only. */
        for (size_t p = 0; p < n; p++) {
            const float *v = in + p * DENOISE_HALF_CHANNELS;
            memcpy(feat + p * FEATURE_STRIDE, v, DENOISE_CHANNELS * sizeof *feat);
            feat[p * FEATURE_STRIDE + FEATURE_MIRROR] =
                specular ? (v[DENOISE_CH_MIRROR] + v[DENOISE_CH_MIRROR + 1] + v[DENOISE_CH_MIRROR + 2]) / 3 : 0.0f;
        }
        split_part(width, height, in, specular, a, b, sample);
        firefly_bound(width, height, b, bound_a);
        firefly_bound(width, height, a, bound_b);
        clamp_to(n, a, bound_a);
        clamp_to(n, b, bound_b);
        rc = feature_regression_halves(width, height, feat, a, b, sample, K_PARTS, 3, part);
        for (size_t p = 0; p < n && rc == 0; p++)
            for (int c = 0; c < 3; c++) {
                double d = specular ? 1.0 : demodulation(in + p * DENOISE_HALF_CHANNELS, c);
                out[3 * p + c] = (float)((specular ? out[3 * p + c] : 0.0) + part[3 * p + c] * d);
            }
    }
    free(feat), free(a), free(b), free(part), free(sample), free(bound_a), free(bound_b);
    return rc;
}
