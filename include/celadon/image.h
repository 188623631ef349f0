/* Image I/O: a thin C API over OpenImageIO (src/image/oiio_shim.cpp). */
#ifndef CELADON_IMAGE_H
#define CELADON_IMAGE_H

#include <stddef.h>
#include <stdint.h>

/* Pixels as float in [0,1] (the file's encoded values: 8-bit sRGB stays sRGB),
 * row-major, channels interleaved, origin top-left, EXIF orientation applied. */
typedef struct {
    int width, height, channels;
    int bits;        /* bits per channel in the file (8, 16, 32, ...) */
    int has_alpha;   /* the last channel is alpha */
    float *data;
} image_t;

/* Reads any format OpenImageIO knows. Returns 0 on success; otherwise -1 with a
 * one-line reason (without the file name) in err. */
int image_read(const char *path, image_t *img, char *err, size_t errlen);

/* image_read behind the checks a photo must pass: a readable, non-empty
 * regular file, an image format, each side at least min_side px and at most
 * max_megapixels (checked on the header, before any pixel is decoded).
 * Decoding libraries' own stderr lines are suppressed (stderr is captured
 * around the call, so calls are serialised). Returns 0, or -1 with a
 * one-line reason (without the file name) in err. */
int image_read_checked(const char *path, int min_side, double max_megapixels, image_t *img, char *err,
                       size_t errlen);

/* image_read with the decoding libraries' own stderr lines suppressed, as
 * image_read_checked does them: for files whose error the caller reports
 * in one line of its own (a scene's textures). */
int image_read_quiet(const char *path, image_t *img, char *err, size_t errlen);

/* Reads only the header: size and channels, cheap. */
int image_probe(const char *path, int *width, int *height, int *channels, char *err, size_t errlen);

/* The photo's 35 mm equivalent focal length from its EXIF
 * (FocalLengthIn35mmFilm), mm; 0 when it has none or cannot be read. */
double image_exif_focal_35mm(const char *path);

/* Writes 8-bit pixels; the format follows the extension (png, jpg, tif, ...).
 * Written to a temporary file in the same folder and renamed, so a failure
 * leaves no partial file. */
int image_write_u8(const char *path, int width, int height, int channels,
                   const uint8_t *pixels, char *err, size_t errlen);

/* Writes 16-bit pixels (PNG, TIFF), atomically like image_write_u8. */
int image_write_u16(const char *path, int width, int height, int channels,
                    const uint16_t *pixels, char *err, size_t errlen);

/* A text attribute of a written image, under OpenImageIO's name for it:
 * "ImageDescription" (PNG's Description, JPEG's comment, TIFF's
 * ImageDescription), "Software", "DateTime", or any other name (a PNG
 * text chunk, a TIFF or EXR header attribute). */
typedef struct {
    const char *name, *value;
} image_text;

typedef enum { IMAGE_U8, IMAGE_U16, IMAGE_F32 } image_sample_type;

/* Writes pixels of that sample type with the text attributes, atomically
 * like image_write_u8; the format follows the extension (png, jpg, tif,
 * hdr, ...). Returns 0, or -1 with a one-line reason. */
int image_write_with_text(const char *path, int width, int height, int channels, image_sample_type type,
                          const void *pixels, const image_text *text, int ntext, char *err, size_t errlen);

image_t image_alloc(int width, int height, int channels);
void image_free(image_t *img);

#endif
