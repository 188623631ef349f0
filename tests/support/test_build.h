/* Which build of the suite is running. The optimised build asserts what
 * depends on speed or on many samples; the ASan+UBSan build (2-4x slower)
 * runs the same code to let the sanitizers check it, on a share of the
 * cases or sizes where the optimised run already asserts every number
 * (docs/BENCHMARKS.md, "Test suite"). */
#ifndef CELADON_TEST_BUILD_H
#define CELADON_TEST_BUILD_H

#include <stdbool.h>

/* True in the ASan+UBSan build (the compiler defines __SANITIZE_ADDRESS__). */
bool test_build_is_sanitized(void);

/* n in the optimised build, n / share (at least 1) in the sanitized one:
 * the count of random samples or the size of an input. */
int test_build_share(int n, int share);

/* The step through a loop over n independent cases: 1 in the optimised
 * build, so that the sanitized one runs about n / share of them (the first
 * always). */
int test_build_case_step(int share);

#endif
