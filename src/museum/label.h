/* The label plate of an exhibit, drawn with cairo: title, date, size,
 * a note and the description on a light card, as a PNG in memory (embedded
 * in museum.glb, and written beside museum.xml for the path tracer).
 *
 * The plate's rules (docs/museum.md, "Labels"): the title takes at most
 * LABEL_TITLE_LINES lines, the date, the size and the note one line each,
 * the description what is left; every line fits the plate's width, broken
 * at spaces (inside a word only when the word alone is wider, and then
 * between UTF-8 characters); text that does not fit ends its last line with
 * an ellipsis, so the description is never pushed off by a long title. */
#ifndef CELADON_MUSEUM_LABEL_H
#define CELADON_MUSEUM_LABEL_H

#include <stddef.h>
#include <stdint.h>

enum { LABEL_TITLE_LINES = 2, LABEL_MAX_LINES = 32, LABEL_LINE_BYTES = 512 };

typedef struct {
    const char *title;       /* required */
    const char *date;        /* may be NULL */
    const char *size;        /* the size line (vessel_size_line), may be NULL */
    const char *note;        /* e.g. below the quality gate; may be NULL */
    const char *description; /* may be NULL */
} label_text;

typedef enum { LABEL_TITLE, LABEL_DATE, LABEL_SIZE, LABEL_NOTE, LABEL_DESCRIPTION, LABEL_SIGN } label_role;

/* The title sign's face (LABEL_SIGN lines), bold: narrower letters than the
 * labels' sans-serif, so more of a title fits a plinth's width. */
#define LABEL_SIGN_FONT "DejaVu Sans Condensed"

typedef struct {
    char text[LABEL_LINE_BYTES]; /* UTF-8, an ellipsis "…" at the end when cut */
    label_role role;
    double x, y, size;            /* baseline origin and font size, px */
    double advance;               /* the line's measured width, px */
    int cut;                      /* 1 when text of this part remains after it */
} label_line;

/* The lines of a width x height px plate, as label_render_png draws them.
 * Returns their number (0 when nothing fits), or -1. */
int label_layout(const label_text *t, int width, int height, label_line *lines, int max_lines);

/* The plate's inner width: lines never advance past it (px). */
double label_text_width(int width);

/* The plate as a PNG; *png (malloc'd) receives the file's bytes. Returns 0 or -1. */
int label_render_png(const label_text *t, int width, int height, uint8_t **png, size_t *len);

/* The title sign of an exhibit (layout.h, LAYOUT_SIGN_*): the title alone,
 * bold, its capitals cap_px tall, centred, on at most LABEL_TITLE_LINES
 * lines (fewer when the height has no room), the last one cut with "…";
 * light letters on a dark plate. label_sign_layout gives its lines (their
 * number, or -1), label_sign_png the plate as a PNG (0 or -1). */
int label_sign_layout(const char *title, int width, int height, double cap_px, label_line *lines, int max_lines);
int label_sign_png(const char *title, int width, int height, double cap_px, uint8_t **png, size_t *len);

#endif
