#include "realdev_truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sort.h>

#include "celadon/image.h"

int realdev_truth_load(const char *photo_path, realdev_truth *t)
{
    memset(t, 0, sizeof *t);
    const char *b = strrchr(photo_path, '/');
    char name[256], path[1024], err[256];
    snprintf(name, sizeof name, "%s", b ? b + 1 : photo_path);
    char *dot = strrchr(name, '.');
    if (dot)
        *dot = '\0';
    snprintf(path, sizeof path, "%s/%s.png", REALDEV_TRUTH_DIR, name);
    image_t img;
    if (image_read(path, &img, err, sizeof err) != 0)
        return -1;
    t->width = img.width;
    t->height = img.height;
    t->mask = malloc((size_t)img.width * img.height);
    t->rim_row = img.height;
    t->base_row = -1;
    for (size_t i = 0; t->mask && i < (size_t)img.width * img.height; i++)
        if ((t->mask[i] = img.data[i * img.channels] > 0.5f)) {
            t->rim_row = (int)fmin(t->rim_row, i / img.width);
            t->base_row = (int)(i / img.width);
        }
    image_free(&img);
    if (t->mask && t->rim_row >= t->base_row) {
        free(t->mask);
        t->mask = NULL;
    }
    return t->mask ? 0 : -1;
}

void realdev_truth_free(realdev_truth *t)
{
    free(t->mask);
    memset(t, 0, sizeof *t);
}

double realdev_truth_iou(const realdev_truth *t, const uint8_t *mask)
{
    size_t in = 0, un = 0;
    for (size_t i = 0; i < (size_t)t->width * t->height; i++) {
        in += t->mask[i] && mask[i];
        un += t->mask[i] || mask[i];
    }
    return un ? (double)in / un : 1;
}

/* The truth's edge on row y nearest to x of the kind a side's outline is
 * (side 0: background to its left, vessel to its right; 1: the reverse),
 * the outer silhouette's or a handle window's; 0 when the row has none. */
static int truth_edge(const realdev_truth *t, int y, int side, double x, double *edge)
{
    const uint8_t *row = t->mask + (size_t)y * t->width;
    int found = 0;
    for (int i = 0; i <= t->width; i++) {
        int in = i < t->width && row[i], before = i > 0 && row[i - 1];
        if (side ? (before && !in) : (!before && in)) {
            if (!found || fabs(i - x) < fabs(*edge - x))
                *edge = i;
            found = 1;
        }
    }
    return found;
}

/* Where the profile's image outline on one side crosses the line y (the
 * crossing farthest from the axis); 0 when it does not. */
static int profile_x(const recon_result *x, int side, double y, double *out)
{
    int found = 0;
    double best = 0;
    vec2 prev = {0, 0};
    for (int i = 0; i < x->n_polyline; i++) {
        vec2 p = recon_profile_to_image(x->axis_origin, x->axis_direction, x->polyline[i].x, x->polyline[i].y, side);
        if (i > 0 && (prev.y - y) * (p.y - y) <= 0 && prev.y != p.y) {
            double xc = prev.x + (p.x - prev.x) * (y - prev.y) / (p.y - prev.y);
            if (!found || side * xc > side * best)
                best = xc;
            found = 1;
        }
        prev = p;
    }
    *out = best;
    return found;
}

/* The image rows the profile spans, both sides: [*top, *bottom]. */
static void profile_rows(const recon_result *x, double *top, double *bottom)
{
    *top = INFINITY;
    *bottom = -INFINITY;
    for (int side = -1; side <= 1; side += 2)
        for (int i = 0; i < x->n_polyline; i++) {
            vec2 p = recon_profile_to_image(x->axis_origin, x->axis_direction, x->polyline[i].x, x->polyline[i].y,
                                            side);
            *top = fmin(*top, p.y);
            *bottom = fmax(*bottom, p.y);
        }
}

double realdev_truth_outline(const realdev_truth *t, const recon_result *x)
{
    if (!x->polyline || x->n_polyline < 2)
        return INFINITY;
    int body = t->base_row - t->rim_row + 1;
    double top, bottom;
    profile_rows(x, &top, &bottom);
    int ymin = (int)floor(top), ymax = (int)ceil(bottom);
    /* rows of the body and of the profile, the latter beyond the body by
     * more than the tolerance counted as wrong */
    int slack = (int)ceil(REALDEV_ON_OUTLINE * body);
    int y0 = (int)fmin(t->rim_row, fmax(0, ymin)), y1 = (int)fmax(t->base_row, fmin(t->height - 1, ymax));
    int n = y1 - y0 + 1, m = 0;
    double *d = malloc((size_t)n * sizeof *d);
    if (!d)
        return INFINITY;
    for (int y = y0; y <= y1; y++) {
        int in_body = y >= t->rim_row && y <= t->base_row;
        int near_body = y >= t->rim_row - slack && y <= t->base_row + slack;
        double xp[2], e[2], best = INFINITY;
        int has[2] = {profile_x(x, -1, y + 0.5, &xp[0]), profile_x(x, 1, y + 0.5, &xp[1])};
        if (!in_body && !has[0] && !has[1])
            continue; /* neither the body nor the profile */
        for (int s = 0; near_body && s < 2; s++) {
            if (!has[s] || !truth_edge(t, y, s, xp[s], &e[s]))
                continue;
            /* across the outline: the edge's slope over two rows either side */
            double a, c, slope = 0;
            if (y >= 2 && y + 2 < t->height && truth_edge(t, y - 2, s, e[s], &a) && truth_edge(t, y + 2, s, e[s], &c))
                slope = (c - a) / 4;
            best = fmin(best, fabs(xp[s] - e[s]) / sqrt(1 + slope * slope));
        }
        d[m++] = best;
    }
    gsl_sort(d, 1, (size_t)m);
    int keep = m - (int)floor(0.2 * body);
    double sum = 0;
    for (int i = 0; i < keep; i++)
        sum += d[i];
    free(d);
    return keep > 0 && isfinite(sum) ? sum / keep / body : INFINITY;
}

double realdev_truth_overreach(const realdev_truth *t, const recon_result *x)
{
    if (!x->polyline || x->n_polyline < 2)
        return INFINITY;
    double top, bottom;
    profile_rows(x, &top, &bottom);
    double body = t->base_row - t->rim_row + 1;
    return (fmax(0, t->rim_row - top) + fmax(0, bottom - (t->base_row + 1))) / body;
}

int realdev_truth_on_outline(const realdev_truth *t, const recon_result *x)
{
    return realdev_truth_outline(t, x) <= REALDEV_ON_OUTLINE && realdev_truth_overreach(t, x) <= REALDEV_MAX_OVERREACH;
}
