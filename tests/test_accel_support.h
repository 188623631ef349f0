/* Shared by the tests/test_accel_*.c suites: a seeded generator and random
 * rays around a box. */
#ifndef CELADON_TEST_ACCEL_SUPPORT_H
#define CELADON_TEST_ACCEL_SUPPORT_H

#include <stdint.h>

#include "celadon/vecmath.h"

typedef struct {
    uint64_t s;
} test_rng;

double test_rng_uniform(test_rng *r); /* [0, 1) */
vec3 test_rng_unit_vector(test_rng *r);

/* From a random point on the sphere around the box (1.5 times its half
 * diagonal) toward a random point inside it; the direction has a random length
 * in [0.5, 2), so callers never rely on unit directions. */
ray3 test_ray_toward_box(test_rng *r, vec3 lo, vec3 hi);
/* From a random point inside the box in a random direction. */
ray3 test_ray_inside_box(test_rng *r, vec3 lo, vec3 hi);

#endif
