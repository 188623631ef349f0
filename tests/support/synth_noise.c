/* Seeded, stateless noise: see synth_noise.h. */
#include "synth_noise.h"

#include <math.h>

/* A 32-bit integer hash with full avalanche (the "lowbias32" finaliser). */
static uint32_t mix32(uint32_t h)
{
    h ^= h >> 16;
    h *= 0x7feb352dU;
    h ^= h >> 15;
    h *= 0x846ca68bU;
    h ^= h >> 16;
    return h;
}

double synth_noise_uniform(uint32_t seed, int x, int y, int k)
{
    uint32_t h = mix32(seed ^ 0x9e3779b9U);
    h = mix32(h ^ (uint32_t)x);
    h = mix32(h ^ (uint32_t)y);
    h = mix32(h ^ (uint32_t)k);
    return (h >> 8) * (1.0 / 16777216.0);
}

double synth_noise_gauss(uint32_t seed, int x, int y, int k)
{
    double u1 = synth_noise_uniform(seed, x, y, 2 * k), u2 = synth_noise_uniform(seed, x, y, 2 * k + 1);
    return sqrt(-2 * log(1 - u1)) * cos(6.283185307179586 * u2);
}

double synth_noise_value(uint32_t seed, double x, double y)
{
    double fx = floor(x), fy = floor(y), tx = x - fx, ty = y - fy;
    int ix = (int)fx, iy = (int)fy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    double v00 = synth_noise_uniform(seed, ix, iy, 0), v10 = synth_noise_uniform(seed, ix + 1, iy, 0);
    double v01 = synth_noise_uniform(seed, ix, iy + 1, 0), v11 = synth_noise_uniform(seed, ix + 1, iy + 1, 0);
    double v = (v00 + tx * (v10 - v00)) + ty * ((v01 + tx * (v11 - v01)) - (v00 + tx * (v10 - v00)));
    return 2 * v - 1;
}

double synth_noise_fractal(uint32_t seed, double x, double y, double scale, int octaves)
{
    double sum = 0, norm = 0, amp = 1;
    for (int o = 0; o < octaves; o++, amp *= 0.5, scale *= 0.5) {
        sum += amp * synth_noise_value(seed + (uint32_t)o * 7919U, x / scale, y / scale);
        norm += amp;
    }
    return norm > 0 ? sum / norm : 0;
}
