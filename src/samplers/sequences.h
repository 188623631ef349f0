/* The building blocks the stratified and low-discrepancy samplers share:
 * keyed hashes, pseudo-random permutations of [0, n), the first two
 * dimensions of the Sobol sequence and their Owen scrambling. Private to
 * src/samplers/. Values named "digits" are 32-bit fixed-point fractions
 * (v / 2^32 in [0, 1)); "reversed" digits have the first digit (1/2) in bit
 * 0, which is how a Sobol point comes out of its index. */
#ifndef CELADON_SEQUENCES_H
#define CELADON_SEQUENCES_H

#include <stdint.h>

#include "celadon/rng.h"

/* A 32-bit hash of (key, salt): distinct salts give unrelated values (the
 * golden-ratio multiple spreads small salts over all 64 bits). */
static inline uint32_t seq_hash(uint64_t key, uint64_t salt)
{
    return (uint32_t)(rng_mix64(key ^ (salt * 0x9E3779B97F4A7C15ull)) >> 32);
}

/* One round of a keyed bijection of the k-bit words (mask = 2^k - 1): xor a
 * key, multiply by an odd number (carries move entropy up), xorshift right
 * (moves it down); each step is invertible modulo 2^k. */
static inline uint32_t seq_permute_round(uint32_t x, uint32_t mask, int shift, uint32_t key, uint32_t mult)
{
    x = (x ^ key) & mask;
    x = (x * (mult | 1u)) & mask;
    return x ^ (x >> shift);
}

/* Element i of a pseudo-random permutation of [0, n) chosen by seed
 * (i < n; n >= 1): for a fixed seed, i -> seq_permute(i, n, seed) is a
 * bijection of [0, n). A keyed bijection of the next power of two, walked
 * until it lands below n. Inline: the samplers call it for every dimension
 * of every sample. */
static inline uint32_t seq_permute(uint32_t i, uint32_t n, uint32_t seed)
{
    if (n <= 1)
        return 0;
    uint32_t mask = ~0u >> __builtin_clz(n - 1); /* the next power of two, less 1 */
    int bits = 32 - __builtin_clz(mask), shift = bits > 1 ? (bits + 1) / 2 : 1;
    /* Only the low k bits of a key act on k-bit words: each round takes its
     * key and multiplier from a different slice of a hash of the seed, so
     * small counts get many permutations too. */
    uint64_t h = rng_mix64(seed), g = rng_mix64(h);
    /* Cycle walking: a bijection of [0, mask] applied until the value is
     * below n is a bijection of [0, n) (under two steps on average). */
    do {
        i = seq_permute_round(i, mask, shift, (uint32_t)h, (uint32_t)g);
        i = seq_permute_round(i, mask, shift, (uint32_t)(h >> 16), (uint32_t)(g >> 16));
        i = seq_permute_round(i, mask, shift, (uint32_t)(h >> 32), (uint32_t)(g >> 32));
        i = seq_permute_round(i, mask, shift, (uint32_t)(h >> 48), (uint32_t)(g >> 48));
    } while (i >= n);
    return i;
}

static inline uint32_t seq_reverse_bits(uint32_t v)
{
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    return __builtin_bswap32(v);
}

/* Dimension 0 of the Sobol sequence (the van der Corput sequence in base 2:
 * reversed, its digits are the index itself) and dimension 1, for point i.
 * Together, each aligned block of 2^m consecutive points is a (0,m,2)-net in
 * base 2: every elementary interval of area 2^-m holds exactly one point. */
static inline uint32_t seq_sobol0(uint32_t i) { return seq_reverse_bits(i); }
/* Dimension 1 (primitive polynomial x + 1) has the direction numbers
 * v_1 = 1/2, v_(k+1) = v_k xor v_k / 2: reversed, v_(k+1) is (1 + X)^k over
 * GF(2), whose digit j is C(k, j) mod 2, 1 exactly when the bits of j are a
 * subset of those of k (Lucas). Point i, the xor of v_(k+1) over the bits k
 * of i, therefore has reversed digit j = the parity of i's bits k whose
 * positions hold j's bits: a superset-sum transform over the five bits of a
 * position, one shift-and-xor per bit. */
static inline uint32_t seq_sobol1_reversed(uint32_t i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    return i ^ (i >> 16);
}
static inline uint32_t seq_sobol1(uint32_t i) { return seq_reverse_bits(seq_sobol1_reversed(i)); }

/* Owen's nested uniform scrambling, keyed by seed, of reversed digits r,
 * returned as digits: each digit is flipped by a hash of the digits before
 * it, so every (0,m,2)-net stays one (Burley 2020, "Practical hash-based
 * Owen scrambling", with the hash of Vegas & Whitted 2022). With r reversed,
 * bit k is digit k of the fraction; additions and multiplications carry
 * upwards only, so each output bit depends on the input bits at or below
 * it. */
static inline uint32_t seq_owen_reversed(uint32_t r, uint32_t seed)
{
    r ^= r * 0x3d20adeau;
    r += seed;
    r *= (seed >> 16) | 1u;
    r ^= r * 0x05526c56u;
    r ^= r * 0x53a22864u;
    return seq_reverse_bits(r);
}
/* The same of digits v. */
static inline uint32_t seq_owen_scramble(uint32_t v, uint32_t seed)
{
    return seq_owen_reversed(seq_reverse_bits(v), seed);
}

/* digits as a number in [0, 1). */
static inline double seq_unit(uint32_t v) { return (double)v * 0x1p-32; }
/* x clamped below 1: sums like (cell + jitter) / n may round up to 1.0. */
static inline double seq_below_one(double x) { return x < 0x1.fffffffffffffp-1 ? x : 0x1.fffffffffffffp-1; }

#endif
