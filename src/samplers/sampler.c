/* Dispatch to the scene's sampler plugin, and what the plugins share. */
#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

void sampler_prepare(sampler_t *s, int width, int height)
{
    s->ops->prepare(s, width, height);
}

void sampler_start(const sampler_t *s, sampler_stream *st, uint32_t px, uint32_t py, uint32_t index)
{
    st->sampler = s;
    st->px = px, st->py = py, st->index = index;
    st->dim = 0;
    st->key = rng_mix64(s->seed ^ rng_mix64(((uint64_t)py << 32) | px));
    s->ops->start(st);
}

double sampler_next_1d(sampler_stream *st)
{
    return st->sampler->ops->next_1d(st);
}

vec2 sampler_next_2d(sampler_stream *st)
{
    return st->sampler->ops->next_2d(st);
}

void sampler_read_common(scene_obj *o, bool with_jitter, sampler_t *out)
{
    out->sample_count = scene_obj_int(o, "sample_count", 4);
    out->seed = (uint64_t)scene_obj_int(o, "seed", 0);
    out->jitter = with_jitter ? scene_obj_bool(o, "jitter", true) : false;
    out->in_order = false;
    out->strength = 0;
}

void sampler_start_nothing(sampler_stream *st)
{
    (void)st;
}

double sampler_jitter(const sampler_stream *st, uint32_t salt)
{
    if (!st->sampler->jitter)
        return 0.5;
    uint64_t h = rng_mix64(st->key ^ rng_mix64(((uint64_t)st->index << 32) | st->dim) ^ ((uint64_t)salt << 56));
    return (double)(h >> 11) * 0x1p-53;
}

double sampler_shuffled_strata_1d(sampler_stream *st)
{
    uint32_t count = (uint32_t)st->sampler->sample_count;
    uint32_t cell = seq_permute(st->index % count, count, sampler_dim_hash(st, 0));
    double x = seq_below_one((cell + sampler_jitter(st, 0)) / count);
    st->dim++;
    return x;
}

int sampler_ceil_log2(long long n)
{
    int k = 0;
    while ((1ll << k) < n)
        k++;
    return k;
}
