/* Mitsuba's `bitmap` texture: an image in linear RGB with bilinear or nearest
 * lookups and repeat, mirror or clamp wrapping. 8- and 16-bit files are
 * sRGB-decoded unless `raw`; float formats (exr, hdr, pfm) are linear. One
 * channel is grey, two are grey+alpha, 3+ are RGB(A); alpha is ignored. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/image.h"
#include "textures/texture_impl.h"

typedef enum { WRAP_REPEAT, WRAP_MIRROR, WRAP_CLAMP } wrap_mode;

typedef struct {
    int width, height;
    rgb *pixels; /* linear, row-major, row 0 = top */
    int nearest; /* 1: nearest texel, 0: bilinear */
    wrap_mode wrap;
} bitmap;

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

/* Texel index i (integral valued) folded into [0, n) by the wrap mode. */
static int wrap_index(double i, int n, wrap_mode wrap)
{
    if (!isfinite(i))
        return 0;
    double m;
    switch (wrap) {
    case WRAP_REPEAT:
        m = i - n * floor(i / n);
        break;
    case WRAP_MIRROR:
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

static rgb texel(const bitmap *b, double x, double y)
{
    int i = wrap_index(x, b->width, b->wrap), j = wrap_index(y, b->height, b->wrap);
    return b->pixels[(size_t)j * b->width + i];
}

static rgb bitmap_lookup(const texture_t *t, vec2 uv)
{
    const bitmap *b = t->data;
    double x = uv.x * b->width, y = uv.y * b->height;
    if (b->nearest)
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

/* The bilinear interpolant's gradient, of the texels' luminance: within a
 * cell f = lerp(lerp(f00, f10, fx), lerp(f01, f11, fx), fy), by texel
 * units, times the resolution for uv units (Mitsuba's eval_1_grad). */
static vec2 bitmap_gradient_1(const texture_t *t, vec2 uv)
{
    const bitmap *b = t->data;
    if (b->nearest)
        return v2(0.0, 0.0);
    double x = uv.x * b->width - 0.5, y = uv.y * b->height - 0.5;
    double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    if (!isfinite(fx) || !isfinite(fy))
        return v2(0.0, 0.0);
    double f00 = rgb_luminance(texel(b, x0, y0)), f10 = rgb_luminance(texel(b, x0 + 1.0, y0));
    double f01 = rgb_luminance(texel(b, x0, y0 + 1.0)), f11 = rgb_luminance(texel(b, x0 + 1.0, y0 + 1.0));
    double dx = (1.0 - fy) * (f10 - f00) + fy * (f11 - f01), dy = (1.0 - fx) * (f01 - f00) + fx * (f11 - f10);
    return v2(dx * b->width, dy * b->height);
}

static void bitmap_release(void *data)
{
    free(((bitmap *)data)->pixels);
}

static const texture_ops bitmap_ops = {bitmap_lookup, bitmap_release, bitmap_gradient_1, NULL, NULL};

/* The decoded pixels of img into t, and their mean. */
static int fill_pixels(texture_t *t, const image_t *img, int decode_srgb)
{
    bitmap *b = t->data;
    size_t n = (size_t)img->width * img->height;
    b->pixels = malloc(n * sizeof *b->pixels);
    if (!b->pixels)
        return -1;
    b->width = t->width = img->width, b->height = t->height = img->height;
    int ch = img->channels;
    rgb sum = rgb_gray(0.0);
    for (size_t i = 0; i < n; i++) {
        const float *s = img->data + i * ch;
        rgb c = ch >= 3 ? rgb_make(s[0], s[1], s[2]) : rgb_gray(s[0]);
        if (decode_srgb)
            c = rgb_srgb_to_linear(c);
        b->pixels[i] = c;
        sum = rgb_add(sum, c);
    }
    t->mean = rgb_scale(sum, 1.0 / (double)n);
    return 0;
}

static texture_t *bitmap_create(scene_obj *o, char *err, size_t errlen)
{
    const char *filename = scene_obj_string(o, "filename", NULL);
    bool raw = scene_obj_bool(o, "raw", false);
    const char *filter = scene_obj_string(o, "filter_type", "bilinear");
    const char *wrap = scene_obj_string(o, "wrap_mode", "repeat");
    (void)scene_obj_string(o, "format", "auto"); /* texels are kept as floats whatever the storage asked for */
    uv_transform to_uv = texture_to_uv_param(o);
    image_t img;
    char why[256];
    if (image_read_quiet(filename, &img, why, sizeof why) != 0) {
        /* The texture is the bad input: its name first (issue 28). */
        snprintf(err, errlen, "%s: not a readable image (%s; the bitmap texture at %s:%d)", filename, why, o->file,
                 o->line);
        return NULL;
    }
    texture_t *t = NULL;
    if (img.width < 1 || img.height < 1 || img.channels < 1 || !img.data) {
        scene_obj_error(o, err, errlen, "empty image");
    } else if (!(t = texture_alloc(&bitmap_ops, sizeof(bitmap))) ||
               fill_pixels(t, &img, !is_linear_format(filename) && !raw) != 0) {
        free(t);
        t = NULL;
        scene_obj_error(o, err, errlen, "out of memory");
    } else {
        bitmap *b = t->data;
        b->nearest = strcmp(filter, "nearest") == 0;
        b->wrap = !strcmp(wrap, "mirror") ? WRAP_MIRROR : !strcmp(wrap, "clamp") ? WRAP_CLAMP : WRAP_REPEAT;
        t->to_uv = to_uv;
    }
    image_free(&img);
    return t;
}

static const scene_param_decl bitmap_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"raw", PARAM_BOOL, 0, NULL},
    {"filter_type", PARAM_STRING, 0, "nearest|bilinear"},
    {"wrap_mode", PARAM_STRING, 0, "repeat|mirror|clamp"},
    {"format", PARAM_STRING, 0, "auto|variant|float16|fp16|uint8"},
    {"to_uv", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const texture_plugin texture_bitmap = {
    .decl = {.cls = SCENE_TEXTURE, .type = "bitmap", .params = bitmap_params},
    .create = bitmap_create,
};
