/* The PNG backend against OpenImageIO, the independent decoder it stands in
 * for: every PNG it reads gives OpenImageIO's floats, sizes and bit depth,
 * every PNG it writes reads back the same in OpenImageIO with the same
 * metadata, and what it declines (alpha, palettes, EXIF) still reads
 * through celadon/image.h as OpenImageIO reads it. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/image.h"
#include "image/oiio_backend.h"
#include "image/png_backend.h"
#include "support/scratch_dir.h"

static char dir[256];

static void open_dir(void) { scratch_dir_make(dir, sizeof dir, "png"); }
static void close_dir(void) { scratch_dir_remove(dir); }

TestSuite(image_png, .init = open_dir, .fini = close_dir);

static const image_backend *oiio(void)
{
    char err[256];
    const image_backend *b = oiio_backend_get(err, sizeof err);
    cr_assert_not_null(b, "%s", err);
    return b;
}

/* Samples of a smooth ramp with noise: every code of the depth occurs. */
static void *samples(int w, int h, int ch, int bits, uint32_t seed)
{
    size_t n = (size_t)w * h * ch;
    void *px = malloc(n * (size_t)(bits / 8));
    cr_assert_not_null(px);
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        uint32_t v = (uint32_t)(i * 977u) + (seed >> 20);
        if (bits == 16)
            ((uint16_t *)px)[i] = (uint16_t)v;
        else
            ((uint8_t *)px)[i] = (uint8_t)v;
    }
    return px;
}

static void expect_same(const image_t *a, const image_t *b, const char *what)
{
    cr_assert(a->width == b->width && a->height == b->height && a->channels == b->channels, "%s: sizes", what);
    cr_expect_eq(a->bits, b->bits, "%s: %d bits against %d", what, a->bits, b->bits);
    cr_expect_eq(a->has_alpha, b->has_alpha, "%s: alpha", what);
    size_t n = (size_t)a->width * a->height * a->channels, differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += a->data[i] != b->data[i]; /* the very floats */
    cr_expect_eq(differ, 0, "%s: %zu of %zu samples differ", what, differ, n);
}

static image_t read_with(const image_backend *b, const char *path)
{
    image_t img;
    char err[256];
    int rc = b->read(path, &img, err, sizeof err);
    cr_assert_eq(rc, 0, "%s: %s", path, rc < 0 ? err : "declined");
    return img;
}

/* Gray and RGB, 8 and 16 bits, odd sizes: written by each backend, read by
 * each; the PNG backend's reading is OpenImageIO's to the bit. */
Test(image_png, reads_and_writes_what_openimageio_does)
{
    static const struct {
        int w, h, ch, bits;
    } cases[] = {{37, 23, 1, 8}, {37, 23, 3, 8}, {19, 41, 1, 16}, {19, 41, 3, 16}, {300, 2, 3, 8}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        int w = cases[k].w, h = cases[k].h, ch = cases[k].ch, bits = cases[k].bits;
        void *px = samples(w, h, ch, bits, (uint32_t)k);
        image_sample_type type = bits == 16 ? IMAGE_U16 : IMAGE_U8;
        const image_backend *writers[] = {&png_backend, oiio()};
        for (int wr = 0; wr < 2; wr++) {
            char path[400], err[256];
            snprintf(path, sizeof path, "%s/case%zu-%d.png", dir, k, wr);
            cr_assert_eq(writers[wr]->write(path, path, w, h, ch, type, px, NULL, 0, err, sizeof err), 0, "%s", err);
            image_t mine = read_with(&png_backend, path), theirs = read_with(oiio(), path);
            char what[64];
            snprintf(what, sizeof what, "case %zu written by %s", k, wr ? "OpenImageIO" : "libpng");
            expect_same(&mine, &theirs, what);
            cr_expect_eq(mine.bits, bits, "%s", what);
            /* and the samples written are the samples read */
            size_t n = (size_t)w * h * ch, wrong = 0;
            for (size_t i = 0; i < n; i++) {
                double v = bits == 16 ? ((uint16_t *)px)[i] / 65535.0 : ((uint8_t *)px)[i] / 255.0;
                wrong += fabs(mine.data[i] - v) > 1e-7;
            }
            cr_expect_eq(wrong, 0, "%s: %zu samples are not those written", what, wrong);
            int pw, ph, pch;
            cr_expect_eq(png_backend.probe(path, &pw, &ph, &pch, err, sizeof err), 0);
            cr_expect(pw == w && ph == h && pch == ch, "%s: probe says %dx%dx%d", what, pw, ph, pch);
            image_free(&mine), image_free(&theirs);
        }
        free(px);
    }
}

