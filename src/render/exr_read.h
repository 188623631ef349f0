/* Reading back what exr_write_float_attrs writes (film.h): a scanline
 * OpenEXR's size, string attributes and float channels by name, through the
 * OpenEXR 3 core C API. Private to src/render/ (the parts' merge reads
 * with it). */
#ifndef CELADON_EXR_READ_H
#define CELADON_EXR_READ_H

#include <openexr.h>
#include <stddef.h>

#include "celadon/film.h"

typedef struct exr_in exr_in;

/* Opens path and reads its header; NULL with a one-line reason (naming the
 * file) in err when it is not a readable single-part scanline OpenEXR whose
 * data window starts at (0, 0). */
exr_in *exr_in_open(const char *path, char *err, size_t errlen);
void exr_in_close(exr_in *e);

void exr_in_size(const exr_in *e, int *width, int *height);
/* The string attribute name, or NULL when there is none of that type. */
const char *exr_in_attr(const exr_in *e, const char *name);
/* The film metadata of its header (exr_metadata.h). */
void exr_in_metadata(const exr_in *e, film_metadata *meta);
/* Whether the file has the channel. */
int exr_in_has_channel(const exr_in *e, const char *name);
/* The number of channels, and the name of channel i (0 <= i < count, in
 * the file's order: sorted by name), pointing into e. */
int exr_in_channel_count(const exr_in *e);
const char *exr_in_channel_name(const exr_in *e, int i);
/* The file's context, for exr_write_float_like to copy its header from. */
exr_const_context_t exr_in_context(const exr_in *e);

/* exr_write_float_attrs (film.h) with no film metadata: the attributes
 * are attrs, then every attribute of like's header that the new file does
 * not set itself (its channels, size and compression are its own). */
int exr_write_float_like(const char *path, int width, int height, int nch, const char *const *names,
                         const float *pixels, const exr_in *like, const film_attr *attrs, int nattrs, char *err,
                         size_t errlen);

/* Decodes the nch channels named names into pixels (width * height * nch
 * floats, interleaved in the order of names); every name must be a
 * channel. Returns 0, or -1 with a one-line reason naming the file. */
int exr_in_read(exr_in *e, int nch, const char *const *names, float *pixels, char *err, size_t errlen);

#endif
