/* Textures: sRGB decoding of a PNG written here, bilinear and nearest lookups
 * at known uv, Mitsuba's wrap modes, the checkerboard pattern. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/texture.h"

static char dir[64];
static char png[128];

/* A 4x2 RGB image: pixel (i, j) has channels (40 i + 10 j, 255 - 60 i, 128). */
static uint8_t pixel_value(int i, int j, int c)
{
    return (uint8_t)(c == 0 ? 40 * i + 10 * j : c == 1 ? 255 - 60 * i : 128);
}

static void write_png(void)
{
    strcpy(dir, "/tmp/celadon-texture-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    snprintf(png, sizeof png, "%s/t.png", dir);
    uint8_t px[4 * 2 * 3];
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 4; i++)
            for (int c = 0; c < 3; c++)
                px[(j * 4 + i) * 3 + c] = pixel_value(i, j, c);
    char err[256];
    cr_assert_eq(image_write_u8(png, 4, 2, 3, px, err, sizeof err), 0, "%s", err);
}

static void remove_png(void)
{
    unlink(png);
    rmdir(dir);
}

static rgb expected_linear(int i, int j)
{
    return rgb_make(srgb_to_linear(pixel_value(i, j, 0) / 255.0), srgb_to_linear(pixel_value(i, j, 1) / 255.0),
                    srgb_to_linear(pixel_value(i, j, 2) / 255.0));
}

static vec2 texel_centre(int i, int j) { return v2((i + 0.5) / 4.0, (j + 0.5) / 2.0); }

static void assert_rgb(rgb a, rgb b, double tol, const char *what)
{
    cr_assert(fabs(a.r - b.r) <= tol && fabs(a.g - b.g) <= tol && fabs(a.b - b.b) <= tol,
              "%s: (%g %g %g) vs (%g %g %g)", what, a.r, a.g, a.b, b.r, b.g, b.b);
}

static texture_t *load(texture_filter filter, texture_wrap wrap, int raw)
{
    texture_bitmap_params p = texture_bitmap_defaults();
    p.filename = png;
    p.filter_type = filter;
    p.wrap_mode = wrap;
    p.raw = raw;
    char err[256];
    texture_t *t = texture_create_bitmap(&p, err, sizeof err);
    cr_assert_not_null(t, "%s", err);
    return t;
}

TestSuite(texture, .init = write_png, .fini = remove_png);

Test(texture, bitmap_decodes_srgb_unless_raw)
{
    texture_bitmap_params d = texture_bitmap_defaults();
    cr_assert_eq(d.filter_type, TEXTURE_FILTER_BILINEAR);
    cr_assert_eq(d.wrap_mode, TEXTURE_WRAP_REPEAT);
    cr_assert_eq(d.raw, 0);
    texture_t *t = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_REPEAT, 0);
    texture_t *raw = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_REPEAT, 1);
    rgb mean = rgb_gray(0.0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 4; i++) {
            /* At a texel centre bilinear filtering returns the texel; row 0 is the top. */
            assert_rgb(texture_eval(t, texel_centre(i, j)), expected_linear(i, j), 1e-6, "decoded");
            rgb e = rgb_make(pixel_value(i, j, 0) / 255.0, pixel_value(i, j, 1) / 255.0, pixel_value(i, j, 2) / 255.0);
            assert_rgb(texture_eval(raw, texel_centre(i, j)), e, 1e-6, "raw");
            mean = rgb_add(mean, rgb_scale(expected_linear(i, j), 1.0 / 8.0));
        }
    assert_rgb(texture_mean(t), mean, 1e-6, "mean");
    /* Mid-grey 128 decodes to about 0.2158 (IEC 61966-2-1). */
    cr_assert_float_eq(texture_eval(t, texel_centre(0, 0)).b, 0.21586, 1e-5);
    cr_assert_eq(texture_is_constant(t), 0);
    texture_free(t);
    texture_free(raw);
}

Test(texture, bilinear_interpolates_linear_values)
{
    texture_t *t = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_CLAMP, 0);
    /* x = u * 4 - 0.5 = 1.25, y = v * 2 - 0.5 = 0.5: a quarter of the way from
     * texel column 1 to 2, halfway between rows 0 and 1. */
    vec2 uv = v2(1.75 / 4.0, 0.5);
    rgb top = rgb_lerp(expected_linear(1, 0), expected_linear(2, 0), 0.25);
    rgb bottom = rgb_lerp(expected_linear(1, 1), expected_linear(2, 1), 0.25);
    assert_rgb(texture_eval(t, uv), rgb_lerp(top, bottom, 0.5), 1e-6, "bilinear");
    texture_free(t);

    texture_t *n = load(TEXTURE_FILTER_NEAREST, TEXTURE_WRAP_CLAMP, 0);
    assert_rgb(texture_eval(n, uv), expected_linear(1, 1), 1e-6, "nearest");
    assert_rgb(texture_eval(n, v2(0.74, 0.49)), expected_linear(2, 0), 1e-6, "nearest");
    texture_free(n);
}

