/* image_read's pixel values: every 8-bit code of a gray or RGB file
 * (decoded as bytes and scaled by the shim) and 16-bit codes (converted by
 * OpenImageIO) come back as the file's encoded value over the code range.
 * (Files with alpha keep OpenImageIO's float path and its premultiplication.) */
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
