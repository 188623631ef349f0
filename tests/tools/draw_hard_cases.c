/* Draws every named hard case of tests/support/synth_scene (the table in
 * synth_scene.c) so a person can look at them, as `make hard-cases` does:
 *
 *   draw_hard_cases OUTDIR [WIDTH HEIGHT]
 *
 * writes OUTDIR/NAME.png for each case (600x800 unless a size is given),
 * OUTDIR/contact-sheet.png (every case, named), OUTDIR/truth-sheet.png
 * (the same with the truth drawn on: the body's exact outline in red, the
 * base and rim discs' centres, the foot row in green, and each part's box
 * and name in blue) and OUTDIR/recon-sheet.png (each case reconstructed as
 * `celadon reconstruct --force` does, its overlay, labelled with the quality
 * gate's verdict or the refusal). */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../support/synth_scene.h"
#include "../support/synth_vessel.h"
#include "celadon/overlay.h"
#include "celadon/reconstruct.h"

enum { COLUMNS = 6, THUMB_W = 210, LABEL_H = 30, MARGIN = 8 };

/* A box-filtered thumbnail of img painted at (x, y), scale s (< 1). */
static void paint_thumbnail(cairo_surface_t *sheet, const image_t *img, int x, int y, double s)
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

/* The truth over a thumbnail at (x, y), scale s. */
static void draw_truth(cairo_t *cr, const synth_scene_truth *t, int width, int height, int x, int y, double s)
{
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, s, s);
    cairo_rectangle(cr, 0, 0, width, height);
    cairo_clip(cr);
    cairo_set_line_width(cr, 1.2 / s);
    if (t->vessel_count >= 1) {
        cairo_set_source_rgb(cr, 0.9, 0.1, 0.1);
        for (int side = 0; side < 2; side++) {
            int started = 0;
            for (double yy = 0.5; yy < height; yy += 1) {
                double xl, xr;
                if (!synth_scene_outline_x(t, yy, &xl, &xr)) {
                    started = 0;
                    continue;
                }
                double xx = side ? xr : xl;
                if (started)
                    cairo_line_to(cr, xx, yy);
                else
                    cairo_move_to(cr, xx, yy);
                started = 1;
            }
            cairo_stroke(cr);
        }
        vec2 centres[2] = {t->base_center, t->rim_center};
        for (int k = 0; k < 2; k++) {
            cairo_arc(cr, centres[k].x, centres[k].y, 3 / s, 0, 2 * M_PI);
            cairo_fill(cr);
        }
        if (!isnan(t->foot_y)) {
            cairo_set_source_rgb(cr, 0.1, 0.7, 0.2);
            cairo_move_to(cr, t->base_center.x - 0.6 * t->body.height_px, t->foot_y);
            cairo_line_to(cr, t->base_center.x + 0.6 * t->body.height_px, t->foot_y);
            cairo_stroke(cr);
        }
    }
    cairo_set_source_rgb(cr, 0.1, 0.3, 0.95);
    cairo_set_font_size(cr, 10 / s);
    for (int k = 0; k < t->part_count; k++) {
        const synth_part_truth *p = &t->parts[k];
        if (p->row0 < 0)
            continue;
        cairo_rectangle(cr, p->col0, p->row0, p->col1 + 1 - p->col0, p->row1 + 1 - p->row0);
        cairo_stroke(cr);
        cairo_move_to(cr, p->col0 + 2 / s, p->row0 + 11 / s);
        cairo_show_text(cr, synth_part_name(p->kind));
    }
    cairo_restore(cr);
}

static void label(cairo_t *cr, const char *text, int x, int y)
{
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_font_size(cr, 12);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, text);
}

/* The photo at path reconstructed with --force: its overlay as an image
 * (the photo itself when refused), and the verdict in `verdict`. */
