/* Fast printf("%.*g") for floats, for the text mesh exporters. */
#ifndef CELADON_MESH_FORMAT_FLOAT_H
#define CELADON_MESH_FORMAT_FLOAT_H

/* Writes v as snprintf(out, 32, "%.*g", precision, (double)v) does (byte
 * for byte, ties to even as glibc), precision 1..9, and returns the length
 * (no terminating NUL is written). out needs 16 bytes. */
int format_float_g(char *out, float v, int precision);

/* Writes v in decimal; returns the length (at most 10, no NUL). */
int format_uint(char *out, unsigned v);

#endif
