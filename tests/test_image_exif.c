/* The EXIF 35 mm equivalent focal length: read from a JPEG that has it
 * (tests/data/exif_focal35_50mm.jpg, written by oiiotool with
 * Exif:FocalLengthIn35mmFilm = 50), 0 for one without it and for a file
 * that is not there. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "celadon/image.h"

Test(image_exif, focal_length_35mm)
{
    cr_expect_eq(image_exif_focal_35mm("tests/data/exif_focal35_50mm.jpg"), 50.0);
    char path[] = "/tmp/celadon-exif-XXXXXX.jpg", err[256];
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    uint8_t px[16 * 16 * 3] = {0};
    cr_assert_eq(image_write_u8(path, 16, 16, 3, px, err, sizeof err), 0, "%s", err);
    cr_expect_eq(image_exif_focal_35mm(path), 0.0, "a JPEG written without EXIF");
    remove(path);
    cr_expect_eq(image_exif_focal_35mm("/nonexistent/photo.jpg"), 0.0);
}
