/* Radiance RGBE (.hdr) images in memory: the museum's environment probes,
 * which three.js's HDRLoader reads (Ward, "Real Pixels", Graphics Gems II,
 * 1991: a shared 8-bit exponent and three 8-bit mantissas; scanlines in the
 * "new" run-length form: 2, 2, width, then each component's bytes in
 * literal runs of at most 128, here never repeated runs). */
#ifndef CELADON_MUSEUM_RGBE_H
#define CELADON_MUSEUM_RGBE_H

#include <stddef.h>
#include <stdint.h>

/* Encodes width x height linear RGB floats (rows top down; 8 <= width <
 * 32768) into *out (malloc'd). Returns 0, or -1 out of memory. */
int rgbe_encode(const float *rgb, int width, int height, uint8_t **out, size_t *len);

/* One pixel's four bytes, and back (for tests): relative error under 2^-8. */
void rgbe_from_float(const float c[3], uint8_t e[4]);
void rgbe_to_float(const uint8_t e[4], float c[3]);

#endif
