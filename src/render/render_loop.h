/* The render loop's pieces, for the drivers in src/render that share its
 * work out: render_scene (one process, render.c) and distribute_mpi.c (the
 * ranks of an MPI job). Private to src/render/.
 *
 * The unit of work is a range of samples of every pixel of a band of rows:
 * render_samples takes one, its tiles shared among OpenMP threads. Sample k
 * of pixel (x, y) draws from its own stream of the sampler, and a film adds a
 * pixel's samples in the order they come, so units taken in increasing
 * sample order give the same bits however they were grouped. */
#ifndef CELADON_RENDER_LOOP_H
#define CELADON_RENDER_LOOP_H

#include <stdatomic.h>
#include <stdbool.h>

#include "celadon/render.h"
#include "core/core.h"

/* Samples taken so far (updated as tiles finish), and an optional progress
 * bar the first thread of the team draws. */
typedef struct {
    _Atomic uint64_t taken;
    progress_t *bar; /* NULL: none */
    double t_start;  /* for the bar's Msamples/s */
    /* The threads' CPU seconds in tiles and their wait at the end of each
     * render_samples (render_stats), added by the calling thread. */
    double busy_cpu_seconds, idle_cpu_seconds;
} render_tally;

/* The film for the scene's size, pixel format, the requested AOVs and the
 * integrator's own channels, with the metadata of its EXR header
 * (film_init_format). */
int render_film_init(const scene_t *s, unsigned aovs, film_t *film, char *err, size_t errlen);

/* The camera samples that samples [s0, s1) of every pixel take: the film's
 * pixels and, with hdrfilm's sample_border, the border's. */
uint64_t render_sample_count(const scene_t *s, int s0, int s1);

/* The samples [*s0, *s1) of every pixel that opt asks for (all by default). */
void render_sample_range(const scene_t *s, const render_options *opt, int *s0, int *s1);

/* The OpenMP threads opt asks for. */
int render_thread_count(const render_options *opt);

/* Samples [s0, s1) of every pixel in rows [y0, y1) into film (splatted
 * through the filter, so into rows up to its radius beyond; the first and
 * last bands also sample the border rows with sample_border), the tiles
 * shared among threads; ends early (after the samples in flight) on a stop
 * request. */
void render_samples(const scene_t *s, int threads, unsigned aovs, film_t *film, int s0, int s1, int y0, int y1,
                    render_tally *tally);

/* Whether render_request_stop was called, and clearing it (the drivers do
 * once their render is over). */
bool render_stop_requested(void);
void render_stop_clear(void);

/* The summary line of a finished render on stderr ("render: WxH, ..."). */
void render_print_summary(const scene_t *s, const render_options *opt, const render_stats *st, const char *who);

#endif
