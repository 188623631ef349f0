/* Mitsuba's `multijitter` sampler: correlated multi-jittered sampling
 * (Kensler 2013, "Correlated multi-jittered sampling"). A pixel's samples
 * fill an m x n grid of cells in every 2D dimension pair (sample_count
 * rounded up to m n with n = floor(sqrt(count)), m = ceil(count / n)), one
 * per cell, and within its cell each sample sits in the sub-column of its
 * row and the sub-row of its column, shuffled by one permutation for all
 * rows and one for all columns: so each 2D projection is stratified in the
 * grid and each 1D projection of it in m n strata (n-rooks). 1D dimensions
 * are m n shuffled strata. Offsets within the sub-cells are uniform unless
 * `jitter` is false. */
#include <math.h>

#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

static void multijitter_prepare(sampler_t *s, int width, int height)
{
    (void)width, (void)height;
    long long n = (long long)sqrt((double)s->sample_count);
    n = n > 0 ? n : 1;
    long long m = (s->sample_count + n - 1) / n;
    s->sample_count = m * n;
    s->cells[0] = (uint32_t)m, s->cells[1] = (uint32_t)n;
}

static vec2 multijitter_next_2d(sampler_stream *st)
{
    const sampler_t *s = st->sampler;
    uint32_t count = (uint32_t)s->sample_count, m = s->cells[0], n = s->cells[1];
    uint32_t cell = seq_permute(st->index % count, count, sampler_dim_hash(st, 0));
    uint32_t cx = cell % m, cy = cell / m;
    uint32_t sub_x = seq_permute(cy, n, sampler_dim_hash(st, 1)); /* the same for every row cy */
    uint32_t sub_y = seq_permute(cx, m, sampler_dim_hash(st, 2));
    double jx = sampler_jitter(st, 0), jy = sampler_jitter(st, 1);
    st->dim += 2;
    return v2(seq_below_one((cx + (sub_x + jx) / n) / m), seq_below_one((cy + (sub_y + jy) / m) / n));
}

static const sampler_ops multijitter_ops = {multijitter_prepare, sampler_start_nothing, sampler_shuffled_strata_1d,
                                            multijitter_next_2d};

static int multijitter_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    out->ops = &multijitter_ops;
    sampler_read_common(o, true, out);
    return 0;
}

static const scene_param_decl multijitter_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAM_JITTER,
                                                      SAMPLER_PARAMS_END};

const sampler_plugin sampler_multijitter = {
    .decl = {.cls = SCENE_SAMPLER, .type = "multijitter", .params = multijitter_params},
    .create = multijitter_create,
};
