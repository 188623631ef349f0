/* Parts of a render, for any job scheduler (docs/distributed.md): part K of
 * N renders the K-th of N shares of every pixel's samples (sample k of pixel
 * (x, y) draws from its own stream of the sampler, so the shares are exactly
 * the full render's samples) into an OpenEXR that records in its header
 * which share, of which render; render_parts_merge checks that a set of them
 * belongs together and is complete, and sums them into the full render's
 * film, equal to a one-process render up to float rounding.
 *
 * A part's EXR: each channel of the film (R, G, B and the AOVs) as the
 * average of the part's samples, so a part is an image of its own; the
 * channel celadon.weight, each pixel's sum of sample weights; the channels
 * celadon.samples, celadon.luminance and celadon.luminance2, the pixel's own
 * sample count and the sums of their luminance and its square (film_t's
 * samples, for the spp and variance channels); and the string
 * attributes celadon.part ("K/N"), celadon.spp (the full render's),
 * celadon.samples ("first-last", the share), celadon.seed, celadon.scene
 * (scene_digest in hex), celadon.channels (the film's channels in order),
 * celadon.format (hdrfilm's pixel_format: the channels are the film's R, G,
 * B and A whatever the format, converted when the merge writes it) and
 * celadon.complete ("yes", or "no" when the render was interrupted); and the
 * film's metadata (film_metadata), which the merged film gets back. */
#ifndef CELADON_PARTS_H
#define CELADON_PARTS_H

#include <stddef.h>

#include "celadon/film.h"
#include "celadon/scene.h"

typedef struct {
    int k, n; /* the k-th (1 <= k <= n) of n shares */
} render_part;

enum { RENDER_PARTS_MAX = 1000000 };

/* "K/N" with 1 <= K <= N <= RENDER_PARTS_MAX: 0, or -1. */
int render_part_parse(const char *text, render_part *out);

/* The samples [*s0, *s1) of part p of a render of spp samples per pixel: the
 * shares differ by at most one sample. Returns 0, or -1 when p gets none
 * (more parts than samples). */
int render_part_samples(render_part p, int spp, int *s0, int *s1);

/* Writes the film of part p of the render of s (rendered with the sample
 * range of render_part_samples) to path, an .exr, atomically; complete is 0
 * for an interrupted render (merge refuses it). Returns 0 or -1 with a
 * one-line reason naming the file. */
int render_part_write(const film_t *film, const scene_t *s, render_part p, int complete, const char *path, char *err,
                      size_t errlen);

/* Reads the n part files, checks that they are parts of one render (same
 * scene digest, seed, spp, number of parts, size and channels) and, when
 * `of` is not NULL, of a render of that scene (its digest and seed),
 * complete, each share once and none missing, and sums them (in share
 * order) into film, which is film_init'ed here (film_free it). Returns 0;
 * -2 when the set is refused (a file that is no part, a part of another
 * render, an incomplete, duplicated or missing part, a part whose pixels
 * cannot be decoded: damaged or truncated), with one line in err
 * naming the file or the missing shares; -1 on other failures. */
int render_parts_merge(const char *const *paths, int n, const scene_t *of, film_t *film, char *err, size_t errlen);

#endif
