/* Private layout of texture_t, shared by the texture_*.c files. */
#ifndef CELADON_TEXTURE_IMPL_H
#define CELADON_TEXTURE_IMPL_H

#include "celadon/texture.h"

typedef enum { TEXTURE_KIND_CONSTANT, TEXTURE_KIND_BITMAP, TEXTURE_KIND_CHECKERBOARD } texture_kind;

typedef struct {
    int width, height;
    rgb *pixels; /* linear, row-major, row 0 = top */
    texture_filter filter;
    texture_wrap wrap;
} texture_bitmap_data;

struct texture {
    texture_kind kind;
    uv_transform to_uv;
    rgb mean;
    union {
        rgb constant;
        texture_bitmap_data bitmap;
        struct { rgb color0, color1; } checker;
    } u;
};

rgb texture_bitmap_lookup(const texture_bitmap_data *b, vec2 uv);
rgb texture_checkerboard_lookup(const texture_t *t, vec2 uv);

#endif
