/* Texture dispatch, uv transforms and the constant texture. */
#include <stdlib.h>
#include <string.h>

#include "render/texture_impl.h"

uv_transform uv_transform_identity(void)
{
    return uv_transform_scale(1.0, 1.0);
}

uv_transform uv_transform_scale(double su, double sv)
{
    uv_transform t = {{{su, 0.0, 0.0}, {0.0, sv, 0.0}}};
    return t;
}

static vec2 uv_apply(const uv_transform *t, vec2 uv)
{
    return v2(t->m[0][0] * uv.x + t->m[0][1] * uv.y + t->m[0][2], t->m[1][0] * uv.x + t->m[1][1] * uv.y + t->m[1][2]);
}

int texture_wrap_parse(const char *name, texture_wrap *out)
{
    if (strcmp(name, "repeat") == 0)
        *out = TEXTURE_WRAP_REPEAT;
    else if (strcmp(name, "mirror") == 0)
        *out = TEXTURE_WRAP_MIRROR;
    else if (strcmp(name, "clamp") == 0)
        *out = TEXTURE_WRAP_CLAMP;
    else
        return -1;
    return 0;
}

int texture_filter_parse(const char *name, texture_filter *out)
{
    if (strcmp(name, "bilinear") == 0)
        *out = TEXTURE_FILTER_BILINEAR;
    else if (strcmp(name, "nearest") == 0)
        *out = TEXTURE_FILTER_NEAREST;
    else
        return -1;
    return 0;
}

texture_t *texture_create_constant(rgb value)
{
    texture_t *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    t->kind = TEXTURE_KIND_CONSTANT;
    t->to_uv = uv_transform_identity();
    t->u.constant = value;
    t->mean = value;
    return t;
}

rgb texture_eval(const texture_t *t, vec2 uv)
{
    switch (t->kind) {
    case TEXTURE_KIND_CONSTANT:
        return t->u.constant;
    case TEXTURE_KIND_BITMAP:
        return texture_bitmap_lookup(&t->u.bitmap, uv_apply(&t->to_uv, uv));
    case TEXTURE_KIND_CHECKERBOARD:
        return texture_checkerboard_lookup(t, uv_apply(&t->to_uv, uv));
    }
    return rgb_gray(0.0);
}

rgb texture_mean(const texture_t *t)
{
    return t->mean;
}

int texture_is_constant(const texture_t *t)
{
    return t->kind == TEXTURE_KIND_CONSTANT;
}

void texture_free(texture_t *t)
{
    if (!t)
        return;
    if (t->kind == TEXTURE_KIND_BITMAP)
        free(t->u.bitmap.pixels);
    free(t);
}

const char *const *texture_plugin_params(const char *plugin)
{
    static const char *const bitmap[] = {"filename", "filter_type", "wrap_mode", "raw", "to_uv", NULL};
    static const char *const checkerboard[] = {"color0", "color1", "to_uv", NULL};
    if (strcmp(plugin, "bitmap") == 0)
        return bitmap;
    if (strcmp(plugin, "checkerboard") == 0)
        return checkerboard;
    return NULL;
}