Test(texture, wrap_modes_follow_mitsuba)
{
    texture_t *rep = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_REPEAT, 0);
    texture_t *mir = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_MIRROR, 0);
    texture_t *cla = load(TEXTURE_FILTER_BILINEAR, TEXTURE_WRAP_CLAMP, 0);
    const vec2 probes[] = {{0.1, 0.3}, {0.37, 0.8}, {0.93, 0.05}, {0.5, 0.5}};
    for (int k = 0; k < 4; k++) {
        vec2 p = probes[k];
        /* repeat: period 1 in u and v */
        assert_rgb(texture_eval(rep, v2(p.x + 3.0, p.y - 2.0)), texture_eval(rep, p), 1e-9, "repeat");
        /* mirror: symmetric about 0 and 1, period 2 */
        assert_rgb(texture_eval(mir, v2(-p.x, p.y)), texture_eval(mir, p), 1e-9, "mirror at 0");
        assert_rgb(texture_eval(mir, v2(2.0 - p.x, p.y)), texture_eval(mir, p), 1e-9, "mirror at 1");
        assert_rgb(texture_eval(mir, v2(p.x + 2.0, -p.y)), texture_eval(mir, p), 1e-9, "mirror period");
    }
    /* Repeat blends the last and first columns across the seam. */
    rgb seam = rgb_lerp(expected_linear(3, 0), expected_linear(0, 0), 0.5);
    assert_rgb(texture_eval(rep, v2(1.0, 0.25)), seam, 1e-6, "repeat seam");
    /* Clamp holds the edge texels beyond the border. */
    assert_rgb(texture_eval(cla, v2(-5.0, 0.25)), expected_linear(0, 0), 1e-6, "clamp low");
    assert_rgb(texture_eval(cla, v2(1.7, 3.0)), expected_linear(3, 1), 1e-6, "clamp high");
    /* Non-finite coordinates do not crash. */
    rgb x = texture_eval(rep, v2(NAN, INFINITY));
    cr_assert(isfinite(x.r));
    x = texture_eval(mir, v2(1e300, -1e300));
    cr_assert(isfinite(x.r));
    texture_free(rep);
    texture_free(mir);
    texture_free(cla);
}

Test(texture, to_uv_and_grey_images)
{
    float grey[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    image_t img = {2, 2, 1, 8, 0, grey};
    texture_bitmap_params p = texture_bitmap_defaults();
    p.filter_type = TEXTURE_FILTER_NEAREST;
    p.to_uv = uv_transform_scale(0.5, 0.5);
    char err[256];
    texture_t *t = texture_create_bitmap_image(&img, 0, &p, err, sizeof err);
    cr_assert_not_null(t);
    /* uv (1.5, 0.5) -> (0.75, 0.25): texel (1, 0); grey replicated, no decoding. */
    rgb c = texture_eval(t, v2(1.5, 0.5));
    cr_assert(c.r == 0.25 && c.g == 0.25 && c.b == 0.25);
    texture_free(t);
}

Test(texture, checkerboard_pattern)
{
    texture_checkerboard_params p = texture_checkerboard_defaults();
    cr_assert_float_eq(p.color0.r, 0.4, 0);
    cr_assert_float_eq(p.color1.r, 0.2, 0);
    texture_t *t = texture_create_checkerboard(&p);
    cr_assert_float_eq(texture_eval(t, v2(0.25, 0.25)).g, 0.4, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.75, 0.25)).g, 0.2, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.25, 0.75)).g, 0.2, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.75, 0.75)).g, 0.4, 0);
    cr_assert_float_eq(texture_eval(t, v2(-0.25, 0.25)).g, 0.2, 0); /* frac(-0.25) = 0.75 */
    cr_assert_float_eq(texture_mean(t).b, 0.3, 1e-15);
    texture_free(t);
    p.to_uv = uv_transform_scale(4.0, 4.0);
    t = texture_create_checkerboard(&p);
    cr_assert_float_eq(texture_eval(t, v2(0.15, 0.05)).g, 0.2, 0); /* (0.6, 0.2) in tiles */
    cr_assert_float_eq(texture_eval(t, v2(0.1, 0.05)).g, 0.4, 0);  /* (0.4, 0.2) */
    texture_free(t);
    texture_t *c = texture_create_constant(rgb_make(1, 2, 3));
    cr_assert(texture_is_constant(c));
    cr_assert_eq(texture_eval(c, v2(9, 9)).b, 3.0);
    texture_free(c);
}

Test(texture, bad_input)
{
    texture_bitmap_params p = texture_bitmap_defaults();
    char err[256] = "";
    p.filename = "/nonexistent/nope.png";
    cr_assert_null(texture_create_bitmap(&p, err, sizeof err));
    cr_assert_gt(strlen(err), 0);
    p.filename = NULL;
    cr_assert_null(texture_create_bitmap(&p, err, sizeof err));
    texture_wrap w;
    texture_filter f;
    cr_assert_eq(texture_wrap_parse("mirror", &w), 0);
    cr_assert_eq(w, TEXTURE_WRAP_MIRROR);
    cr_assert_eq(texture_wrap_parse("border", &w), -1);
    cr_assert_eq(texture_filter_parse("nearest", &f), 0);
    cr_assert_eq(texture_filter_parse("trilinear", &f), -1);
    cr_assert_null(texture_plugin_params("noise"));
}
