/* The film: per-pixel sums of RGB radiance plus optional AOV channels, and
 * their output as float32 OpenEXR or tonemapped 8-bit PNG/JPEG.
 *
 * Reconstruction is a box of one pixel: a sample counts, with its weight,
 * only in the pixel it falls in, so disjoint pixel sets can be rendered by
 * different threads without locks (or threads can render into films of
 * their own and film_merge them). A film can be written whenever no thread
 * is adding to it, e.g. after Ctrl-C stopped a render between passes:
 * pixels that have no samples yet are written black. */
#ifndef CELADON_FILM_H
#define CELADON_FILM_H

#include <stddef.h>
#include <stdint.h>

/* An extra output: channels is 1 or 3, written as "<name>.<suffix>" with
 * one suffix per channel ("T" for a depth, "X", "Y", "Z" for a vector, as
 * Mitsuba's `aov` integrator names them), or, without suffixes, as
 * "<name>.Y" or "<name>.R", "<name>.G", "<name>.B". */
typedef struct {
    const char *name;
    int channels;
    const char *const *suffixes; /* NULL: Y or R, G, B */
} film_aov;

typedef struct {
    int width, height;
    int nchannels;  /* 3 (R, G, B) + the AOV channels, in that order */
    char **names;   /* the EXR channel name of each channel */
    double *sum;    /* weighted sums, width * height * nchannels, row-major from the top-left */
    double *weight; /* sum of sample weights, width * height */
} film_t;

/* Returns 0, or -1 with a reason (bad size, bad AOV). */
int film_init(film_t *f, int width, int height, const film_aov *aovs, int naovs, char *err, size_t errlen);
void film_free(film_t *f);

/* Adds weight · values (nchannels numbers) to pixel (x, y). */
void film_add(film_t *f, int x, int y, const double *values, double weight);
/* Adds src's sums and weights into dst (same size and channels). */
void film_merge(film_t *dst, const film_t *src);

/* Per-pixel averages as float (width * height * nchannels); 0 where a pixel
 * has no weight. */
void film_develop(const film_t *f, float *out);

/* Writes the film; the format follows the extension: .exr (every channel,
 * float32, ZIP) or .png / .jpg / .jpeg (RGB, clamped to [0,1], sRGB-encoded,
 * 8-bit). The file appears whole or not at all. Returns 0 or -1 with a
 * one-line reason naming the file. */
int film_write(const film_t *f, const char *path, char *err, size_t errlen);

/* The RGB channels tonemapped for 8-bit output (film_srgb8 of each
 * averaged value): width * height * 3 bytes. */
void film_develop_srgb8(const film_t *f, uint8_t *out);

/* Linear value -> 8-bit sRGB code (clamp to [0,1], sRGB OETF, round);
 * NaN gives 0. */
uint8_t film_srgb8(double linear);

/* Writes interleaved float pixels (nch channels named names) as a float32
 * scanline OpenEXR with ZIP compression, atomically. Returns 0 or -1. */
int exr_write_float(const char *path, int width, int height, int nch, const char *const *names,
                    const float *pixels, char *err, size_t errlen);

/* A string attribute of an EXR header, e.g. {"celadon.part", "2/4"}. */
typedef struct {
    const char *name, *value;
} film_attr;

/* exr_write_float with nattrs string attributes added to the header. */
int exr_write_float_attrs(const char *path, int width, int height, int nch, const char *const *names,
                          const float *pixels, const film_attr *attrs, int nattrs, char *err, size_t errlen);

#endif
