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

/* The colour channels as the format writes them into an EXR (Y, or X, Y, Z,
 * or R, G, B; then A with alpha) into names[0..3]; returns their count. */
int film_format_colour_names(film_pixel_format f, const char **names);

/* How the image was made, written into the EXR header: "spp" (int, the
 * samples per pixel asked for), "seed" (string: a 64-bit number),
 * "renderer", "integrator", "camera" (strings), the standard
 * "worldToCamera" matrix, "comments", "capDate" and "utcOffset", and the
 * rest as "celadon/..." attributes (docs/rendering.md, "What a file
 * says"); PNG and JPEG carry the same as text (film_write). */
typedef struct {
    int spp;              /* 0: no metadata */
    uint64_t seed;
    char integrator[64];  /* the integrator plugin */
    char camera[160];     /* the sensor plugin and its projection, e.g. "perspective fov_x=39.6" */
    double world_to_camera[4][4]; /* row-major, column vectors */
    /* Set by the scene build (render_film_init): */
    char sampler[32];     /* the sampler plugin */
    char scene_digest[20];/* scene_digest in hex */
    /* Set by the render (render_scene, distribute_render): */
    double seconds;       /* wall-clock time of the sampling */
    int interrupted;      /* 1: stopped before every sample was taken */
    int passes;           /* passes over the image completed */
    int threads, ranks;   /* OpenMP threads (per rank) and MPI ranks */
    double time_budget;   /* render --time, seconds (0: none) */
    int crop[4];          /* the crop window x, y, width, height in the full film (width 0: none) */
    int full_width, full_height; /* the full film's size */
    /* Set by the command line (empty: not written): */
    char scene_path[1024];
    char command_line[2048];
    /* Set by denoise_film (denoise.h): what denoised the colour (empty: nothing). */
    char denoised[128];
} film_metadata;

/* What film_write adds from each pixel's own samples (film_t.samples),
 * as channels named as compositors read them: "spp.X" (the camera samples
 * the pixel got; written anyway when the pixels' counts differ) and
 * "variance.X" (the sample variance of the luminance of the pixel's samples
 * over their count: the variance of the estimate of their mean). */
enum { FILM_EXTRA_SPP = 1u, FILM_EXTRA_VARIANCE = 2u, FILM_EXTRA_INDEX = 4u };

typedef struct {
    int width, height;
    int nchannels;  /* 3 (R, G, B), + 1 (A) with an alpha format, + the AOV channels, in that order */
    char **names;   /* the EXR channel name of each channel */
    double *sum;    /* weighted sums, width * height * nchannels, row-major from the top-left */
    double *weight; /* sum of sample weights, width * height */
    film_pixel_format format;
    film_metadata meta;
    /* Each pixel's own camera samples (those whose film position falls in
     * it, whatever the filter): their count, the sum of their luminance
     * and of its square; width * height * 3. */
    double *samples;
    /* The object and material numbers (from 1; 0: nothing) of the first
     * surface that each pixel's sample 0 meets, written once, never
     * averaged (FILM_EXTRA_INDEX: "IndexOB.X", "IndexMA.X"); width * height
     * * 2, 0 elsewhere, so that sums of films keep them. */
    double *ids;
    unsigned extras; /* FILM_EXTRA_* channels to write */
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
/* Counts one camera sample of luminance y taken in pixel (x, y). */
static inline void film_count_sample(film_t *f, int x, int y, double lum)
{
    double *s = f->samples + 3 * ((size_t)y * f->width + x);
    s[0] += 1.0, s[1] += lum, s[2] += lum * lum;
}

/* The least and the most camera samples a pixel got. */
void film_sample_range(const film_t *f, double *least, double *most);

/* Adds src's sums, weights, sample counts and ids into dst (same size and
 * channels). */
void film_merge(film_t *dst, const film_t *src);

/* Per-pixel averages as float (width * height * nchannels); 0 where a pixel
 * has no weight. */
void film_develop(const film_t *f, float *out);

/* The developed film as its EXR holds it: the channels of the pixel format
 * (R, G, B; Y; or X, Y, Z; then A and the AOVs) and the extra channels
 * (spp, when the pixels' counts differ or asked; variance; IndexOB.X,
 * IndexMA.X), float32, interleaved, row-major from the top left: a
 * malloc'd array of width * height * *nch floats (the caller frees it).
 * names (room for f->nchannels + FILM_EXR_EXTRA_MAX) receives the
 * channels' names, pointing into f's or static strings. */
#define FILM_EXR_EXTRA_MAX 4
float *film_develop_exr(const film_t *f, int *nch, const char **names);

/* How scene-linear values become a display's code values, as Blender's
 * colour management calls them (docs/rendering.md, "Output formats"):
 * `standard`: clamped to [0, 1] and sRGB-encoded; `filmic`: an AgX-like
 * log encoding of 16.5 stops around middle grey through a sigmoid, so
 * highlights roll off instead of clipping. */
typedef enum { FILM_VIEW_STANDARD, FILM_VIEW_FILMIC } film_view;

/* "standard" or "filmic": 0, or -1 for another name. */
int film_view_parse(const char *name, film_view *v);
/* The code value in [0, 1] of a scene-linear value (NaN gives 0). */
double film_view_encode(film_view v, double linear);

/* How film_write_as writes: the view transform and the exposure (stops:
 * values times 2^exposure) of display-referred outputs (PNG, JPEG, 8- and
 * 16-bit TIFF; float outputs stay scene-linear, as Blender keeps them),
 * and the bits per channel: 0 for the format's default (PNG, JPEG 8; TIFF
 * 32, float), 8, 16 (PNG, TIFF) or 32 (TIFF). */
typedef struct {
    double exposure;
    film_view view;
    int depth;
} film_output;

/* Whether path's extension is a format film_write_as writes at that depth
 * (0: its default): 0, or -1 with the reason in err. */
int film_output_check(const char *path, int depth, char *err, size_t errlen);

/* Writes the film; the format follows the extension: .exr (every channel,
 * float32, ZIP, in the film's pixel format, with the FILM_EXTRA_* channels
 * and the metadata), .hdr (Radiance RGBE, linear RGB), .tif / .tiff (RGB:
 * float32 linear, or 8/16-bit display-referred), .png (8 or 16-bit) or
 * .jpg / .jpeg (8-bit), the display-referred ones through o's exposure and
 * view transform, all with the metadata as text. The file appears whole or
 * not at all. Returns 0 or -1 with a one-line reason naming the file. */
int film_write_as(const film_t *f, const char *path, const film_output *o, char *err, size_t errlen);
/* film_write_as with the defaults: standard view, no exposure, default depth. */
int film_write(const film_t *f, const char *path, char *err, size_t errlen);

/* The RGB channels tonemapped for 8-bit output (film_srgb8 of each
 * averaged value): width * height * 3 bytes. */
void film_develop_srgb8(const film_t *f, uint8_t *out);

/* Linear value -> 8-bit sRGB code (clamp to [0,1], sRGB OETF, round:
 * the standard view); NaN gives 0. */
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
