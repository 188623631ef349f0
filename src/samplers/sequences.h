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

/* Element i of a pseudo-random permutation of [0, n) chosen by seed
 * (i < n; n >= 1): for a fixed seed, i -> seq_permute(i, n, seed) is a
 * bijection of [0, n). A keyed bijection of the next power of two, walked
 * until it lands below n. */
uint32_t seq_permute(uint32_t i, uint32_t n, uint32_t seed);

static inline uint32_t seq_reverse_bits(uint32_t v)
{
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
    return (v >> 16) | (v << 16);
}

/* Dimension 0 of the Sobol sequence (the van der Corput sequence in base 2:
 * reversed, its digits are the index itself) and dimension 1, for point i.
 * Together, each aligned block of 2^m consecutive points is a (0,m,2)-net in
 * base 2: every elementary interval of area 2^-m holds exactly one point. */
static inline uint32_t seq_sobol0(uint32_t i) { return seq_reverse_bits(i); }
uint32_t seq_sobol1_reversed(uint32_t i);
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