/* A PNG written by libpng itself with the given colour type and
 * interlacing, from bytes. */
static void write_raw_png(const char *path, int w, int h, int color, int interlace, const uint8_t *bytes, int ch)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    cr_assert(png && info);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, color, interlace, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        png_color palette[256];
        for (int i = 0; i < 256; i++)
            palette[i] = (png_color){(png_byte)i, (png_byte)(255 - i), (png_byte)(i * 7)};
        png_set_PLTE(png, info, palette, 256);
    }
    png_write_info(png, info);
    png_bytep *rows = malloc((size_t)h * sizeof *rows);
    cr_assert_not_null(rows);
    for (int y = 0; y < h; y++)
        rows[y] = (png_bytep)bytes + (size_t)y * w * ch;
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(rows);
    fclose(f);
}

/* Adam7 interlacing is the PNG backend's; alpha and palettes are left to
 * OpenImageIO (premultiplied alpha, expanded palettes) and read through
 * celadon/image.h as OpenImageIO reads them. */
Test(image_png, interlaced_alpha_and_palette_files_read_as_openimageio_reads_them)
{
    enum { W = 29, H = 17 };
    uint8_t *px = samples(W, H, 4, 8, 7);
    static const struct {
        int color, ch, interlace, declined;
    } cases[] = {{PNG_COLOR_TYPE_RGB, 3, PNG_INTERLACE_ADAM7, 0},
                 {PNG_COLOR_TYPE_RGB_ALPHA, 4, PNG_INTERLACE_NONE, 1},
                 {PNG_COLOR_TYPE_GRAY_ALPHA, 2, PNG_INTERLACE_NONE, 1},
                 {PNG_COLOR_TYPE_PALETTE, 1, PNG_INTERLACE_NONE, 1}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        char path[400], err[256];
        snprintf(path, sizeof path, "%s/kind%zu.png", dir, k);
        write_raw_png(path, W, H, cases[k].color, cases[k].interlace, px, cases[k].ch);
        image_t mine;
        int rc = png_backend.read(path, &mine, err, sizeof err);
        cr_expect_eq(rc, cases[k].declined ? IMAGE_BACKEND_DECLINED : 0, "kind %zu: %d (%s)", k, rc, err);
        if (rc == 0)
            image_free(&mine);
        image_t through, theirs = read_with(oiio(), path);
        cr_assert_eq(image_read(path, &through, err, sizeof err), 0, "%s", err);
        char what[32];
        snprintf(what, sizeof what, "kind %zu", k);
        expect_same(&through, &theirs, what);
        image_free(&through), image_free(&theirs);
    }
    free(px);
}

/* A PNG cut short, or with a damaged image chunk: one line that says so,
 * and nothing on stderr from libpng. */
Test(image_png, a_cut_or_damaged_file_says_which, .init = cr_redirect_stderr)
{
    enum { W = 64, H = 64 };
    uint8_t *px = samples(W, H, 3, 8, 3); /* noise: a long image chunk */
    char path[400], err[256];
    snprintf(path, sizeof path, "%s/whole.png", dir);
    cr_assert_eq(png_backend.write(path, path, W, H, 3, IMAGE_U8, px, NULL, 0, err, sizeof err), 0, "%s", err);
    free(px);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    static uint8_t bytes[1 << 16];
    size_t len = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    cr_assert(len > 4096 && len < sizeof bytes);

    snprintf(path, sizeof path, "%s/cut.png", dir);
    f = fopen(path, "wb");
    fwrite(bytes, 1, len / 2, f);
    fclose(f);
    image_t img;
    cr_expect_eq(image_read(path, &img, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "truncated PNG"), "%s", err);
    cr_expect_null(img.data);

    bytes[len / 2] ^= 0x55; /* inside the image data: its checksum fails */
    snprintf(path, sizeof path, "%s/damaged.png", dir);
    f = fopen(path, "wb");
    fwrite(bytes, 1, len, f);
    fclose(f);
    cr_expect_eq(image_read(path, &img, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "damaged PNG"), "%s", err);
    fflush(stderr);
    cr_expect_stderr_eq_str("");
}
