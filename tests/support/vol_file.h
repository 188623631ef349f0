/* Mitsuba .vol grid files for tests (the gridvolume volume, the sdfgrid
 * shape): float32 values, x fastest, over the box [0,1]^3. */
#ifndef CELADON_TEST_VOL_FILE_H
#define CELADON_TEST_VOL_FILE_H

#include <stddef.h>

/* The bytes of a .vol file of nx x ny x nz points of `channels` floats
 * into buf (48 + 4 nx ny nz channels bytes); returns its length. */
size_t vol_file_bytes(unsigned char *buf, int nx, int ny, int nz, int channels, const float *values);
/* Writes such a file to path; fails the test if it cannot. */
void vol_file_write(const char *path, int nx, int ny, int nz, int channels, const float *values);

#endif
