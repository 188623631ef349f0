/* Criterion reports every assertion to its runner, which is slow in loops of
 * a million rays: such loops count their failures with CHECK, print the first
 * few, and assert once on the count. Each test file gets its own counter. */
#ifndef CELADON_TEST_COUNTED_CHECK_H
#define CELADON_TEST_COUNTED_CHECK_H

#include <stdio.h>

static int failures;
#define CHECK(cond, ...)                                                                                              \
    do {                                                                                                              \
        if (!(cond) && failures++ < 10) {                                                                              \
            fprintf(stderr, __VA_ARGS__);                                                                             \
            fputc('\n', stderr);                                                                                      \
        }                                                                                                             \
    } while (0)

#endif
