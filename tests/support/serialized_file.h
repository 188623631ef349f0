/* Mitsuba `.serialized` files written by the tests themselves, in the layout
 * Mitsuba documents (src/shapes/serialized.c describes it): the shape's tests
 * read them back, and tests/tools/write_serialized_seeds.c makes the fuzz
 * target's seeds from them. */
#ifndef CELADON_TEST_SERIALIZED_FILE_H
#define CELADON_TEST_SERIALIZED_FILE_H

#include <stddef.h>

/* Each mesh k of a file: SERIALIZED_FILE_NV vertices at (i, i^2 + k, -i/4)
 * with normals (0, 0, 1), uvs (i/8, 1 - i/8) and colours (0.5, 0.5, 0.5)
 * where flags ask for them, and the fan of triangles (0, i, i + 1). */
enum {
    SERIALIZED_FILE_NV = 6,
    SERIALIZED_FILE_NORMALS = 0x1,
    SERIALIZED_FILE_UVS = 0x2,
    SERIALIZED_FILE_COLORS = 0x8,
};

/* A file of nmeshes (1 to 4) such meshes, format version 3 or 4, reals as
 * doubles (dbl) or floats, each mesh's stream compressed at zlib level
 * (0: stored, to 9), and the dictionary of their offsets at the end.
 * Returns the bytes (malloc'd) and their count in *len; aborts when out of
 * memory. */
unsigned char *serialized_file_bytes(int version, int nmeshes, int dbl, unsigned flags, int level, size_t *len);

/* The same written to path: 0, or -1 when it cannot be written. */
int serialized_file_write(const char *path, int version, int nmeshes, int dbl, unsigned flags, int level);

#endif
