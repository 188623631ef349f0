/* The OpenImageIO backend: the one C++ file (oiio_shim.cpp), built as its own
 * shared object (libceladon-oiio.so) and loaded on the first image read or
 * written. OpenImageIO as Debian builds it brings about 270 shared
 * libraries (codecs, OpenCV, GDAL, ...) whose loading and relocation cost
 * 0.4-0.5 s of CPU at every process start (0.75 s under ASan): a render to
 * EXR, a mesh or a merge never pays it (docs/BENCHMARKS.md, "Test suite").
 * The backend decodes and encodes files only; the checks an input passes,
 * the temporary names and the renames stay in C (image_io.c). */
#ifndef CELADON_IMAGE_OIIO_BACKEND_H
#define CELADON_IMAGE_OIIO_BACKEND_H

#include <stddef.h>

#include "celadon/image.h"

/* Every function returns 0, or -1 with a one-line reason in err; none
 * throws. */
typedef struct {
    int (*probe)(const char *path, int *width, int *height, int *channels, char *err, size_t errlen);
    /* 0 when the file has no FocalLengthIn35mmFilm or cannot be read. */
    double (*exif_focal_35mm)(const char *path);
    /* img->data is malloc'd; left NULL on failure. */
    int (*read)(const char *path, image_t *img, char *err, size_t errlen);
    /* Writes pixels of that sample type to file, with the text attributes,
     * in the format format_path's extension names (file is a temporary
     * name with the same extension). */
    int (*write)(const char *format_path, const char *file, int width, int height, int channels,
                 image_sample_type type, const void *pixels, const image_text *text, int ntext, char *err,
                 size_t errlen);
} oiio_backend;

/* The symbol the shared object exports. */
#define OIIO_BACKEND_SYMBOL "celadon_oiio_backend"

/* The backend, loaded by the first call (thread-safe; backend_library.h
 * says where it is looked for, $CELADON_OIIO_BACKEND first); NULL with one
 * line in err when it cannot be loaded. */
const oiio_backend *oiio_backend_get(char *err, size_t errlen);

#endif
