/* pbrt-v4's `zsobol` sampler: Owen-scrambled Sobol points ordered across
 * pixels along a Morton curve whose digits are randomly permuted (Ahmed &
 * Wonka 2020, "Screen-space blue-noise diffusion of Monte Carlo sampling
 * error via hierarchical ordering of pixels"). Sample s of pixel (x, y) is
 * point (morton(x, y) << log2(count)) + s of one global sequence, whose index
 * is permuted per dimension, each level's children by a function of their
 * parents (below: permuted_index). A pixel's samples stay an aligned block of
 * the sequence, so every 2D dimension pair of them is a (0,m,2)-net (the
 * first two Sobol dimensions, Owen-scrambled) and every 1D dimension is
 * stratified in sample_count strata; and the four pixels of each 2 x 2 block
 * at every scale take four different blocks of the sequence, which spreads
 * the error over the screen as blue noise rather than white. sample_count is
 * rounded up to a power of 2. */
#include "samplers/sampler_impl.h"
#include "samplers/sequences.h"

static void zsobol_prepare(sampler_t *s, int width, int height)
{
    (void)width, (void)height;
    s->log2_count = sampler_ceil_log2(s->sample_count);
    s->sample_count = 1ll << s->log2_count;
}

/* The bits of x spread to the even positions of 64. */
static uint64_t spread_bits(uint32_t x)
{
    uint64_t v = x;
    v = (v | v << 16) & 0x0000ffff0000ffffull;
    v = (v | v << 8) & 0x00ff00ff00ff00ffull;
    v = (v | v << 4) & 0x0f0f0f0f0f0f0f0full;
    v = (v | v << 2) & 0x3333333333333333ull;
    return (v | v << 1) & 0x5555555555555555ull;
}

/* Bits of x in the even positions, y in the odd ones. */
static uint64_t morton2(uint32_t x, uint32_t y)
{
    return spread_bits(x) | spread_bits(y) << 1;
}


/* The global index of this sample permuted for this dimension. The sample's
 * own bits and those of the FINE_LEVELS finest pixel levels (the fine part,
 * the index within a 2^FINE_LEVELS-pixel square, where the blue noise is
 * made) are Owen-scrambled as an integer: each bit flipped by a hash of the
 * bits above it, i.e. the hash of seq_owen_reversed on the bits reversed.
 * That permutes every level's children (2 x 2 pixels, or halves of a
 * pixel's samples) by a function of their parents, keeping each pixel's
 * samples one aligned block. The coarser bits stay as they are and only key
 * the scramble, with the seed and the dimension: *key, which also keys the
 * points' own scrambles. (A random permutation of each base-4 digit, as in
 * pbrt-v4, needs a hash per digit, which cost more than the rest of a
 * sample here.) */
enum { FINE_LEVELS = 4 };

static int fine_bits(const sampler_t *s) { return s->log2_count + 2 * FINE_LEVELS; /* at most 24 + 8 */ }

/* What every dimension of the sample shares, computed once per sample: its
 * global index, the coarse bits keyed with the seed and the fine bits
 * reversed. */
static void zsobol_start(sampler_stream *st)
{
    const sampler_t *s = st->sampler;
    st->base = morton2(st->px, st->py) << s->log2_count;
    uint64_t index = st->base | (st->index & ((1u << s->log2_count) - 1u));
    st->coarse_key = (index >> fine_bits(s)) ^ (s->seed * 0x9E3779B97F4A7C15ull);
    st->coarse_bits = (uint32_t)(index >> fine_bits(s) << fine_bits(s));
    st->fine_reversed = seq_reverse_bits((uint32_t)index & (uint32_t)((1ull << fine_bits(s)) - 1u));
}

static uint32_t permuted_index(const sampler_stream *st, uint64_t *key)
{
    int fb = fine_bits(st->sampler);
    *key = rng_mix64(st->coarse_key ^ ((uint64_t)st->dim << 40));
    uint32_t scrambled = seq_owen_reversed(st->fine_reversed, (uint32_t)((*key * 0x9E3779B97F4A7C15ull) >> 32));
    /* Owen-scrambled from bit fb - 1 down, the bits above (zeros before)
     * are dropped. */
    return st->coarse_bits | (scrambled & (uint32_t)((1ull << fb) - 1u));
}

/* Owen scrambling keyed per dimension (and coarse block: the blue noise
 * needs one scramble across each fine block only). */
static double zsobol_next_1d(sampler_stream *st)
{
    uint64_t key;
    uint32_t i = permuted_index(st, &key);
    st->dim++;
    return seq_unit(seq_owen_reversed(i, (uint32_t)key));
}

static vec2 zsobol_next_2d(sampler_stream *st)
{
    uint64_t key;
    uint32_t i = permuted_index(st, &key);
    st->dim += 2;
    return v2(seq_unit(seq_owen_reversed(i, (uint32_t)key)),
              seq_unit(seq_owen_reversed(seq_sobol1_reversed(i), (uint32_t)(key >> 32))));
}

static const sampler_ops zsobol_ops = {zsobol_prepare, zsobol_start, zsobol_next_1d, zsobol_next_2d};

static int zsobol_create(scene_obj *o, sampler_t *out, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    out->ops = &zsobol_ops;
    sampler_read_common(o, false, out);
    return 0;
}

static const scene_param_decl zsobol_params[] = {SAMPLER_PARAMS_COMMON, SAMPLER_PARAMS_END};

const sampler_plugin sampler_zsobol = {
    .decl = {.cls = SCENE_SAMPLER, .type = "zsobol", .params = zsobol_params},
    .create = zsobol_create,
};
