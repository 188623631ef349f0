/* Test profiles for the surface-of-revolution intersector and its Embree
 * cross-check: clamped cubic B-splines (r, h) with h(0) = 0 < h(1), r >= 0. */
#ifndef CELADON_TEST_SOR_PROFILES_H
#define CELADON_TEST_SOR_PROFILES_H

#include "celadon/bspline.h"
#include "celadon/sor.h"

int sor_test_profile_count(void);
/* A short lowercase name, e.g. "bowl". NULL when i is out of range. */
const char *sor_test_profile_name(int i);
/* Fills *out (allocated; free with bspline_free). i must be in range. */
void sor_test_profile(int i, bspline_t *out);

/* The SOR of profile i at height 1 with the given caps; aborts on failure. */
sor_t *sor_test_create(int i, unsigned caps);

#endif
