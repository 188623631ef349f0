/* Hashes, permutations and the Sobol (0,2)-sequence with Owen scrambling;
 * see sequences.h. */
#include "samplers/sequences.h"

#include <pthread.h>

/* One round of a keyed bijection of the k-bit words (mask = 2^k - 1): xor a
 * key, multiply by an odd number (carries move entropy up), xorshift right
 * (moves it down); each step is invertible modulo 2^k. */
static uint32_t permute_round(uint32_t x, uint32_t mask, int shift, uint32_t key, uint32_t mult)
{
    x = (x ^ key) & mask;
    x = (x * (mult | 1u)) & mask;
    return x ^ (x >> shift);
}

uint32_t seq_permute(uint32_t i, uint32_t n, uint32_t seed)
{
    if (n <= 1)
        return 0;
    uint32_t mask = n - 1;
    mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
    int bits = 32 - __builtin_clz(mask), shift = bits > 1 ? (bits + 1) / 2 : 1;
    /* Only the low k bits of a key act on k-bit words: each round takes its
     * key and multiplier from a different slice of a hash of the seed, so
     * small counts get many permutations too. */
    uint64_t h = rng_mix64(seed), g = rng_mix64(h);
    /* Cycle walking: a bijection of [0, mask] applied until the value is
     * below n is a bijection of [0, n) (under two steps on average). */
    do {
        i = permute_round(i, mask, shift, (uint32_t)h, (uint32_t)g);
        i = permute_round(i, mask, shift, (uint32_t)(h >> 16), (uint32_t)(g >> 16));
        i = permute_round(i, mask, shift, (uint32_t)(h >> 32), (uint32_t)(g >> 32));
        i = permute_round(i, mask, shift, (uint32_t)(h >> 48), (uint32_t)(g >> 48));
    } while (i >= n);
    return i;
}

/* Sobol's second dimension (primitive polynomial x + 1) has the direction
 * numbers v_1 = 1/2, v_(k+1) = v_k xor v_k / 2 (Pascal's triangle mod 2);
 * point i is the xor of v_k over the bits k of i, i.e. linear over GF(2),
 * so four tables of the xors over each byte of i (kept reversed) give it in
 * four lookups. */
static uint32_t sobol1_bytes[4][256];
static pthread_once_t sobol1_once = PTHREAD_ONCE_INIT;

static void sobol1_tables(void)
{
    uint32_t v[32];
    v[0] = 1u << 31;
    for (int k = 1; k < 32; k++)
        v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int b = 0; b < 4; b++)
        for (uint32_t x = 0; x < 256; x++) {
            uint32_t r = 0;
            for (int k = 0; k < 8; k++)
                if (x & (1u << k))
                    r ^= v[8 * b + k];
            sobol1_bytes[b][x] = seq_reverse_bits(r);
        }
}

uint32_t seq_sobol1_reversed(uint32_t i)
{
    pthread_once(&sobol1_once, sobol1_tables);
    return sobol1_bytes[0][i & 255u] ^ sobol1_bytes[1][(i >> 8) & 255u] ^ sobol1_bytes[2][(i >> 16) & 255u] ^
           sobol1_bytes[3][i >> 24];
}
