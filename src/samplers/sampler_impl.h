/* What a sampler plugin provides, and what the plugins share. Private to
 * src/samplers/. */
#ifndef CELADON_SAMPLER_IMPL_H
#define CELADON_SAMPLER_IMPL_H

#include "samplers/samplers.h"
#include "samplers/sequences.h"

struct sampler_ops {
    /* Rounds s->sample_count and sets up the plugin's fields (samplers.h). */
    void (*prepare)(sampler_t *s, int width, int height);
    /* Sets up st: its sampler, pixel, index, dimension 0 and the per-pixel
     * key are already set (sampler_start). */
    void (*start)(sampler_stream *st);
    double (*next_1d)(sampler_stream *st);
    vec2 (*next_2d)(sampler_stream *st);
};

/* Reads `sample_count` (4 by default, Mitsuba's), `seed` (0) and, when
 * with_jitter, `jitter` (true) into out; the scene build checks the count's
 * range once the options have overridden it. */
void sampler_read_common(scene_obj *o, bool with_jitter, sampler_t *out);

/* The declarations of those parameters, to open a plugin's list with. */
#define SAMPLER_PARAMS_COMMON {"sample_count", PARAM_INT, 0, NULL}, {"seed", PARAM_INT, 0, NULL}
#define SAMPLER_PARAM_JITTER {"jitter", PARAM_BOOL, 0, NULL}
#define SAMPLER_PARAMS_END {NULL, 0, 0, NULL}

/* start for the plugins whose numbers are functions of the stream's pixel,
 * index and dimension alone. */
void sampler_start_nothing(sampler_stream *st);

/* The jitter within a cell of the current dimension (salt tells the
 * coordinates of a 2D point apart): uniform, a hash of the pixel, sample
 * and dimension (so a sample's numbers do not depend on what it drew
 * before), or the cell's centre when `jitter` is false. */
double sampler_jitter(const sampler_stream *st, uint32_t salt);

/* next_1d of the stratifying plugins: sample_count strata of [0, 1), one
 * sample each, shuffled per pixel and dimension (jittered within). */
double sampler_shuffled_strata_1d(sampler_stream *st);

/* A hash of the stream's pixel key and dimension (plus salt), for the
 * permutations and scrambles of that dimension in that pixel. */
static inline uint32_t sampler_dim_hash(const sampler_stream *st, uint32_t salt)
{
    return seq_hash(st->key, ((uint64_t)salt << 32) | st->dim);
}

/* The smallest power of two >= n (n >= 1), and its log2. */
int sampler_ceil_log2(long long n);

#endif
