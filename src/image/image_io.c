/* celadon/image.h's file I/O: the checks every input passes and the
 * temporary-then-rename of every output, around the OpenImageIO backend
 * that decodes and encodes (oiio_backend.h), loaded here. */
#include "celadon/image.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "core/core.h"
#include "image/oiio_backend.h"

/* Defined here only where a build links the backend in (the fuzzers). */
extern const oiio_backend celadon_oiio_backend __attribute__((weak));

const oiio_backend *oiio_backend_get(char *err, size_t errlen)
{
    static backend_library lib =
        BACKEND_LIBRARY("libceladon-oiio.so", "CELADON_OIIO_BACKEND", OIIO_BACKEND_SYMBOL, "the image library");
    return backend_library_get(&lib, &celadon_oiio_backend, err, errlen);
}

/* The backend, after the checks every input passes (the image library
 * opens the file itself). */
static const oiio_backend *for_input(const char *path, char *err, size_t errlen)
{
    if (input_check(path, INPUT_MAX_DATA_BYTES, NULL, err, errlen) != 0)
        return NULL;
    return oiio_backend_get(err, errlen);
}

int image_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
{
    const oiio_backend *b = for_input(path, err, errlen);
    return b ? b->probe(path, width, height, channels, err, errlen) : -1;
}

double image_exif_focal_35mm(const char *path)
{
    const oiio_backend *b = oiio_backend_get(NULL, 0);
    return b ? b->exif_focal_35mm(path) : 0.0;
}

int image_read(const char *path, image_t *img, char *err, size_t errlen)
{
    memset(img, 0, sizeof *img);
    const oiio_backend *b = for_input(path, err, errlen);
    return b ? b->read(path, img, err, errlen) : -1;
}

/* Written to a temporary sibling, renamed when whole; removed on any failure. */
int image_write_with_text(const char *path, int w, int h, int ch, image_sample_type type, const void *pixels,
                          const image_text *text, int ntext, char *err, size_t errlen)
{
    const oiio_backend *b = oiio_backend_get(err, errlen);
    if (!b)
        return -1;
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    int rc = b->write(path, tmp, w, h, ch, type, pixels, text, ntext, err, errlen);
    if (rc == 0 && rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot rename into place: %s", strerror(errno));
        rc = -1;
    }
    if (rc != 0)
        remove(tmp);
    atomic_temp_done(tmp);
    return rc;
}

int image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels, char *err,
                   size_t errlen)
{
    return image_write_with_text(path, width, height, channels, IMAGE_U8, pixels, NULL, 0, err, errlen);
}

int image_write_u16(const char *path, int width, int height, int channels, const uint16_t *pixels, char *err,
                    size_t errlen)
{
    return image_write_with_text(path, width, height, channels, IMAGE_U16, pixels, NULL, 0, err, errlen);
}
