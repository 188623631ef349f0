/* Outputs are checked before the work starts: a folder that cannot be
 * written is found in a moment, not after a long render (exit code 1,
 * docs/faults.md). */
#ifndef CELADON_CORE_OUTPUT_CHECK_H
#define CELADON_CORE_OUTPUT_CHECK_H

#include <stddef.h>

/* Whether path can be written: the output file path (or, with is_folder,
 * the output folder path, made with its missing parents) gets its
 * temporaries in the nearest folder that exists, so a file is created and
 * removed there. Returns 0, or -1 with a one-line reason without the path
 * in why ("Read-only file system", "Permission denied", "Not a directory"). */
int output_check(const char *path, int is_folder, char *why, size_t whylen);

#endif
