/* The seeds of the `serialized` fuzz target (fuzz/seeds/serialized/): small
 * valid .serialized files of every kind the reader takes, written by
 * tests/support/serialized_file.c. `make fuzz-seeds` runs it:
 *   write_serialized_seeds DIR */
#include <stdio.h>

#include "../support/serialized_file.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: write_serialized_seeds DIR\n");
        return 2;
    }
    static const struct {
        const char *name;
        int version, nmeshes, dbl;
        unsigned flags;
        int level;
    } seeds[] = {
        {"v4-float-normals-uvs.serialized", 4, 1, 0, SERIALIZED_FILE_NORMALS | SERIALIZED_FILE_UVS, 9},
        {"v4-double-two-meshes.serialized", 4, 2, 1, SERIALIZED_FILE_NORMALS, 9},
        {"v3-float-uvs-colours-three-meshes.serialized", 3, 3, 0, SERIALIZED_FILE_UVS | SERIALIZED_FILE_COLORS, 6},
        {"v4-positions-only.serialized", 4, 1, 0, 0, 9},
        /* zlib level 0: the mesh stored in its stream, so that the fuzzer's
         * mutations reach the values rather than the compressed bits */
        {"v4-float-stored.serialized", 4, 2, 0, SERIALIZED_FILE_NORMALS | SERIALIZED_FILE_UVS, 0},
        {"v3-double-stored.serialized", 3, 1, 1, SERIALIZED_FILE_COLORS, 0},
    };
    for (size_t i = 0; i < sizeof seeds / sizeof *seeds; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], seeds[i].name);
        if (serialized_file_write(path, seeds[i].version, seeds[i].nmeshes, seeds[i].dbl, seeds[i].flags,
                                  seeds[i].level) != 0) {
            perror(path);
            return 1;
        }
    }
    return 0;
}
