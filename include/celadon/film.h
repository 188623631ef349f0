/* The film: per-pixel weighted sums of RGB radiance (and alpha) plus
 * optional AOV channels, and their output as float32 OpenEXR or tonemapped
 * 8-bit PNG/JPEG.
 *
 * The film only accumulates: film_add adds a sample to one pixel with a
 * weight, and a pixel's value is its weighted mean. The render loop splats
 * each sample into the pixels its reconstruction filter reaches, with the
 * filter's weights (render.h). A film can be written whenever no thread is
 * adding to it, e.g. after Ctrl-C stopped a render between passes: pixels
 * that have no samples yet are written black. */
#ifndef CELADON_FILM_H
#define CELADON_FILM_H

#include <stddef.h>
#include <stdint.h>

/* An extra output: channels is 1 or 3, written as "<name>.Y" or
 * "<name>.R", "<name>.G", "<name>.B"; or, with suffixes, 1 to 4 channels
 * named "<name>.<suffix>" ("T" for a depth, "X", "Y", "Z" for a vector, as
 * Mitsuba's `aov` integrator names them; "<name>" alone for an empty
 * suffix). */
typedef struct {
    const char *name;
    int channels;
    const char *const *suffixes; /* NULL: Y or R, G, B */
} film_aov;

/* What the EXR file says: Mitsuba's hdrfilm `pixel_format`. The film holds
 * R, G, B (and A, the coverage, for the alpha formats) whatever the format;
 * luminance and XYZ are computed from them when the EXR is written. */
typedef enum {
    FILM_RGB,
    FILM_RGBA,
    FILM_LUMINANCE,
    FILM_LUMINANCE_ALPHA,
    FILM_XYZ,
    FILM_XYZA
} film_pixel_format;

/* The format's name in hdrfilm's pixel_format ("rgb", "luminance_alpha"...),
 * and back: 0, or -1 for a name that is none. */
const char *film_format_name(film_pixel_format f);
int film_format_parse(const char *name, film_pixel_format *f);

static inline int film_format_has_alpha(film_pixel_format f)
{
    return f == FILM_RGBA || f == FILM_LUMINANCE_ALPHA || f == FILM_XYZA;
}

/* How the image was made, written into the EXR header: "spp" (int),
 * "seed" (string: a 64-bit number), "renderer", "integrator", "camera"
 * (strings) and the standard "worldToCamera" matrix. */
typedef struct {
    int spp;              /* 0: no metadata */
    uint64_t seed;
    char integrator[64];  /* the integrator plugin */
    char camera[160];     /* the sensor plugin and its projection, e.g. "perspective fov_x=39.6" */
    double world_to_camera[4][4]; /* row-major, column vectors */
} film_metadata;

typedef struct {
    int width, height;
    int nchannels;  /* 3 (R, G, B), + 1 (A) with an alpha format, + the AOV channels, in that order */
    char **names;   /* the EXR channel name of each channel */
    double *sum;    /* weighted sums, width * height * nchannels, row-major from the top-left */
    double *weight; /* sum of sample weights, width * height */
    film_pixel_format format;
    film_metadata meta;
} film_t;

/* The largest film: each side, and the pixels (10^9 pixels of RGB sums
 * and weights are 32 GB). */
#define FILM_MAX_SIDE 65536
#define FILM_MAX_PIXELS 1e9

/* An RGB film. Returns 0, or -1 with a reason (bad size, bad AOV). */
int film_init(film_t *f, int width, int height, const film_aov *aovs, int naovs, char *err, size_t errlen);
/* A film of the given pixel format: R, G, B, then A for the alpha formats,
 * then the AOVs. */
int film_init_format(film_t *f, int width, int height, film_pixel_format format, const film_aov *aovs, int naovs,
                     char *err, size_t errlen);
void film_free(film_t *f);

/* Adds weight · values (nchannels numbers) to pixel (x, y). */
void film_add(film_t *f, int x, int y, const double *values, double weight);
/* Adds src's sums and weights into dst (same size and channels). */
void film_merge(film_t *dst, const film_t *src);

/* Per-pixel averages as float (width * height * nchannels); 0 where a pixel
 * has no weight. */
void film_develop(const film_t *f, float *out);

/* The developed film as its EXR holds it: the channels of the pixel format
 * (R, G, B; Y; or X, Y, Z; then A and the AOVs), float32, interleaved,
 * row-major from the top left: a malloc'd array of width * height * *nch
 * floats (the caller frees it). names (room for f->nchannels) receives the
 * channels' names, pointing into f's or static strings. */
float *film_develop_exr(const film_t *f, int *nch, const char **names);

/* Writes the film; the format follows the extension: .exr (every channel,
 * float32, ZIP, in the film's pixel format, with its metadata) or .png /
 * .jpg / .jpeg (RGB, clamped to [0,1], sRGB-encoded, 8-bit). The file
 * appears whole or not at all. Returns 0 or -1 with a one-line reason
 * naming the file. */
int film_write(const film_t *f, const char *path, char *err, size_t errlen);

/* The RGB channels tonemapped for 8-bit output (film_srgb8 of each
 * averaged value): width * height * 3 bytes. */
void film_develop_srgb8(const film_t *f, uint8_t *out);

/* Linear value -> 8-bit sRGB code (clamp to [0,1], sRGB OETF, round);
 * NaN gives 0. */
uint8_t film_srgb8(double linear);

/* Writes interleaved float pixels (nch channels named names) as a float32
 * scanline OpenEXR with ZIP compression, atomically, with the header
 * attributes of meta (NULL or meta->spp == 0: none). Returns 0 or -1. */
int exr_write_float(const char *path, int width, int height, int nch, const char *const *names,
                    const float *pixels, const film_metadata *meta, char *err, size_t errlen);

/* A string attribute of an EXR header, e.g. {"celadon.part", "2/4"}. */
typedef struct {
    const char *name, *value;
} film_attr;

/* exr_write_float with nattrs string attributes added to the header. */
int exr_write_float_attrs(const char *path, int width, int height, int nch, const char *const *names,
                          const float *pixels, const film_metadata *meta, const film_attr *attrs, int nattrs,
                          char *err, size_t errlen);

#endif
