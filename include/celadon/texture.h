/* Textures in the sense of Mitsuba 3: functions of the surface uv returning
 * linear RGB. Plugins: a constant, `bitmap` (image file, sRGB-decoded unless
 * raw, bilinear or nearest lookups, repeat/mirror/clamp wrapping) and
 * `checkerboard`. All accept an affine `to_uv` transform applied to uv first.
 * Pixel lookup follows Mitsuba: texel (i, j) has its centre at
 * uv = ((i + 0.5) / width, (j + 0.5) / height) with row j = 0 the top row of the
 * file, i.e. v grows downwards in the image. */
#ifndef CELADON_TEXTURE_H
#define CELADON_TEXTURE_H

#include <stddef.h>

#include "celadon/color.h"
#include "celadon/image.h"
#include "celadon/vecmath.h"

typedef struct texture texture_t;

typedef enum { TEXTURE_WRAP_REPEAT, TEXTURE_WRAP_MIRROR, TEXTURE_WRAP_CLAMP } texture_wrap;
typedef enum { TEXTURE_FILTER_BILINEAR, TEXTURE_FILTER_NEAREST } texture_filter;

/* uv' = (m[0][0] u + m[0][1] v + m[0][2], m[1][0] u + m[1][1] v + m[1][2]):
 * the upper 2x3 block of Mitsuba's 3x3 to_uv matrix. */
typedef struct { double m[2][3]; } uv_transform;
uv_transform uv_transform_identity(void);
uv_transform uv_transform_scale(double su, double sv);

typedef struct {
    const char *filename;
    texture_filter filter_type; /* default bilinear */
    texture_wrap wrap_mode;     /* default repeat */
    int raw;                    /* 1: no sRGB -> linear decoding (default 0) */
    uv_transform to_uv;         /* default identity */
} texture_bitmap_params;

typedef struct {
    rgb color0, color1; /* defaults 0.4 and 0.2 */
    uv_transform to_uv;
} texture_checkerboard_params;

texture_bitmap_params texture_bitmap_defaults(void);
texture_checkerboard_params texture_checkerboard_defaults(void);

/* Parse Mitsuba's option strings; -1 for an unknown value. */
int texture_wrap_parse(const char *name, texture_wrap *out);
int texture_filter_parse(const char *name, texture_filter *out);

texture_t *texture_create_constant(rgb value);
/* Loads params->filename with image_read. 8/16-bit formats are treated as
 * sRGB-encoded and decoded to linear unless raw; float formats (exr, hdr, pfm)
 * are linear. One channel is grey, two are grey+alpha, 3+ are RGB(A); alpha is
 * ignored. NULL and a one-line reason in err on failure. */
texture_t *texture_create_bitmap(const texture_bitmap_params *params, char *err, size_t errlen);
/* The same from pixels already in memory (encoded values as image_read gives). */
texture_t *texture_create_bitmap_image(const image_t *img, int srgb_encoded, const texture_bitmap_params *params,
                                       char *err, size_t errlen);
texture_t *texture_create_checkerboard(const texture_checkerboard_params *params);

rgb texture_eval(const texture_t *t, vec2 uv);
/* Mean value over the uv unit square (Mitsuba's Texture::mean). */
rgb texture_mean(const texture_t *t);
/* 1 when eval does not depend on uv. */
int texture_is_constant(const texture_t *t);
void texture_free(texture_t *t);

/* Names of the parameters each texture plugin accepts (NULL-terminated), or
 * NULL for an unknown plugin name. */
const char *const *texture_plugin_params(const char *plugin);

#endif
