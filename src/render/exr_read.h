/* Reading back what exr_write_float_attrs writes (film.h): a scanline
 * OpenEXR's size, string attributes and float channels by name, through the
 * OpenEXR 3 core C API. Private to src/render/ (the parts' merge reads
 * with it). */
#ifndef CELADON_EXR_READ_H
#define CELADON_EXR_READ_H

#include <stddef.h>

typedef struct exr_in exr_in;

/* Opens path and reads its header; NULL with a one-line reason (naming the
 * file) in err when it is not a readable single-part scanline OpenEXR whose
 * data window starts at (0, 0). */
exr_in *exr_in_open(const char *path, char *err, size_t errlen);
void exr_in_close(exr_in *e);

void exr_in_size(const exr_in *e, int *width, int *height);
/* The string attribute name, or NULL when there is none of that type. */
const char *exr_in_attr(const exr_in *e, const char *name);
/* Whether the file has the channel. */
int exr_in_has_channel(const exr_in *e, const char *name);

/* Decodes the nch channels named names into pixels (width * height * nch
 * floats, interleaved in the order of names); every name must be a
 * channel. Returns 0, or -1 with a one-line reason naming the file. */
int exr_in_read(exr_in *e, int nch, const char *const *names, float *pixels, char *err, size_t errlen);

#endif
