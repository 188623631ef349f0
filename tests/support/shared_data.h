/* The project's shared data (../shared, or $CELADON_SHARED): where a test
 * finds it, and what happens when it is absent. Criterion prints no line
 * for a skipped test, so a missing data set would go unnoticed: with
 * $CELADON_REQUIRE_DATA set (CI does, .ci/run) the test fails instead. */
#ifndef CELADON_TEST_SHARED_DATA_H
#define CELADON_TEST_SHARED_DATA_H

#include <stddef.h>

/* out = "<shared>/rel". */
void shared_data_path(char *out, size_t len, const char *rel);

/* Returns when path exists; else skips the test, or fails it when
 * $CELADON_REQUIRE_DATA is set. */
void shared_data_require(const char *path);

#endif
