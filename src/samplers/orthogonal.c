/* Mitsuba's `orthogonal` sampler: orthogonal array sampling (Jarosz et al.
 * 2019, "Orthogonal array sampling for Monte Carlo rendering"). A pixel's
 * samples are the rows of an orthogonal array of strength t (`strength`,
 * default 2) built by Bush's construction over the prime p, sample_count
 * rounded up to p^t: row i, with base-p digits c_0 .. c_(t-1), has in
 * column j < p the level sum_k c_k j^k mod p, and in column p the level
 * c_(t-1). Any t of the p + 1 columns take every combination of levels
 * equally often, so with t = 2 every pair of dimensions (among p + 1
 * consecutive ones) is stratified in a p x p grid; within its level a
 * sample's sub-stratum comes from the remaining digits, so every dimension
 * alone is stratified in p^t strata too (the correlated multi-jitter
 * flavour). Dimension d uses column d mod (p + 1); levels and sub-strata are
 * shuffled per pixel and dimension, and jittered unless `jitter` is false. */
#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

enum { MAX_STRENGTH = 8 };

static bool is_prime(long long n)
{
    if (n < 2)
        return false;
    for (long long k = 2; k * k <= n; k++)
        if (n % k == 0)
            return false;
    return true;
}

static long long ipow(long long b, int e)
{
    long long r = 1;
    while (e-- > 0)
        r *= b;
    return r;
}

static void orthogonal_prepare(sampler_t *s, int width, int height)
{
    (void)width, (void)height;
    long long p = 2;
    while (ipow(p, s->strength) < s->sample_count || !is_prime(p))
        p++;
    s->sample_count = ipow(p, s->strength);
    s->cells[0] = s->cells[1] = (uint32_t)p;
}

static double orthogonal_next_1d(sampler_stream *st)
{
    const sampler_t *s = st->sampler;
    uint32_t p = s->cells[0], n = (uint32_t)s->sample_count, sub_count = n / p;
    int t = s->strength;
    /* The row: the same shuffle of the pixel's samples in every dimension,
     * or the array would fall apart. */
    uint32_t row = seq_permute(st->index % n, n, (uint32_t)st->key);
    uint32_t c[MAX_STRENGTH], r = row;
    for (int k = 0; k < t; k++, r /= p)
        c[k] = r % p;
    uint32_t column = st->dim % (p + 1), level, sub;
    if (column < p) {
        level = c[t - 1];
        for (int k = t - 2; k >= 0; k--)
            level = (level * column + c[k]) % p;
        sub = row / p; /* c_1 .. c_(t-1): with the level they give c_0 back */
    } else {
        level = c[t - 1];
        sub = row % sub_count; /* c_0 .. c_(t-2) */
    }
    level = seq_permute(level, p, sampler_dim_hash(st, 1));
    sub = seq_permute(sub, sub_count, sampler_dim_hash(st, 2));
    double x = seq_below_one((level + (sub + sampler_jitter(st, 0)) / sub_count) / p);
    st->dim++;
    return x;
}

static vec2 orthogonal_next_2d(sampler_stream *st)
{
    double x = orthogonal_next_1d(st);
    return v2(x, orthogonal_next_1d(st));
}

static const sampler_ops orthogonal_ops = {orthogonal_prepare, sampler_start_nothing, orthogonal_next_1d,
                                           orthogonal_next_2d};

static int orthogonal_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    out->ops = &orthogonal_ops;
    sampler_read_common(o, true, out);
    long long t = scene_obj_int(o, "strength", 2);
    if (t < 1 || t > MAX_STRENGTH)
        return scene_obj_error(o, err, errlen, "strength must be from 1 to %d", MAX_STRENGTH);
    out->strength = (int)t;
    return 0;
}

static const scene_param_decl orthogonal_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAM_JITTER,
                                                     {"strength", PARAM_INT, 0, NULL}, SAMPLER_PARAMS_END};

const sampler_plugin sampler_orthogonal = {
    .decl = {.cls = SCENE_SAMPLER, .type = "orthogonal", .params = orthogonal_params},
    .create = orthogonal_create,
};
