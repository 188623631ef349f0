/* The label plate of an exhibit, drawn with cairo: title, date, height and
 * description on a light card, as a PNG in memory (embedded in museum.glb,
 * and written beside museum.xml for the path tracer). */
#ifndef CELADON_MUSEUM_LABEL_H
#define CELADON_MUSEUM_LABEL_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    const char *title;       /* required */
    const char *date;        /* may be NULL */
    const char *description; /* may be NULL */
    double height_cm;        /* the vessel's height as shown */
} label_text;

/* A width x height px plate (width : height is the plate's aspect), the text
 * wrapped at word boundaries and cut with an ellipsis when it does not fit.
 * *png (malloc'd) receives the PNG file's bytes. Returns 0 or -1. */
int label_render_png(const label_text *t, int width, int height, uint8_t **png, size_t *len);

#endif
