/* Samplers in the sense of Mitsuba 3: where the random numbers of each pixel
 * sample come from. Plugin: `independent` (PCG32, one stream per pixel
 * sample: rng.h). A render is deterministic because sample s of pixel
 * (x, y) draws from the stream sampler_start(x, y, s) gives, whatever the
 * thread that takes it.
 *
 * This is src/samplers' interface: what the scene build, the render loop
 * and the integrators use; each plugin is one file plus one line of
 * sampler_table.c (docs/plugins.md). */
#ifndef CELADON_SAMPLERS_H
#define CELADON_SAMPLERS_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/rng.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct sampler_ops sampler_ops;

/* A scene's sampler: its plugin and settings, read-only while rendering. */
typedef struct {
    const sampler_ops *ops;
    long long sample_count; /* samples per pixel */
    uint64_t seed;
} sampler_t;

/* The numbers of one pixel sample, drawn in order by one thread. */
typedef struct {
    const sampler_t *sampler;
    uint32_t px, py, index; /* the pixel and the sample's number in it */
    rng_t rng;
} sampler_stream;

/* Starts the stream of sample index of pixel (px, py). */
void sampler_start(const sampler_t *s, sampler_stream *st, uint32_t px, uint32_t py, uint32_t index);
/* The next number, uniform in [0, 1). */
double sampler_next_1d(sampler_stream *st);
/* The next two, as a point of [0, 1)^2. */
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
