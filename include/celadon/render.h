/* Rendering a built scene (scene.h) with its integrator (Mitsuba's `path`
 * by default: unidirectional path tracing with next-event estimation and
 * multiple importance sampling) and its sampler.
 *
 * Determinism: sample s of pixel (x, y) draws from its own stream of the
 * sampler (for `independent`: rng_for_sample(seed, x, y, s)) and each
 * pixel's samples are added in order, so an image depends on the seed only,
 * never on the thread count or schedule. */
#ifndef CELADON_RENDER_H
#define CELADON_RENDER_H

#include "celadon/color.h"
#include "celadon/film.h"
#include "celadon/scene.h"

/* The --aov outputs (docs/rendering.md, "AOVs"): channels named as
 * Blender's compositor and Nuke read them. */
enum {
    RENDER_AOV_DEPTH = 1u,    /* Z: distance along the camera ray to the first hit */
    RENDER_AOV_NORMAL = 2u,   /* N.X, N.Y, N.Z: its world shading normal */
    RENDER_AOV_ALBEDO = 4u,   /* albedo.R, .G, .B: its BSDF's albedo */
    RENDER_AOV_INDEX = 8u,    /* IndexOB.X, IndexMA.X: its shape's and material's numbers */
    RENDER_AOV_VARIANCE = 16u,/* variance.X: of the pixel's estimate (film.h, FILM_EXTRA_VARIANCE) */
    RENDER_AOV_SPP = 32u,     /* spp.X: the pixel's camera samples */
    /* Denoising Depth.Z, Denoising Normal.X/Y/Z, Denoising Albedo.R/G/B: depth,
     * normal and albedo at the path's first rough vertex (integrators.h) */
    RENDER_AOV_DENOISING = 64u,
    /* half.R, .G, .B, .A: the samples of the first half of the sample
     * indices (k < spp / 2), premultiplied by their share A of the pixel's
     * filter weight: half.RGB / A and (RGB - half.RGB) / (1 - A) are two
     * independent half-sample renders (denoise.h) */
    RENDER_AOV_HALF = 128u,
    /* specular.R, .G, .B: the part of the colour the path gathers after
     * leaving its first rough vertex by a glossy or delta lobe (the rest,
     * RGB - specular, is the diffuse part); with half, also specular
     * half.R, .G, .B: its first half, premultiplied as half.RGB; and
     * Denoising Mirror.R, .G, .B: the light seen in the mirror direction
     * at that vertex where it has a delta reflection (integrators.h) */
    RENDER_AOV_SPECULAR = 256u
};

typedef struct {
    int threads;       /* 0: OpenMP's default */
    unsigned aovs;     /* RENDER_AOV_* mask: extra film channels, in that order */
    int progress;      /* 1: progress bar on a TTY and a summary line on stderr */
    int sample_begin, sample_end; /* render samples [begin, end) of every pixel (a part of the
                                     render, parts.h); 0, 0: all of the sampler's */
    double time_budget;  /* > 0: seconds; no pass is started that the last one's time says would
                            end past it (at least one pass; the sample count stays the limit) */
    const char *preview; /* non-NULL: the film written here (film_write) after a pass once
                            preview_seconds have passed since the last time, and at the end */
    double preview_seconds;
} render_options;

typedef struct {
    double seconds;
    uint64_t samples;   /* camera samples traced */
    int interrupted;    /* 1 when render_request_stop() cut the render short */
    /* The threads' CPU seconds in tiles, and the idle time they imply on an
     * idle machine: at the end of each pass (each colour of tiles of a pass,
     * with a splatting filter) the threads wait for the one with the most
     * work, so the sum over those of (most - each thread's)
     * CPU time is what a core would wait (a measure of the tile schedule
     * that the machine's load does not inflate). Under MPI, this rank's. */
    double busy_cpu_seconds;
    double idle_cpu_seconds;
} render_stats;

/* Parses "depth,normal,albedo,index,variance,spp,denoising,half,specular" (any
 * subset, any order; "Z" and "N" too) into a mask; -1 for an unknown name. */
int render_aov_parse(const char *list, unsigned *mask);

/* Renders into film (initialised here with the scene's size and the AOVs;
 * film_free it). Samples are taken in about eight passes over all pixels
 * (more above 512 spp: a pass takes at most 64 samples of each pixel), so
 * a render stopped after the first pass leaves every pixel with a
 * consistent, noisier average; stopped during the first pass, the pixels not
 * reached yet have no samples (film_develop gives them 0).
 * Returns 0, or -1 with a reason in err (also for a sample range outside
 * [0, spp] or empty). */
int render_scene(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                 size_t errlen);

/* Asks render_scene to stop once the pass under way is finished (so
 * every pixel keeps the same count of samples, unless the first pass is
 * under way), or, called a second time, after the samples in flight (or,
 * if called before it starts, as soon as it starts); the request is
 * cleared when render_scene returns. Async-signal-safe (meant for a
 * signal handler: the first Ctrl-C finishes the pass, the second stops). */
void render_request_stop(void);
/* Asks it to stop after the samples in flight. Async-signal-safe. */
void render_request_stop_now(void);

#endif
