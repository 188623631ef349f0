/* image_read's pixel values: every 8-bit code of a gray or RGB file
 * (decoded as bytes and scaled by the shim) and 16-bit codes (converted by
 * OpenImageIO) come back as the file's encoded value over the code range.
 * (Files with alpha keep OpenImageIO's float path and its premultiplication.)
 * And the EXIF orientation of a file is applied to its pixels. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/image.h"

static void temp_png(char *dir, char *path, size_t len)
{
    strcpy(dir, "/tmp/celadon-imgread-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, len, "%s/p.png", dir);
}

Test(image_read, every_8bit_code_is_code_over_255)
{
    enum { W = 64, H = 4 }; /* W*H = 256 pixels: pixel i holds code i in channel 0 */
    char dir[64], png[96], err[256];
    temp_png(dir, png, sizeof png);
    for (int c = 1; c <= 3; c += 2) {
        uint8_t px[W * H * 3];
        for (int i = 0; i < W * H; i++)
            for (int k = 0; k < c; k++)
                px[i * c + k] = (uint8_t)(i + 85 * k);
        cr_assert_eq(image_write_u8(png, W, H, c, px, err, sizeof err), 0, "%s", err);
        image_t img;
        cr_assert_eq(image_read(png, &img, err, sizeof err), 0, "%s", err);
        cr_assert_eq(img.width, W);
        cr_assert_eq(img.height, H);
        cr_assert_eq(img.channels, c);
        cr_assert_eq(img.bits, 8);
        cr_assert_eq(img.has_alpha, 0);
        for (int i = 0; i < W * H * c; i++) {
            cr_assert_eq(img.data[i], px[i] * (1.0f / 255), "c %d value %d: %.9g", c, i, img.data[i]);
            cr_assert_float_eq(img.data[i], px[i] / 255.0, 1e-7);
        }
        image_free(&img);
    }
    unlink(png);
    rmdir(dir);
}

Test(image_read, sixteen_bit_codes)
{
    enum { W = 32, H = 8 };
    char dir[64], png[96], err[256];
    temp_png(dir, png, sizeof png);
    uint16_t px[W * H * 3];
    for (int i = 0; i < W * H * 3; i++)
        px[i] = (uint16_t)(i * 257 + 13 * (i % 7));
    cr_assert_eq(image_write_u16(png, W, H, 3, px, err, sizeof err), 0, "%s", err);
    image_t img;
    cr_assert_eq(image_read(png, &img, err, sizeof err), 0, "%s", err);
    cr_assert_eq(img.bits, 16);
    for (int i = 0; i < W * H * 3; i++)
        cr_assert_float_eq(img.data[i], px[i] / 65535.0, 1e-7, "value %d", i);
    image_free(&img);
    unlink(png);
    rmdir(dir);
}

/* A minimal little-endian baseline TIFF (8-bit gray, one uncompressed strip)
 * with the given Orientation tag, written byte by byte so that the test
 * controls the EXIF orientation that image_read must apply. */
static void write_oriented_tiff(const char *path, int w, int h, const uint8_t *px, int orientation)
{
    enum { NTAGS = 10 };
    uint8_t buf[8 + 2 + NTAGS * 12 + 4 + 256];
    size_t n = 0, data = 8 + 2 + NTAGS * 12 + 4;
    cr_assert_leq((size_t)w * h, 256);
#define PUT16(v) (buf[n++] = (uint8_t)((v) & 0xff), buf[n++] = (uint8_t)(((v) >> 8) & 0xff))
#define PUT32(v) (PUT16((v) & 0xffff), PUT16(((v) >> 16) & 0xffff))
    buf[n++] = 'I', buf[n++] = 'I';
    PUT16(42);
    PUT32(8); /* the IFD right after the header */
    PUT16(NTAGS);
    /* tag, type (3 SHORT, 4 LONG), count 1, value; in increasing tag order */
    const unsigned tags[NTAGS][3] = {
        {256, 4, (unsigned)w},           /* ImageWidth */
        {257, 4, (unsigned)h},           /* ImageLength */
        {258, 3, 8},                     /* BitsPerSample */
        {259, 3, 1},                     /* Compression: none */
        {262, 3, 1},                     /* PhotometricInterpretation: black is zero */
        {273, 4, (unsigned)data},        /* StripOffsets */
        {274, 3, (unsigned)orientation}, /* Orientation */
        {277, 3, 1},                     /* SamplesPerPixel */
        {278, 4, (unsigned)h},           /* RowsPerStrip */
        {279, 4, (unsigned)(w * h)},     /* StripByteCounts */
    };
    for (int t = 0; t < NTAGS; t++) {
        PUT16(tags[t][0]);
        PUT16(tags[t][1]);
        PUT32(1u);
        if (tags[t][1] == 3) {
            PUT16(tags[t][2]);
            PUT16(0);
        } else {
            PUT32(tags[t][2]);
        }
    }
    PUT32(0); /* no next IFD */
#undef PUT16
#undef PUT32
    cr_assert_eq(n, data);
    memcpy(buf + n, px, (size_t)w * h);
    n += (size_t)w * h;
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(buf, 1, n, f), n);
    fclose(f);
}

/* EXIF orientation is applied (OpenImageIO reports it but does not rotate):
 * 3 is a half turn; 6 means the stored rows are the displayed image's
 * columns from the right (stored row r, column c is displayed at x = H-1-r,
 * y = c); 1 leaves the pixels as stored. */
Test(image_read, exif_orientation_is_applied)
{
    enum { W = 5, H = 3 };
    uint8_t px[W * H];
    for (int i = 0; i < W * H; i++)
        px[i] = (uint8_t)(10 * i + 5);
    char dir[64], path[96], err[256];
    strcpy(dir, "/tmp/celadon-imgread-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/o.tif", dir);
    const int orientations[] = {1, 3, 6};
    for (int k = 0; k < 3; k++) {
        int o = orientations[k];
        write_oriented_tiff(path, W, H, px, o);
        image_t img;
        cr_assert_eq(image_read(path, &img, err, sizeof err), 0, "orientation %d: %s", o, err);
        cr_assert_eq(img.channels, 1);
        cr_assert_eq(img.width, o == 6 ? H : W, "orientation %d", o);
        cr_assert_eq(img.height, o == 6 ? W : H, "orientation %d", o);
        for (int r = 0; r < H; r++)
            for (int c = 0; c < W; c++) {
                int x = o == 1 ? c : (o == 3 ? W - 1 - c : H - 1 - r);
                int y = o == 1 ? r : (o == 3 ? H - 1 - r : c);
                cr_assert_eq(img.data[y * img.width + x], px[r * W + c] * (1.0f / 255),
                             "orientation %d: stored (%d, %d) not at (%d, %d)", o, c, r, x, y);
            }
        image_free(&img);
    }
    unlink(path);
    rmdir(dir);
}
