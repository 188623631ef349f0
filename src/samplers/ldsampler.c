/* Mitsuba's `ldsampler`: Kollig and Keller's (0,2)-sequence sampler (2002,
 * "Efficient multidimensional sampling"), Mitsuba 1's default. Every 2D
 * dimension pair of a pixel's samples is the first sample_count points of
 * the same (0,2)-sequence (the first two Sobol dimensions; sample_count
 * rounded up to a power of 4), randomised per pixel and dimension by a
 * shuffle of the samples and a random digital shift (an xor), which keeps
 * them a (0,m,2)-net: every elementary interval of area 1/sample_count
 * holds one sample. 1D dimensions are the van der Corput points, shuffled
 * and shifted alike. */
#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

static void ldsampler_prepare(sampler_t *s, int width, int height)
{
    (void)width, (void)height;
    int k = sampler_ceil_log2(s->sample_count);
    k += k & 1; /* a power of 4 */
    s->log2_count = k > 2 ? k : 2;
    s->sample_count = 1ll << s->log2_count;
}

/* The sample's point in the shuffled sequence of this pixel and dimension
 * (sample_count a power of 2). */
static uint32_t shuffled_point(const sampler_stream *st)
{
    uint32_t count = (uint32_t)st->sampler->sample_count;
    return seq_permute(st->index & (count - 1u), count, sampler_dim_hash(st, 0));
}

static double ldsampler_next_1d(sampler_stream *st)
{
    uint32_t i = shuffled_point(st);
    uint32_t x = seq_sobol0(i) ^ sampler_dim_hash(st, 1);
    st->dim++;
    return seq_unit(x);
}

static vec2 ldsampler_next_2d(sampler_stream *st)
{
    uint32_t i = shuffled_point(st);
    uint32_t x = seq_sobol0(i) ^ sampler_dim_hash(st, 1), y = seq_sobol1(i) ^ sampler_dim_hash(st, 2);
    st->dim += 2;
    return v2(seq_unit(x), seq_unit(y));
}

static const sampler_ops ldsampler_ops = {ldsampler_prepare, sampler_start_nothing, ldsampler_next_1d, ldsampler_next_2d};

static int ldsampler_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    out->ops = &ldsampler_ops;
    sampler_read_common(o, false, out);
    return 0;
}

static const scene_param_decl ldsampler_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAMS_END};

const sampler_plugin sampler_ldsampler = {
    .decl = {.cls = SCENE_SAMPLER, .type = "ldsampler", .params = ldsampler_params},
    .create = ldsampler_create,
};
