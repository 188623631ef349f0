/* Seeded, stateless noise for synthetic photographs: every value is a pure
 * function of (seed, coordinates), so a drawing is the same in any order, on
 * any thread, on every run. */
#ifndef CELADON_TESTS_SYNTH_NOISE_H
#define CELADON_TESTS_SYNTH_NOISE_H

#include <stdint.h>

/* Uniform in [0, 1) for the integer lattice point (x, y) and a stream k. */
double synth_noise_uniform(uint32_t seed, int x, int y, int k);

/* Standard normal (Box-Muller on two uniforms of the same point). */
double synth_noise_gauss(uint32_t seed, int x, int y, int k);

/* Smooth value noise in [-1, 1] at a real point: uniform values on the unit
 * lattice, blended by smoothstep (C1). */
double synth_noise_value(uint32_t seed, double x, double y);

/* Fractal sum of `octaves` value noises, the first at `scale` px, each next
 * at half the scale and half the amplitude; normalised to [-1, 1]. */
double synth_noise_fractal(uint32_t seed, double x, double y, double scale, int octaves);

#endif
