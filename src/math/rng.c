/* PCG32 (XSH-RR variant), written from the published algorithm description. */
#include "celadon/rng.h"

#define PCG_MULT 6364136223846793005ULL

void rng_seed(rng_t *r, uint64_t initstate, uint64_t initseq)
{
    r->state = 0;
    r->inc = (initseq << 1) | 1u;
    rng_next_u32(r);
    r->state += initstate;
    rng_next_u32(r);
}

uint32_t rng_next_u32(rng_t *r)
{
    uint64_t old = r->state;
    r->state = old * PCG_MULT + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
}

double rng_next_double(rng_t *r)
{
    uint64_t hi = rng_next_u32(r), lo = rng_next_u32(r);
    uint64_t bits = ((hi << 32) | lo) >> 11; /* 53 bits */
    return (double)bits * 0x1.0p-53;
}

uint32_t rng_next_bounded(rng_t *r, uint32_t bound)
{
    uint32_t threshold = (uint32_t)(-bound) % bound; /* 2^32 mod bound */
    for (;;) {
        uint32_t x = rng_next_u32(r);
        if (x >= threshold)
            return x % bound;
    }
}

rng_t rng_for_sample(uint64_t seed, uint32_t px, uint32_t py, uint32_t sample)
{
    uint64_t pixel = ((uint64_t)py << 32) | px;
    uint64_t key = rng_mix64(seed ^ rng_mix64(pixel));
    rng_t r;
    rng_seed(&r, rng_mix64(key ^ sample), key + sample);
    return r;
}
