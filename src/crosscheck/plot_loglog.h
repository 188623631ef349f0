/* Log-log line and scatter plots drawn with cairo into a PNG: decade ticks
 * with minor ticks at 2..9, axis labels, a title, and a legend of the
 * labelled series. Used for the cross-check's convergence plot. */
#ifndef CELADON_PLOT_LOGLOG_H
#define CELADON_PLOT_LOGLOG_H

#include <stddef.h>

enum { PLOT_POINTS = 1u, PLOT_LINE = 2u, PLOT_DASHED = 4u };

typedef struct {
    const char *label; /* legend text, or NULL for none */
    const double *x, *y;
    int n;             /* points; those with x or y <= 0 or not finite are skipped */
    unsigned style;    /* PLOT_* mask: markers, a polyline through the points, dashed line */
    double rgb[3];
} plot_series;

typedef struct {
    const char *title, *xlabel, *ylabel;
    int width, height; /* pixels */
    const plot_series *series;
    int nseries;
} plot_loglog;

/* Draws and writes the PNG atomically. The axes span every drawable point
 * with a margin of 6% of the span on each side (at least 0.1 decade); ticks
 * sit at decades and at 2..9 times them, labelled at decades (and at the
 * minor ticks too when an axis spans less than a decade). Returns
 * 0, or -1 with a one-line reason naming the file (also when no point is
 * drawable). */
int plot_loglog_write_png(const plot_loglog *p, const char *path, char *err, size_t errlen);

#endif
