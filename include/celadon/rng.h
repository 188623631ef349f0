/* PCG32 random numbers (O'Neill 2014: 64-bit LCG state, XSH-RR output), one
 * independent stream per (pixel, sample) so renders are deterministic whatever
 * the thread schedule. */
#ifndef CELADON_RNG_H
#define CELADON_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t state;
    uint64_t inc; /* stream selector, always odd */
} rng_t;

/* Seeds state and stream as PCG's reference pcg32_srandom does. */
void rng_seed(rng_t *r, uint64_t initstate, uint64_t initseq);
uint32_t rng_next_u32(rng_t *r);
/* Uniform in [0, 1) with 53 random bits. */
double rng_next_double(rng_t *r);
/* Uniform integer in [0, bound), unbiased (rejection); bound > 0. */
uint32_t rng_next_bounded(rng_t *r, uint32_t bound);
/* The stream for one pixel sample of a render with a global seed: distinct
 * (seed, px, py, sample) give decorrelated streams. */
rng_t rng_for_sample(uint64_t seed, uint32_t px, uint32_t py, uint32_t sample);
/* SplitMix64's finaliser: a bijective 64-bit mixer that spreads structured
 * keys (pixel coordinates, sample numbers, dimensions) into hash values. */
static inline uint64_t rng_mix64(uint64_t z)
{
    z += 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

#endif
