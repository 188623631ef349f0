/* Textures: sRGB decoding of a PNG written here, bilinear and nearest lookups
 * at known uv, Mitsuba's wrap modes, the checkerboard pattern. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/film.h"
#include "celadon/image.h"
#include "support/plugin_xml.h"
#include "textures/textures.h"

static char dir[64];
static char png[128];
static plugin_xml fx;

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
    plugin_xml_open(&fx);
}

static void remove_png(void)
{
    plugin_xml_close(&fx);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

/* The texture of an XML snippet, which must build. */
static const texture_t *texture_of(const char *xml)
{
    char err[512];
    const texture_t *t = plugin_xml_texture(&fx, xml, err, sizeof err);
    cr_assert_not_null(t, "%s: %s", xml, err);
    return t;
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

/* The bitmap of the test image; filter and wrap NULL for Mitsuba's defaults. */
static const texture_t *load(const char *filter, const char *wrap, int raw)
{
    char xml[512], f[64] = "", w[64] = "";
    if (filter)
        snprintf(f, sizeof f, "<string name='filter_type' value='%s'/>", filter);
    if (wrap)
        snprintf(w, sizeof w, "<string name='wrap_mode' value='%s'/>", wrap);
    snprintf(xml, sizeof xml, "<texture type='bitmap'><string name='filename' value='%s'/>%s%s%s</texture>", png, f,
             w, raw ? "<boolean name='raw' value='true'/>" : "");
    return texture_of(xml);
}

TestSuite(texture, .init = write_png, .fini = remove_png);

Test(texture, bitmap_decodes_srgb_unless_raw)
{
    /* Mitsuba's defaults are bilinear, repeat, decoded: the same texture as spelled out. */
    const texture_t *t = load(NULL, NULL, 0);
    const texture_t *spelled = load("bilinear", "repeat", 0);
    const texture_t *raw = load("bilinear", "repeat", 1);
    const vec2 probes[] = {{0.1, 0.3}, {0.37, 0.8}, {-0.93, 1.05}};
    for (int k = 0; k < 3; k++)
        assert_rgb(texture_eval(t, probes[k]), texture_eval(spelled, probes[k]), 0.0, "defaults");
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
}

Test(texture, bilinear_interpolates_linear_values)
{
    const texture_t *t = load("bilinear", "clamp", 0);
    /* x = u * 4 - 0.5 = 1.25, y = v * 2 - 0.5 = 0.5: a quarter of the way from
     * texel column 1 to 2, halfway between rows 0 and 1. */
    vec2 uv = v2(1.75 / 4.0, 0.5);
    rgb top = rgb_lerp(expected_linear(1, 0), expected_linear(2, 0), 0.25);
    rgb bottom = rgb_lerp(expected_linear(1, 1), expected_linear(2, 1), 0.25);
    assert_rgb(texture_eval(t, uv), rgb_lerp(top, bottom, 0.5), 1e-6, "bilinear");

    const texture_t *n = load("nearest", "clamp", 0);
    assert_rgb(texture_eval(n, uv), expected_linear(1, 1), 1e-6, "nearest");
    assert_rgb(texture_eval(n, v2(0.74, 0.49)), expected_linear(2, 0), 1e-6, "nearest");
}

Test(texture, wrap_modes_follow_mitsuba)
{
    const texture_t *rep = load("bilinear", "repeat", 0);
    const texture_t *mir = load("bilinear", "mirror", 0);
    const texture_t *cla = load("bilinear", "clamp", 0);
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
}

Test(texture, to_uv_and_grey_images)
{
    /* A one-channel float EXR: linear, so not decoded. */
    const float grey[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    const char *const names[] = {"Y"};
    char exr[160], err[256], xml[512];
    snprintf(exr, sizeof exr, "%s/grey.exr", dir);
    cr_assert_eq(exr_write_float(exr, 2, 2, 1, names, grey, NULL, err, sizeof err), 0, "%s", err);
    snprintf(xml, sizeof xml,
             "<texture type='bitmap'><string name='filename' value='%s'/><string name='filter_type' value='nearest'/>"
             "<transform name='to_uv'><scale x='0.5' y='0.5'/></transform></texture>",
             exr);
    const texture_t *t = texture_of(xml);
    /* uv (1.5, 0.5) -> (0.75, 0.25): texel (1, 0); grey replicated, no decoding. */
    rgb c = texture_eval(t, v2(1.5, 0.5));
    cr_assert(c.r == 0.25 && c.g == 0.25 && c.b == 0.25, "%g %g %g", c.r, c.g, c.b);
}

Test(texture, checkerboard_pattern)
{
    /* Mitsuba's defaults: color0 0.4, color1 0.2. */
    const texture_t *t = texture_of("<texture type='checkerboard'/>");
    cr_assert_float_eq(texture_eval(t, v2(0.25, 0.25)).g, 0.4, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.75, 0.25)).g, 0.2, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.25, 0.75)).g, 0.2, 0);
    cr_assert_float_eq(texture_eval(t, v2(0.75, 0.75)).g, 0.4, 0);
    cr_assert_float_eq(texture_eval(t, v2(-0.25, 0.25)).g, 0.2, 0); /* frac(-0.25) = 0.75 */
    cr_assert_float_eq(texture_mean(t).b, 0.3, 1e-15);
    t = texture_of("<texture type='checkerboard'><transform name='to_uv'><scale value='4'/></transform></texture>");
    cr_assert_float_eq(texture_eval(t, v2(0.15, 0.05)).g, 0.2, 0); /* (0.6, 0.2) in tiles */
    cr_assert_float_eq(texture_eval(t, v2(0.1, 0.05)).g, 0.4, 0);  /* (0.4, 0.2) */
}

