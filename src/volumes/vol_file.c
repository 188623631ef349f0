/* Mitsuba's binary .vol grid file: "VOL", version byte 3, then
 * little-endian int32 encoding (1: float32, the only one read here), int32
 * xres, yres, zres, int32 channels (1 or 3), six float32 of a bounding box
 * (min, max) and the float32 values, x fastest, then y, then z. Read by the
 * `gridvolume` volume and the `sdfgrid` shape. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "volumes/volumes.h"

enum { HEADER_BYTES = 48 };

static int32_t le32(const unsigned char *b)
{
    return (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24);
}

static float lef32(const unsigned char *b)
{
    uint32_t u = (uint32_t)le32(b);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The grid of the .vol file in buf (len bytes): 0, or -1 with the problem in why. */
static int parse_vol(const unsigned char *buf, size_t len, vol_grid *g, char *why, size_t whylen)
{
    if (len < HEADER_BYTES || memcmp(buf, "VOL", 3) != 0 || buf[3] != 3) {
        snprintf(why, whylen, "not a Mitsuba .vol file of version 3");
        return -1;
    }
    if (le32(buf + 4) != 1) {
        snprintf(why, whylen, "encoding %d is not float32 (1)", le32(buf + 4));
        return -1;
    }
    int32_t nx = le32(buf + 8), ny = le32(buf + 12), nz = le32(buf + 16), ch = le32(buf + 20);
    if (nx < 1 || ny < 1 || nz < 1 || (ch != 1 && ch != 3)) {
        snprintf(why, whylen, "bad size %dx%dx%d with %d channels (1 or 3)", nx, ny, nz, ch);
        return -1;
    }
    size_t count = (size_t)nx * (size_t)ny * (size_t)nz * (size_t)ch;
    if (count / (size_t)ch / (size_t)nz / (size_t)ny != (size_t)nx || (len - HEADER_BYTES) / 4 != count ||
        (len - HEADER_BYTES) % 4 != 0) {
        snprintf(why, whylen, "holds %zu bytes of values, not 4 x %dx%dx%d x %d", len - HEADER_BYTES, nx, ny, nz, ch);
        return -1;
    }
    g->lo = v3(lef32(buf + 24), lef32(buf + 28), lef32(buf + 32));
    g->hi = v3(lef32(buf + 36), lef32(buf + 40), lef32(buf + 44));
    if (!(g->values = malloc(count * sizeof *g->values))) {
        snprintf(why, whylen, "out of memory");
        return -1;
    }
    g->nx = nx, g->ny = ny, g->nz = nz, g->channels = ch;
    for (size_t i = 0; i < count; i++) {
        float f = lef32(buf + HEADER_BYTES + 4 * i);
        if (!isfinite(f)) {
            snprintf(why, whylen, "value %zu is %g: values must be finite", i, (double)f);
            vol_grid_free(g);
            return -1;
        }
        g->values[i] = f;
    }
    return 0;
}

int vol_grid_read(const char *path, vol_grid *g, char *why, size_t whylen)
{
    memset(g, 0, sizeof *g);
    char *buf = NULL;
    size_t len = 0;
    int rc = input_read_all(path, INPUT_MAX_DATA_BYTES, &buf, &len, why, whylen);
    if (rc == 0)
        rc = parse_vol((const unsigned char *)buf, len, g, why, whylen);
    free(buf);
    return rc;
}

void vol_grid_free(vol_grid *g)
{
    free(g->values);
    memset(g, 0, sizeof *g);
}
