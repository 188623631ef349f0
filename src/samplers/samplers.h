/* Samplers in the sense of Mitsuba 3: where the numbers of each pixel sample
 * come from. Plugins: `independent` (PCG32, one stream per pixel sample:
 * rng.h), Mitsuba's `stratified`, `multijitter`, `orthogonal` and
 * `ldsampler`, and pbrt-v4's `zsobol` (Owen-scrambled Sobol points, their
 * order across pixels a Morton curve with permuted digits: Ahmed & Wonka
 * 2020), the best of them (docs/rendering.md, "Samplers").
 *
 * Dimensions. A pixel sample is a point of the unit hypercube; its
 * coordinates are numbered, and a sampler stratifies each coordinate (1D
 * requests) or each pair (2D requests) over the sample_count samples of a
 * pixel, so the caller must ask for the same dimension for the same purpose
 * in every sample: the film position is dimensions 0-1, the lens 2-3, and an
 * integrator starts at SAMPLER_DIM_INTEGRATOR with a fixed layout per bounce
 * (sampler_seek), whatever the path does. `independent` ignores dimensions
 * (its numbers are all independent anyway).
 *
 * Determinism: the numbers of sample s of pixel (x, y) depend only on the
 * sampler, its seed, x, y, s and the dimension, never on the thread.
 *
 * This is src/samplers' interface: what the scene build, the render loop
 * and the integrators use; each plugin is one file plus one line of
 * sampler_table.c (docs/plugins.md). */
#ifndef CELADON_SAMPLERS_H
#define CELADON_SAMPLERS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celadon/rng.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct sampler_ops sampler_ops;

/* The dimensions every integrator shares. */
enum {
    SAMPLER_DIM_FILM = 0,       /* 2D: the position in the pixel */
    SAMPLER_DIM_LENS = 2,       /* 2D: the position on the lens */
    SAMPLER_DIM_INTEGRATOR = 4, /* the integrator's first */
};

/* A scene's sampler: its plugin and settings, read-only while rendering. */
typedef struct {
    const sampler_ops *ops;
    const char *plugin;     /* its plugin's name (the scene's, or the one the options name) */
    long long sample_count; /* samples per pixel (rounded by sampler_prepare) */
    uint64_t seed;
    bool jitter;            /* stratified, multijitter, orthogonal: random offsets within the cells */
    bool in_order;          /* independent: its numbers come in the order drawn, whatever the dimension */
    int strength;           /* orthogonal: the array's strength */
    /* Set by sampler_prepare: */
    uint32_t cells[2];      /* cells per axis of a 2D stratum grid */
    int log2_count;         /* zsobol, ldsampler: log2(sample_count) */
} sampler_t;

/* The numbers of one pixel sample, drawn in order by one thread. */
typedef struct {
    const sampler_t *sampler;
    uint32_t px, py, index; /* the pixel and the sample's number in it */
    uint32_t dim;           /* the next dimension */
    uint64_t key;           /* a hash of the seed and the pixel */
    uint64_t base;          /* zsobol: the pixel's first global sample index */
    uint64_t coarse_key;    /* zsobol: the sample's coarse index bits and the seed, for every dimension's key */
    uint32_t coarse_bits;   /* zsobol: the sample's coarse index bits, in place */
    uint32_t fine_reversed; /* zsobol: the sample's fine index bits, reversed */
    rng_t rng;              /* independent: the sample's PCG32 stream */
} sampler_stream;

/* Rounds s->sample_count up to a count the plugin can stratify (Mitsuba's
 * rules: a square for `stratified`, a prime's square for `orthogonal`, a
 * power of 4 for `ldsampler`; pbrt-v4's power of 2 for `zsobol`) and sets
 * the plugin up for a film of width x height. Call after any override of
 * sample_count and before rendering. */
void sampler_prepare(sampler_t *s, int width, int height);

/* Starts the stream of sample index of pixel (px, py), at dimension 0. */
void sampler_start(const sampler_t *s, sampler_stream *st, uint32_t px, uint32_t py, uint32_t index);
/* The next dimension is dim. */
static inline void sampler_seek(sampler_stream *st, uint32_t dim) { st->dim = dim; }
/* The number of the next dimension, in [0, 1). */
double sampler_next_1d(sampler_stream *st);
/* The next two dimensions as a point of [0, 1)^2, stratified as a pair. */
vec2 sampler_next_2d(sampler_stream *st);

/* A sampler plugin: its declaration for the scene reader and its
 * constructor from a <sampler> object; 0, or -1 with "file:line: problem"
 * in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, sampler_t *out, char *err, size_t errlen);
} sampler_plugin;

/* The registration table: every sampler plugin, NULL-terminated. */
extern const scene_plugin_decl *const sampler_plugins[];
/* The plugin named name, or NULL. */
const sampler_plugin *sampler_plugin_find(const char *name);

#endif
