/* Label plates with cairo's toy text API: lines broken by measured
 * extents, then drawn. See label.h. */
#include "museum/label.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MARGIN 0.07        /* of the plate's width */
#define TITLE_SIZE 0.075   /* font sizes, of the plate's width */
#define BODY_SIZE 0.05
#define LINE_SPACING 1.3
#define ELLIPSIS "\xe2\x80\xa6" /* U+2026 */

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

/* The surface as PNG bytes (malloc'd), then destroyed. Returns 0 or -1. */
static int surface_png(cairo_surface_t *surf, uint8_t **png, size_t *len)
{
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

/* A width x height RGB surface and its context, or NULL (nothing left over). */
static cairo_t *canvas(int width, int height, cairo_surface_t **surf)
{
    *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t *cr = cairo_create(*surf);
    if (cairo_status(cr) == CAIRO_STATUS_SUCCESS)
        return cr;
    cairo_destroy(cr);
    cairo_surface_destroy(*surf);
    return NULL;
}

static void set_font(cairo_t *cr, label_role role, double size)
{
    cairo_select_font_face(cr, role == LABEL_SIGN ? LABEL_SIGN_FONT : "sans-serif",
                           role == LABEL_DATE || role == LABEL_NOTE ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                           role == LABEL_TITLE || role == LABEL_SIGN ? CAIRO_FONT_WEIGHT_BOLD
                                                                     : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

/* Width of text[0..n) followed by tail. */
static double advance(cairo_t *cr, const char *text, size_t n, const char *tail)
{
    char buf[LABEL_LINE_BYTES];
    snprintf(buf, sizeof buf, "%.*s%s", (int)n, text, tail);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, buf, &ext);
    return ext.x_advance;
}

static int utf8_continuation(char c) { return ((unsigned char)c & 0xC0) == 0x80; }

/* The longest prefix of text that, followed by tail, fits in width: ending
 * before a space (or at the end) when one word at least fits, else between
 * characters (at least one). Never longer than the line buffer allows. */
static size_t fitting_prefix(cairo_t *cr, const char *text, double width, const char *tail)
{
    size_t n = strlen(text), cap = LABEL_LINE_BYTES - 8, best = 0;
    for (size_t i = 1; i <= n && i <= cap; i++) {
        if (i < n && text[i] != ' ')
            continue;
        if (advance(cr, text, i, tail) > width)
            break;
        best = i;
    }
    if (best)
        return best;
    size_t chars = 0;
    for (size_t i = 1; i <= n && i <= cap; i++) {
        if (i < n && utf8_continuation(text[i]))
            continue;
        if (chars && advance(cr, text, i, tail) > width)
            break;
        chars = i;
    }
    return chars;
}

typedef struct {
    cairo_t *cr;
    double x, y, y_max, width;
    label_line *lines;
    int n, max;
} layout_state;

/* Lays text out in at most max_lines lines of role at size from s->y; the
 * last line ends with an ellipsis when text remains. */
static void wrap(layout_state *s, const char *text, label_role role, double size, int max_lines)
{
    if (!text)
        return;
    set_font(s->cr, role, size);
    for (int k = 0; k < max_lines && s->n < s->max; k++) {
        while (*text == ' ')
            text++;
        if (!*text || s->y + size > s->y_max)
            return;
        int last = k == max_lines - 1 || s->y + size * LINE_SPACING + size > s->y_max;
        size_t n = fitting_prefix(s->cr, text, s->width, "");
        const char *rest = text + n;
        while (*rest == ' ')
            rest++;
        int cut = last && *rest;
        if (cut) {
            n = fitting_prefix(s->cr, text, s->width, ELLIPSIS);
            while (n > 0 && text[n - 1] == ' ')
                n--;
        }
        label_line *l = &s->lines[s->n++];
        snprintf(l->text, sizeof l->text, "%.*s%s", (int)n, text, cut ? ELLIPSIS : "");
        l->role = role;
        l->x = s->x;
        l->y = s->y + size;
        l->size = size;
        l->cut = cut;
        cairo_text_extents_t ext;
        cairo_text_extents(s->cr, l->text, &ext);
        l->advance = ext.x_advance;
        s->y += size * LINE_SPACING;
        text += n;
        if (cut)
            return;
    }
}

double label_text_width(int width) { return width - 2 * MARGIN * width; }

static int layout_on(cairo_t *cr, const label_text *t, int width, int height, label_line *lines, int max_lines)
{
    double m = MARGIN * width;
    layout_state s = {cr, m, m, height - m, label_text_width(width), lines, 0, max_lines};
    wrap(&s, t->title, LABEL_TITLE, TITLE_SIZE * width, LABEL_TITLE_LINES);
    s.y += 0.8 * BODY_SIZE * width; /* room for the rule under the title */
    wrap(&s, t->date, LABEL_DATE, BODY_SIZE * width, 1);
    wrap(&s, t->size, LABEL_SIZE, BODY_SIZE * width, 1);
    wrap(&s, t->note, LABEL_NOTE, BODY_SIZE * width, 2);
    s.y += 0.4 * BODY_SIZE * width;
    wrap(&s, t->description, LABEL_DESCRIPTION, BODY_SIZE * width, LABEL_MAX_LINES);
    return s.n;
}

int label_layout(const label_text *t, int width, int height, label_line *lines, int max_lines)
{
    cairo_surface_t *surf;
    cairo_t *cr = canvas(1, 1, &surf); /* only measures text */
    if (!cr)
        return -1;
    int n = layout_on(cr, t, width, height, lines, max_lines);
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return n;
}

int label_render_png(const label_text *t, int width, int height, uint8_t **png, size_t *len)
{
    *png = NULL;
    *len = 0;
    label_line lines[LABEL_MAX_LINES];
    cairo_surface_t *surf;
    cairo_t *cr = canvas(width, height, &surf);
    if (!cr)
        return -1;
    int n = layout_on(cr, t, width, height, lines, LABEL_MAX_LINES);
    cairo_set_source_rgb(cr, 0.94, 0.92, 0.87); /* card */
    cairo_paint(cr);
    int ruled = 0;
    for (int i = 0; i < n; i++) {
        const label_line *l = &lines[i];
        if (!ruled && l->role != LABEL_TITLE) { /* a celadon rule under the title */
            cairo_set_source_rgb(cr, 0.35, 0.45, 0.38);
            cairo_rectangle(cr, l->x, l->y - l->size - 0.5 * BODY_SIZE * width, label_text_width(width),
                            0.006 * width);
            cairo_fill(cr);
            ruled = 1;
        }
        cairo_set_source_rgb(cr, l->role == LABEL_TITLE ? 0.1 : l->role == LABEL_NOTE ? 0.55 : 0.15,
                             l->role == LABEL_NOTE ? 0.2 : 0.1, 0.1);
        set_font(cr, l->role, l->size);
        cairo_move_to(cr, l->x, l->y);
        cairo_show_text(cr, l->text);
    }
    cairo_destroy(cr);
    return surface_png(surf, png, len);
}

/* ------------------------------------------------------------------ title signs */

/* The font size whose capitals are cap px tall (the "H" measured). */
static double size_for_cap(cairo_t *cr, double cap)
{
    set_font(cr, LABEL_SIGN, 100.0);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, "H", &ext);
    return ext.height > 0 ? 100.0 * cap / ext.height : cap;
}

static int sign_layout_on(cairo_t *cr, const char *title, int width, int height, double cap_px, label_line *lines,
                          int max_lines)
{
    double size = size_for_cap(cr, cap_px), m = MARGIN * width;
    int n_max = max_lines < LABEL_TITLE_LINES ? max_lines : LABEL_TITLE_LINES;
    /* Lines that fit the height, the block centred in it. */
    int fit = (int)floor((height - 0.6 * cap_px - 1.3 * size) / (LINE_SPACING * size)) + 1;
    n_max = fit < n_max ? fit : n_max;
    if (n_max < 1)
        return 0;
    layout_state s = {cr, m, 0, height, width - 2 * m, lines, 0, n_max};
    wrap(&s, title, LABEL_SIGN, size, n_max);
    /* The lines' block (the first one's font size above its baseline, 0.3
     * capitals of descent below the last) centred, each line centred. */
    double block = s.n ? size + (s.n - 1) * LINE_SPACING * size + 0.3 * cap_px : 0;
    for (int i = 0; i < s.n; i++) {
        lines[i].x = 0.5 * (width - lines[i].advance);
        lines[i].y += 0.5 * (height - block);
    }
    return s.n;
}

int label_sign_layout(const char *title, int width, int height, double cap_px, label_line *lines, int max_lines)
{
    cairo_surface_t *surf;
    cairo_t *cr = canvas(1, 1, &surf); /* only measures text */
    if (!cr)
        return -1;
    int n = sign_layout_on(cr, title, width, height, cap_px, lines, max_lines);
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return n;
}

int label_sign_png(const char *title, int width, int height, double cap_px, uint8_t **png, size_t *len)
{
    *png = NULL;
    *len = 0;
    label_line lines[LABEL_TITLE_LINES];
    cairo_surface_t *surf;
    cairo_t *cr = canvas(width, height, &surf);
    if (!cr)
        return -1;
    int n = sign_layout_on(cr, title, width, height, cap_px, lines, LABEL_TITLE_LINES);
    cairo_set_source_rgb(cr, 0.16, 0.24, 0.20); /* a dark celadon plate */
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0.96, 0.94, 0.88); /* the card's colour */
    for (int i = 0; i < n; i++) {
        set_font(cr, LABEL_SIGN, lines[i].size);
        cairo_move_to(cr, lines[i].x, lines[i].y);
        cairo_show_text(cr, lines[i].text);
    }
    cairo_destroy(cr);
    return surface_png(surf, png, len);
}