/* Read as a scalar (a roughness, a principled weight), Mitsuba's checkerboard
 * is the other way round: its eval_1 picks color0 where the two fractional
 * parts are on different sides of 1/2 (`neq` in its checkerboard.cpp, where
 * eval has `eq`). Mitsuba's reference images of anisotropic checkerboard
 * roughness are made with it. */
Test(texture, checkerboard_scalar_is_mitsubas_eval_1)
{
    const texture_t *t = texture_of("<texture type='checkerboard'><float name='color0' value='0.05'/>"
                                    "<float name='color1' value='0.3'/></texture>");
    texture_point at = {.uv = v2(0.25, 0.25)};
    cr_assert_float_eq(texture_eval(t, at.uv).g, 0.05, 1e-15, "eval: color0 on the same side");
    cr_assert_float_eq(texture_eval_1(t, &at), 0.3, 1e-12, "eval_1: color1 on the same side");
    at.uv = v2(0.75, 0.25);
    cr_assert_float_eq(texture_eval_1(t, &at), 0.05, 1e-12, "eval_1: color0 on different sides");
    at.uv = v2(0.75, 0.75);
    cr_assert_float_eq(texture_eval_1(t, &at), 0.3, 1e-12);
}

Test(texture, bad_input)
{
    char err[512] = "", xml[512], path[160];
    /* A missing file is the reader's error; a file that is no image, the bitmap's. */
    cr_assert_null(plugin_xml_texture(&fx, "<texture type='bitmap'><string name='filename' value='/nonexistent/nope.png'/>"
                                           "</texture>", err, sizeof err));
    cr_assert(strstr(err, "not found"), "%s", err);
    snprintf(path, sizeof path, "%s/notes.png", dir);
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    fputs("not an image\n", fp);
    fclose(fp);
    snprintf(xml, sizeof xml, "<texture type='bitmap'><string name='filename' value='%s'/></texture>", path);
    cr_assert_null(plugin_xml_texture(&fx, xml, err, sizeof err));
    /* The file that is bad first, then where the scene names it (issue 28). */
    cr_assert(strncmp(err, path, strlen(path)) == 0 && strstr(err, "snippet.xml:1"), "%s", err);
    /* Option words outside Mitsuba's are refused by the reader. */
    snprintf(xml, sizeof xml, "<texture type='bitmap'><string name='filename' value='%s'/>"
             "<string name='wrap_mode' value='border'/></texture>", png);
    cr_assert_null(plugin_xml_texture(&fx, xml, err, sizeof err));
    cr_assert(strstr(err, "bad value 'border' for 'wrap_mode'"), "%s", err);
    cr_assert_null(texture_plugin_find("noise"));
}

Test(texture, rawconstant_is_its_value_as_written)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const texture_t *v = plugin_xml_texture(
        &fx, "<texture type=\"rawconstant\"><vector name=\"value\" value=\"0.5, 0.25, 1\"/></texture>", err, sizeof err);
    cr_assert_not_null(v, "%s", err);
    const texture_t *f =
        plugin_xml_texture(&fx, "<texture type=\"rawconstant\"><float name=\"value\" value=\"0.7\"/></texture>", err,
                           sizeof err);
    cr_assert_not_null(f, "%s", err);
    for (double u = 0.05; u < 3; u += 0.7) {
        rgb a = texture_eval(v, v2(u, 1 - u)), b = texture_eval(f, v2(u, u));
        cr_assert(a.r == 0.5 && a.g == 0.25 && a.b == 1.0, "a normal map's flat value, not sRGB-decoded");
        cr_assert(b.r == 0.7 && b.g == 0.7 && b.b == 0.7);
    }
    cr_assert_null(plugin_xml_texture(&fx, "<texture type=\"rawconstant\"/>", err, sizeof err));
    cr_assert_not_null(strstr(err, "needs the parameter 'value'"), "%s", err);
    plugin_xml_close(&fx);
}
