/* RGBE encoding. See rgbe.h. */
#include "museum/rgbe.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rgbe_from_float(const float c[3], uint8_t e[4])
{
    float m = fmaxf(fmaxf(c[0], c[1]), c[2]);
    if (!(m > 1e-32f)) {
        memset(e, 0, 4);
        return;
    }
    int ex;
    float f = frexpf(m, &ex) * 256.0f / m; /* m = f' 2^ex, f' in [0.5, 1) */
    for (int k = 0; k < 3; k++)
        e[k] = (uint8_t)fminf(255.0f, fmaxf(0.0f, c[k] * f));
    e[3] = (uint8_t)(ex + 128);
}

void rgbe_to_float(const uint8_t e[4], float c[3])
{
    float f = e[3] ? ldexpf(1.0f, e[3] - (128 + 8)) : 0.0f;
    for (int k = 0; k < 3; k++)
        c[k] = e[3] ? (e[k] + 0.5f) * f : 0.0f;
}

int rgbe_encode(const float *rgb, int width, int height, uint8_t **out, size_t *len)
{
    char head[128];
    int hl = snprintf(head, sizeof head, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", height, width);
    /* Per scanline: 4 header bytes, per component its bytes and one count per 128. */
    size_t line = 4 + 4 * ((size_t)width + ((size_t)width + 127) / 128);
    uint8_t *buf = malloc((size_t)hl + line * (size_t)height), *px = malloc(4 * (size_t)width);
    if (!buf || !px) {
        free(buf), free(px);
        return -1;
    }
    memcpy(buf, head, (size_t)hl);
    size_t n = (size_t)hl;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++)
            rgbe_from_float(rgb + 3 * ((size_t)y * width + x), px + 4 * x);
        buf[n++] = 2, buf[n++] = 2, buf[n++] = (uint8_t)(width >> 8), buf[n++] = (uint8_t)(width & 255);
        for (int k = 0; k < 4; k++)
            for (int x = 0; x < width; x += 128) {
                int run = width - x < 128 ? width - x : 128;
                buf[n++] = (uint8_t)run;
                for (int i = 0; i < run; i++)
                    buf[n++] = px[4 * (x + i) + k];
            }
    }
    free(px);
    *out = buf;
    *len = n;
    return 0;
}
