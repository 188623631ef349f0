/* Mitsuba's `stratified` sampler: a pixel's samples fill an n x n grid of
 * cells in every 2D dimension pair, one sample per cell (sample_count
 * rounded up to the square n^2), and n^2 strata in every 1D dimension, each
 * dimension with its own random assignment of samples to cells (so the
 * dimensions are not correlated) and a uniform offset within the cell
 * unless `jitter` is false. */
#include <math.h>

#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

static void stratified_prepare(sampler_t *s, int width, int height)
{
    (void)width, (void)height;
    long long n = (long long)sqrt((double)s->sample_count);
    while (n * n < s->sample_count)
        n++;
    s->sample_count = n * n;
    s->cells[0] = s->cells[1] = (uint32_t)n;
}

static vec2 stratified_next_2d(sampler_stream *st)
{
    uint32_t count = (uint32_t)st->sampler->sample_count, n = st->sampler->cells[0];
    uint32_t cell = seq_permute(st->index % count, count, sampler_dim_hash(st, 0));
    double jx = sampler_jitter(st, 0), jy = sampler_jitter(st, 1);
    st->dim += 2;
    return v2(seq_below_one((cell % n + jx) / n), seq_below_one((cell / n + jy) / n));
}

static const sampler_ops stratified_ops = {stratified_prepare, sampler_start_nothing, sampler_shuffled_strata_1d,
                                           stratified_next_2d};

static int stratified_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    out->ops = &stratified_ops;
    sampler_read_common(o, true, out);
    return 0;
}

static const scene_param_decl stratified_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAM_JITTER,
                                                     SAMPLER_PARAMS_END};

const sampler_plugin sampler_stratified = {
    .decl = {.cls = SCENE_SAMPLER, .type = "stratified", .params = stratified_params},
    .create = stratified_create,
};
