/* Mitsuba .vol grid files for tests (vol_file.h). */
#include "vol_file.h"

#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t vol_file_bytes(unsigned char *buf, int nx, int ny, int nz, int channels, const float *values)
{
    memcpy(buf, "VOL\3", 4);
    int32_t head[5] = {1, nx, ny, nz, channels};
    memcpy(buf + 4, head, sizeof head);
    float box[6] = {0, 0, 0, 1, 1, 1};
    memcpy(buf + 24, box, sizeof box);
    size_t n = (size_t)nx * (size_t)ny * (size_t)nz * (size_t)channels;
    memcpy(buf + 48, values, n * sizeof *values);
    return 48 + n * sizeof *values;
}

void vol_file_write(const char *path, int nx, int ny, int nz, int channels, const float *values)
{
    size_t n = (size_t)nx * (size_t)ny * (size_t)nz * (size_t)channels;
    unsigned char *buf = malloc(48 + 4 * n);
    cr_assert_not_null(buf);
    size_t len = vol_file_bytes(buf, nx, ny, nz, channels, values);
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp, "cannot write %s", path);
    cr_assert_eq(fwrite(buf, 1, len, fp), len);
    cr_assert_eq(fclose(fp), 0);
    free(buf);
}
