/* Label plates with cairo's toy text API (word wrap by measured extents).
 * See label.h. */
#include "museum/label.h"

#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MARGIN 0.07        /* of the plate's width */
#define TITLE_SIZE 0.075   /* font sizes, of the plate's width */
#define BODY_SIZE 0.05
#define LINE_SPACING 1.3

typedef struct {
    uint8_t *data;
    size_t len, cap;
    int failed;
} byte_sink;

static cairo_status_t sink_write(void *closure, const unsigned char *data, unsigned int length)
{
    byte_sink *s = closure;
    if (s->len + length > s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 65536;
        while (cap < s->len + length)
            cap *= 2;
        uint8_t *grown = realloc(s->data, cap);
        if (!grown) {
            s->failed = 1;
            return CAIRO_STATUS_WRITE_ERROR;
        }
        s->data = grown;
        s->cap = cap;
    }
    memcpy(s->data + s->len, data, length);
    s->len += length;
    return CAIRO_STATUS_SUCCESS;
}

/* Length of the longest prefix of text (ending at a space or the end) that
 * fits in width; at least one word, cut to fit when a single word is wider. */
static size_t fitting_prefix(cairo_t *cr, const char *text, double width)
{
    size_t best = 0, n = strlen(text);
    char *buf = malloc(n + 1);
    if (!buf)
        return n;
    for (size_t i = 1; i <= n; i++) {
        if (i < n && text[i] != ' ')
            continue;
        memcpy(buf, text, i);
        buf[i] = 0;
        cairo_text_extents_t ext;
        cairo_text_extents(cr, buf, &ext);
        if (ext.x_advance > width && best > 0)
            break;
        best = i;
        if (ext.x_advance > width)
            break;
    }
    free(buf);
    return best;
}

/* Draws text wrapped into lines from *y down, at most until y_max; the last
 * line that fits ends with an ellipsis when text remains. */
static void draw_wrapped(cairo_t *cr, const char *text, double x, double *y, double width, double size, double y_max)
{
    cairo_set_font_size(cr, size);
    char line[1024];
    while (*text) {
        while (*text == ' ')
            text++;
        if (!*text || *y + size > y_max)
            break;
        size_t n = fitting_prefix(cr, text, width);
        int last = *y + 2 * size * LINE_SPACING > y_max && text[n];
        snprintf(line, sizeof line, "%.*s%s", (int)(n < 1000 ? n : 1000), text, last ? " ..." : "");
        cairo_move_to(cr, x, *y + size);
        cairo_show_text(cr, line);
        *y += size * LINE_SPACING;
        text += n;
        if (last)
            break;
    }
}

int label_render_png(const label_text *t, int width, int height, uint8_t **png, size_t *len)
{
    *png = NULL;
    *len = 0;
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t *cr = cairo_create(surf);
    if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
        cairo_destroy(cr);
        cairo_surface_destroy(surf);
        return -1;
    }
    cairo_set_source_rgb(cr, 0.94, 0.92, 0.87); /* card */
    cairo_paint(cr);
    double m = MARGIN * width, w = width - 2 * m, y = m, y_max = height - m;
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    draw_wrapped(cr, t->title, m, &y, w, TITLE_SIZE * width, y_max);
    y += 0.3 * BODY_SIZE * width;
    cairo_set_source_rgb(cr, 0.35, 0.45, 0.38); /* a celadon rule under the title */
    cairo_rectangle(cr, m, y, w, 0.006 * width);
    cairo_fill(cr);
    y += 0.5 * BODY_SIZE * width;
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    char line[128];
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_ITALIC, CAIRO_FONT_WEIGHT_NORMAL);
    if (t->date)
        draw_wrapped(cr, t->date, m, &y, w, BODY_SIZE * width, y_max);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    snprintf(line, sizeof line, "Height %.1f cm", t->height_cm);
    draw_wrapped(cr, line, m, &y, w, BODY_SIZE * width, y_max);
    if (t->description) {
        y += 0.4 * BODY_SIZE * width;
        draw_wrapped(cr, t->description, m, &y, w, BODY_SIZE * width, y_max);
    }
    cairo_destroy(cr);
    byte_sink sink = {0};
    cairo_status_t st = cairo_surface_write_to_png_stream(surf, sink_write, &sink);
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS || sink.failed) {
        free(sink.data);
        return -1;
    }
    *png = sink.data;
    *len = sink.len;
    return 0;
}
