/* See recon_sheet.h. */
#include "recon_sheet.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "celadon/overlay.h"

void sheet_paint_thumbnail(cairo_surface_t *sheet, const image_t *img, int x, int y, double s)
{
    int tw = (int)(img->width * s), th = (int)(img->height * s), stride = cairo_image_surface_get_stride(sheet);
    int sw = cairo_image_surface_get_width(sheet), sh = cairo_image_surface_get_height(sheet);
    unsigned char *data = cairo_image_surface_get_data(sheet);
    cairo_surface_flush(sheet);
    for (int j = 0; j < th && y + j < sh; j++)
        for (int i = 0; i < tw && x + i < sw; i++) {
            int i0 = (int)(i / s), i1 = (int)((i + 1) / s), j0 = (int)(j / s), j1 = (int)((j + 1) / s);
            double sum[3] = {0}, n = 0;
            for (int b = j0; b < j1 && b < img->height; b++)
                for (int a = i0; a < i1 && a < img->width; a++, n++) {
                    const float *px = img->data + ((size_t)b * img->width + a) * img->channels;
                    for (int q = 0; q < 3; q++)
                        sum[q] += px[img->channels == 1 ? 0 : q];
                }
            uint32_t px = 0xff000000u;
            for (int q = 0; q < 3; q++)
                px |= (uint32_t)lround(255 * fmin(1, sum[q] / fmax(1, n))) << (16 - 8 * q);
            *(uint32_t *)(data + (size_t)(y + j) * stride + 4 * (x + i)) = px;
        }
    cairo_surface_mark_dirty(sheet);
}

int sheet_reconstruct_forced(const char *path, reconstruct_segmenter s, reconstruction *r, char *err, size_t len)
{
    reconstruct_options opt = reconstruct_options_default();
    opt.segmenter = s;
    opt.force = 1;
    return reconstruct_photo(path, &opt, r, err, len);
}

int sheet_reconstruct_overlay(const char *path, int without_photo, reconstruction *r, image_t *out, char *verdict,
                              size_t len)
{
    char err[400];
    if (sheet_reconstruct_forced(path, RECONSTRUCT_SEGMENTER_AUTO, r, err, sizeof err) != 0) {
        snprintf(verdict, len, "refused: %s", err);
        if (!without_photo)
            return image_read(path, out, err, sizeof err);
        image_t probe;
        if (image_read(path, &probe, err, sizeof err) != 0)
            return -1;
        *out = image_alloc(probe.width, probe.height, 3);
        image_free(&probe);
        for (size_t i = 0; out->data && i < (size_t)out->width * out->height * 3; i++)
            out->data[i] = 1;
        return out->data ? 0 : -1;
    }
    snprintf(verdict, len, "%s", r->quality.passed ? "passed" : r->quality.failed);
    const image_t *under = &r->photo;
    image_t seg = {0};
    if (without_photo) {
        seg = image_alloc(r->photo.width, r->photo.height, 3);
        if (!seg.data)
            return -1;
        for (size_t i = 0; i < (size_t)seg.width * seg.height; i++)
            for (int k = 0; k < 3; k++)
                seg.data[3 * i + k] = r->extract.mask[i] ? 0.55f : 1.0f;
        under = &seg;
    }
    uint8_t *rgb = overlay_render(under, &r->extract, &r->curve);
    image_free(&seg);
    if (!rgb)
        return -1;
    *out = image_alloc(r->photo.width, r->photo.height, 3);
    for (size_t i = 0; out->data && i < (size_t)r->photo.width * r->photo.height * 3; i++)
        out->data[i] = rgb[i] / 255.0f;
    free(rgb);
    return out->data ? 0 : -1;
}
