/* A render kept in memory, for callers that take pixels rather than a file
 * (the Python package, docs/python.md): the scene built from its file with
 * `celadon render`'s overrides, rendered, and developed into exactly the
 * channels and values the EXR of `celadon render -o OUT.exr` holds
 * (film_develop_exr), with their names.
 *
 * Lifetime: render_image_create / render_image_destroy; the image owns its
 * pixels and names. Threads: renders may run at once from several threads,
 * each reporting a failure in its own err; render_request_stop (render.h)
 * stops every render in progress, as Ctrl-C stops the CLI's. */
#ifndef CELADON_RENDER_IMAGE_H
#define CELADON_RENDER_IMAGE_H

#include <stddef.h>

#include "celadon/render.h"
#include "celadon/scene.h"

typedef struct render_image render_image_t;

/* `celadon render`'s overrides of the scene's own settings. */
typedef struct {
    int width, height; /* --res WxH; 0, 0: the scene's film */
    int spp;           /* --spp; 0: the scene's sampler. Also $spp where the scene leaves it to the command line */
    long long seed;    /* --seed; < 0: the scene's */
    int mesh_segments; /* --geometry mesh:N; 0: analytic */
    int threads;       /* --threads; 0: OpenMP's default */
    unsigned aovs;     /* --aov: RENDER_AOV_* */
} render_image_options;

/* The scene options (scene.h) of these overrides (search_dirs none). */
scene_options render_image_scene_options(const render_image_options *opt);

/* Builds the scene at scene_path with the defines (-D name=value) and opt,
 * renders it without progress output, and keeps the developed image.
 * Returns NULL on failure with *status 2 for bad input (err: the line
 * `celadon render` prints after "celadon: ") or 1 for another failure.
 * A render stopped by render_request_stop returns the image so far, and its
 * render_image_stats say interrupted. */
render_image_t *render_image_create(const char *scene_path, const scene_define *defs, int ndefs,
                                    const render_image_options *opt, int *status, char *err, size_t errlen);
void render_image_destroy(render_image_t *im);

/* Size and channel count; the name of channel c (0 <= c < channels). */
void render_image_size(const render_image_t *im, int *width, int *height, int *channels);
const char *render_image_channel(const render_image_t *im, int c);
/* height * width * channels floats, interleaved, row-major from the top left. */
const float *render_image_pixels(const render_image_t *im);
const render_stats *render_image_stats(const render_image_t *im);

/* Withdraws a render_request_stop that no render has taken up: a caller that
 * asked for a stop just as its render ended calls it before the next one. */
void render_image_cancel_stop(void);

#endif
