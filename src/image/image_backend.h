/* One interface for the codecs behind celadon/image.h: the PNG backend
 * (libpng, in the library itself) and the OpenImageIO backend (its own
 * shared object, loaded on first use: oiio_backend.h). image_io.c asks the
 * PNG backend first; what it declines goes to OpenImageIO. A backend only
 * decodes and encodes: the checks an input passes, the temporary names and
 * the renames stay in image_io.c. */
#ifndef CELADON_IMAGE_IMAGE_BACKEND_H
#define CELADON_IMAGE_IMAGE_BACKEND_H

#include <stddef.h>

#include "celadon/image.h"

/* Returned by a backend for a file it leaves to the next one (not its
 * format, or a variant of it that the next decodes its own way). */
enum { IMAGE_BACKEND_DECLINED = 1 };

/* Every function returns 0, IMAGE_BACKEND_DECLINED, or -1 with a one-line
 * reason in err; none throws. */
typedef struct {
    int (*probe)(const char *path, int *width, int *height, int *channels, char *err, size_t errlen);
    /* *mm = the file's FocalLengthIn35mmFilm, 0 when it has none or cannot
     * be read. */
    int (*exif_focal_35mm)(const char *path, double *mm);
    /* img->data is malloc'd; left NULL on failure. Pixels are floats: an
     * N-bit sample v as v * (1.0f / (2^N - 1)). */
    int (*read)(const char *path, image_t *img, char *err, size_t errlen);
    /* Writes pixels of that sample type to file, with the text attributes,
     * in the format format_path's extension names (file is a temporary
     * name with the same extension). */
    int (*write)(const char *format_path, const char *file, int width, int height, int channels,
                 image_sample_type type, const void *pixels, const image_text *text, int ntext, char *err,
                 size_t errlen);
} image_backend;

#endif