static int reconstruct_overlay(const char *path, image_t *out, char *verdict, size_t len)
{
    reconstruct_options opt = reconstruct_options_default();
    opt.force = 1;
    reconstruction r;
    char err[400];
    if (reconstruct_photo(path, &opt, &r, err, sizeof err) != 0) {
        snprintf(verdict, len, "refused: %s", err);
        reconstruction_free(&r);
        return image_read(path, out, err, sizeof err);
    }
    snprintf(verdict, len, "%s", r.quality.passed ? "passed" : r.quality.failed);
    uint8_t *rgb = overlay_render(&r.photo, &r.extract, &r.curve);
    int rc = -1;
    if (rgb) {
        *out = image_alloc(r.photo.width, r.photo.height, 3);
        for (size_t i = 0; i < (size_t)r.photo.width * r.photo.height * 3; i++)
            out->data[i] = rgb[i] / 255.0f;
        free(rgb);
        rc = 0;
    }
    reconstruction_free(&r);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 2 && argc != 4) {
        fprintf(stderr, "usage: draw_hard_cases OUTDIR [WIDTH HEIGHT]\n");
        return 2;
    }
    int W = argc == 4 ? atoi(argv[2]) : 600, H = argc == 4 ? atoi(argv[3]) : 800;
    if (W < 32 || H < 32 || W > 8000 || H > 8000) {
        fprintf(stderr, "draw_hard_cases: size %sx%s: each side must be 32 to 8000 px\n", argv[2], argv[3]);
        return 2;
    }
    int n = synth_scene_case_count(), rows = (n + COLUMNS - 1) / COLUMNS;
    double s = (double)THUMB_W / W;
    int cell_w = THUMB_W + MARGIN, cell_h = (int)(H * s) + LABEL_H;
    enum { SHEETS = 3 };
    cairo_surface_t *sheets[SHEETS];
    cairo_t *cr[SHEETS];
    for (int k = 0; k < SHEETS; k++) {
        sheets[k] = cairo_image_surface_create(CAIRO_FORMAT_RGB24, COLUMNS * cell_w + MARGIN, rows * cell_h + MARGIN);
        cr[k] = cairo_create(sheets[k]);
        cairo_set_source_rgb(cr[k], 1, 1, 1);
        cairo_paint(cr[k]);
    }
    int rc = 0;
    for (int i = 0; i < n && rc == 0; i++) {
        const char *name = synth_scene_case_name(i);
        synth_scene_params p;
        synth_scene_truth t;
        image_t img;
        char path[4096], err[256];
        if (synth_scene_case(name, W, H, &p) || synth_scene_draw(&p, &img, NULL, &t)) {
            fprintf(stderr, "draw_hard_cases: %s: cannot draw\n", name);
            rc = 1;
            break;
        }
        snprintf(path, sizeof path, "%s/%s.png", argv[1], name);
        if (synth_write(path, &img, 8, err, sizeof err)) {
            fprintf(stderr, "draw_hard_cases: %s: %s\n", path, err);
            rc = 1;
        }
        int x = MARGIN + (i % COLUMNS) * cell_w, y = MARGIN + (i / COLUMNS) * cell_h;
        for (int k = 0; k < 2; k++) {
            paint_thumbnail(sheets[k], &img, x, y, s);
            label(cr[k], name, x, y + (int)(H * s) + 16);
        }
        draw_truth(cr[1], &t, W, H, x, y, s);
        image_t ov;
        char verdict[512];
        if (rc == 0 && reconstruct_overlay(path, &ov, verdict, sizeof verdict) == 0) {
            paint_thumbnail(sheets[2], &ov, x, y, s);
            label(cr[2], name, x, y + (int)(H * s) + 13);
            if (strlen(verdict) > 44) /* the cell's width */
                strcpy(verdict + 41, "...");
            cairo_set_font_size(cr[2], 9);
            cairo_move_to(cr[2], x, y + (int)(H * s) + 25);
            cairo_show_text(cr[2], verdict);
            image_free(&ov);
        }
        printf("%-22s %s\n", name, synth_scene_case_description(i));
        image_free(&img);
    }
    const char *names[SHEETS] = {"contact-sheet.png", "truth-sheet.png", "recon-sheet.png"};
    for (int k = 0; k < SHEETS; k++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", argv[1], names[k]);
        if (rc == 0 && cairo_surface_write_to_png(sheets[k], path) != CAIRO_STATUS_SUCCESS) {
            fprintf(stderr, "draw_hard_cases: %s: cannot write\n", path);
            rc = 1;
        }
        cairo_destroy(cr[k]);
        cairo_surface_destroy(sheets[k]);
    }
    return rc;
}
