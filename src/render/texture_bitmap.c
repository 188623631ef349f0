/* Bitmap texture: an image in linear RGB with bilinear or nearest lookups. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "render/texture_impl.h"

texture_bitmap_params texture_bitmap_defaults(void)
{
    texture_bitmap_params p = {NULL, TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_REPEAT, 0, uv_transform_identity()};
    return p;
}

/* Formats that store linear floating-point values (everything else is sRGB). */
static int is_linear_format(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return 0;
    static const char *const linear[] = {".exr", ".hdr", ".pfm", NULL};
    for (int i = 0; linear[i]; i++)
        if (strcasecmp(dot, linear[i]) == 0)
            return 1;
    return 0;
}

texture_t *texture_create_bitmap_image(const image_t *img, int srgb_encoded, const texture_bitmap_params *params,
                                       char *err, size_t errlen)
{
    if (img->width < 1 || img->height < 1 || img->channels < 1 || !img->data) {
        snprintf(err, errlen, "empty image");
        return NULL;
    }
    texture_t *t = calloc(1, sizeof *t);
    size_t n = (size_t)img->width * img->height;
    rgb *px = t ? malloc(n * sizeof *px) : NULL;
    if (!px) {
        free(t);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    int ch = img->channels;
    rgb sum = rgb_gray(0.0);
    for (size_t i = 0; i < n; i++) {
        const float *s = img->data + i * ch;
        rgb c = ch >= 3 ? rgb_make(s[0], s[1], s[2]) : rgb_gray(s[0]);
        if (srgb_encoded && !params->raw)
            c = rgb_srgb_to_linear(c);
        px[i] = c;
        sum = rgb_add(sum, c);
    }
    t->kind = TEXTURE_KIND_BITMAP;
    t->to_uv = params->to_uv;
    t->mean = rgb_scale(sum, 1.0 / (double)n);
    t->u.bitmap = (texture_bitmap_data){img->width, img->height, px, params->filter_type, params->wrap_mode};
    return t;
}

texture_t *texture_create_bitmap(const texture_bitmap_params *params, char *err, size_t errlen)
{
    if (!params->filename) {
        snprintf(err, errlen, "bitmap texture needs a filename");
        return NULL;
    }
    image_t img;
    char why[256];
    if (image_read(params->filename, &img, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return NULL;
    }
    texture_t *t = texture_create_bitmap_image(&img, !is_linear_format(params->filename), params, err, errlen);
    image_free(&img);
    return t;
}

/* Texel index i (integral valued) folded into [0, n) by the wrap mode. */
static int wrap_index(double i, int n, texture_wrap wrap)
{
    if (!isfinite(i))
        return 0;
    double m;
    switch (wrap) {
    case TEXTURE_WRAP_REPEAT:
        m = i - n * floor(i / n);
        break;
    case TEXTURE_WRAP_MIRROR:
        m = i - 2.0 * n * floor(i / (2.0 * n));
        if (m >= n)
            m = 2.0 * n - 1.0 - m;
        break;
    default:
        m = fmin(fmax(i, 0.0), n - 1.0);
        break;
    }
    int k = (int)m;
    return k < 0 ? 0 : (k >= n ? n - 1 : k);
}

static rgb texel(const texture_bitmap_data *b, double x, double y)
{
    int i = wrap_index(x, b->width, b->wrap), j = wrap_index(y, b->height, b->wrap);
    return b->pixels[(size_t)j * b->width + i];
}

rgb texture_bitmap_lookup(const texture_bitmap_data *b, vec2 uv)
{
    double x = uv.x * b->width, y = uv.y * b->height;
    if (b->filter == TEXTURE_FILTER_NEAREST)
        return texel(b, floor(x), floor(y));
    x -= 0.5;
    y -= 0.5;
    double x0 = floor(x), y0 = floor(y);
    double fx = x - x0, fy = y - y0;
    if (!isfinite(fx) || !isfinite(fy))
        fx = fy = 0.0;
    rgb top = rgb_lerp(texel(b, x0, y0), texel(b, x0 + 1.0, y0), fx);
    rgb bottom = rgb_lerp(texel(b, x0, y0 + 1.0), texel(b, x0 + 1.0, y0 + 1.0), fx);
    return rgb_lerp(top, bottom, fy);
}
