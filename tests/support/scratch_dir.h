/* A temporary folder for a test suite's files: made by the suite's .init,
 * removed with everything in it by its .fini. */
#ifndef CELADON_TEST_SCRATCH_DIR_H
#define CELADON_TEST_SCRATCH_DIR_H

#include <stddef.h>

/* Makes /tmp/celadon-<tag>-XXXXXX into dir (len >= 64); fails the test if it cannot. */
void scratch_dir_make(char *dir, size_t len, const char *tag);
/* Writes text to dir/name; its path into path. */
void scratch_write_file(const char *dir, const char *name, const char *text, char *path, size_t len);
/* Removes dir and everything under it. */
void scratch_dir_remove(const char *dir);

#endif
