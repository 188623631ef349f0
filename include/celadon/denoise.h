/* Feature-guided denoising of a path-traced image (docs/rendering.md,
 * "Denoising"): first-order regression in the manner of NFOR (Bitterli et
 * al. 2016). Each pixel's colour is the intercept of a weighted linear
 * regression of its neighbours' colours on their features (screen offset,
 * albedo, normal, depth) relative to its own; the weights are non-local
 * means distances of 3x3 colour patches normalised by the pixels'
 * variance (Rousselle et al. 2012), times a closeness in the features,
 * times the inverse of the neighbour's variance relative to the pixel's
 * where it is the noisier. With two independent half-sample renders
 * (render --aov half), as NFOR: each half is regressed with weights from
 * the other's patches (cross-filtering), at three bandwidths of the
 * patch weights; per pixel, the bandwidth whose error the halves estimate
 * least (averaged over 7x7 pixels) is kept, and the two filtered halves
 * averaged. The colour's diffuse and specular parts (render --aov
 * specular) are denoised so apart, the diffuse divided by the albedo
 * first and multiplied by it after, the specular regressed on the light
 * seen in the mirror direction too, and summed; fireflies that one half
 * alone holds are clamped first.
 *
 * What the regression keeps: an image that is exactly linear in the
 * features over a window is reproduced (up to the ridge's 1e-4 relative
 * shrinkage), and so is an antialiased edge whose pixels mix two sides in
 * the same proportion in colour as in features; what it removes is noise
 * the features do not explain. Images are float, interleaved, row-major
 * from the top left. */
#ifndef CELADON_DENOISE_H
#define CELADON_DENOISE_H

#include <stddef.h>

#include "celadon/film.h"

/* The channels the denoiser reads, in this order, per pixel: colour,
 * albedo (3), normal (3), depth, the variance of the colour's estimate
 * (DENOISE_CHANNELS of them), then, for denoise_image_halves, the first
 * half of the samples, premultiplied by its share of the pixel (4: R, G,
 * B, A; render.h, RENDER_AOV_HALF), the colour's specular part (3),
 * its first half (3, premultiplied alike) and the light seen in the
 * mirror direction at the first rough vertex (3; RENDER_AOV_SPECULAR).
 * denoise_channel_names has the names the renderer's EXR gives them
 * (docs/rendering.md, "AOVs"): R, G, B, Denoising Albedo.R/G/B, Denoising
 * Normal.X/Y/Z, Denoising Depth.Z (the features at the first rough
 * vertex), variance.X, half.R/G/B/A, specular.R/G/B, specular
 * half.R/G/B, Denoising Mirror.R/G/B. */
enum { DENOISE_CHANNELS = 11, DENOISE_HALF_CHANNELS = 24 };
extern const char *const denoise_channel_names[DENOISE_HALF_CHANNELS];

/* Denoises the RGB of in (width * height * DENOISE_CHANNELS floats, as
 * above) into out (width * height * 3 floats; not in). Pixels whose values
 * are not finite are taken as they are. width, height >= 1. Uses OpenMP's
 * threads; the result does not depend on their count. Returns 0, or -1
 * when out of memory (out then undefined). */
int denoise_image(int width, int height, const float *in, float *out);
/* The same from two halves and the specular part: in has
 * DENOISE_HALF_CHANNELS floats a pixel. Where a half's share is below 5%
 * or above 95% (an interrupted render), both halves are taken as the
 * whole pixel. */
int denoise_image_halves(int width, int height, const float *in, float *out);

/* What a denoised image's "celadon/denoised" attribute says. */
#define DENOISE_DESCRIPTION                                                                                           \
    "first-order feature regression (NFOR-like) on the rough vertex's albedo, N, depth; diffuse, specular apart; " \
    "halves crossed"

/* Denoises the film's colour in place (render --denoise) from two halves:
 * the film needs the denoising and half AOVs (RENDER_AOV_DENOISING,
 * RENDER_AOV_HALF, render.h) and the variance (FILM_EXTRA_VARIANCE); its
 * other channels, the variance among them, stay those of the render. Sets
 * f->meta.denoised. Returns 0, or -1 with the missing channel named in err. */
int denoise_film(film_t *f, char *err, size_t errlen);

/* Reads the OpenEXR in_path (a render with the channels of
 * denoise_channel_names), denoises its R, G, B from its halves and writes every channel to
 * the OpenEXR out_path (whole or not at all), its header the input's plus
 * "celadon/denoised". Returns 0; -2 when in_path is not such a file, with
 * "IN: problem" in err (every missing channel named); -1 when out_path
 * cannot be written, with "OUT: problem". */
int denoise_exr(const char *in_path, const char *out_path, char *err, size_t errlen);

#endif
