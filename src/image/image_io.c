/* celadon/image.h's file I/O: the checks every input passes and the
 * temporary-then-rename of every output, around the backends that decode
 * and encode (image_backend.h): the PNG backend first, OpenImageIO (loaded
 * here, on first use) for what it declines. */
#include "celadon/image.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "core/core.h"
#include "image/oiio_backend.h"
#include "image/png_backend.h"

/* Defined here only where a build links the backend in (the fuzzers). */
extern const image_backend celadon_oiio_image_backend __attribute__((weak));

const image_backend *oiio_backend_get(char *err, size_t errlen)
{
    static backend_library lib =
        BACKEND_LIBRARY("libceladon-oiio.so", "CELADON_OIIO_BACKEND", OIIO_BACKEND_SYMBOL, "the image library");
    return backend_library_get(&lib, &celadon_oiio_image_backend, err, errlen);
}

int image_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen)
{
    if (input_check(path, INPUT_MAX_DATA_BYTES, NULL, err, errlen) != 0)
        return -1;
    int rc = png_backend.probe(path, width, height, channels, err, errlen);
    const image_backend *oiio;
    if (rc == IMAGE_BACKEND_DECLINED)
        rc = (oiio = oiio_backend_get(err, errlen)) ? oiio->probe(path, width, height, channels, err, errlen) : -1;
    return rc;
}

double image_exif_focal_35mm(const char *path)
{
    double mm = 0;
    int rc = png_backend.exif_focal_35mm(path, &mm);
    const image_backend *oiio;
    if (rc == IMAGE_BACKEND_DECLINED)
        rc = (oiio = oiio_backend_get(NULL, 0)) ? oiio->exif_focal_35mm(path, &mm) : -1;
    return rc == 0 ? mm : 0.0;
}

int image_read(const char *path, image_t *img, char *err, size_t errlen)
{
    memset(img, 0, sizeof *img);
    if (input_check(path, INPUT_MAX_DATA_BYTES, NULL, err, errlen) != 0)
        return -1;
    int rc = png_backend.read(path, img, err, errlen);
    const image_backend *oiio;
    if (rc == IMAGE_BACKEND_DECLINED)
        rc = (oiio = oiio_backend_get(err, errlen)) ? oiio->read(path, img, err, errlen) : -1;
    return rc;
}

/* Written to a temporary sibling, renamed when whole; removed on any failure. */
int image_write_with_text(const char *path, int w, int h, int ch, image_sample_type type, const void *pixels,
                          const image_text *text, int ntext, char *err, size_t errlen)
{
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    int rc = png_backend.write(path, tmp, w, h, ch, type, pixels, text, ntext, err, errlen);
    const image_backend *oiio;
    if (rc == IMAGE_BACKEND_DECLINED)
        rc = (oiio = oiio_backend_get(err, errlen)) ? oiio->write(path, tmp, w, h, ch, type, pixels, text, ntext, err, errlen)
                                            : -1;
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
