/* recon_select_object: which of the segmentation's objects is the vessel.
 * See recon_internal.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "segment/segment.h"

typedef struct {
    long area;
    int x0, y0, x1, y1; /* bounding box, inclusive */
} component;

/* A thin part of a frame drawn around the photo, or a strip along one edge:
 * it spans nearly a whole side of the image and fills little of its box. */
static int is_border_strip(const component *c, int w, int h)
{
    int touches = c->x0 == 0 || c->y0 == 0 || c->x1 == w - 1 || c->y1 == h - 1;
    long box = (long)(c->x1 - c->x0 + 1) * (c->y1 - c->y0 + 1);
    int spans = c->x1 - c->x0 + 1 >= 0.9 * w || c->y1 - c->y0 + 1 >= 0.9 * h;
    return touches && spans && c->area < 0.25 * box;
}

/* Each component's area and bounding box (comp[1..n]). */
static void boxes(const int *lab, int w, int h, const long *area, int n, component *comp)
{
    for (int k = 1; k <= n; k++)
        comp[k] = (component){area[k], w, h, -1, -1};
    for (int y = 0; y < h; y++) { /* run by run; background runs (label 0) skipped */
        const int *row = lab + (size_t)y * w;
        for (int x = 0; x < w;) {
            int k = row[x], x0 = x;
            while (x < w && row[x] == k)
                x++;
            if (!k)
                continue;
            component *c = &comp[k];
            c->x0 = x0 < c->x0 ? x0 : c->x0;
            c->x1 = x - 1 > c->x1 ? x - 1 : c->x1;
            c->y0 = y < c->y0 ? y : c->y0;
            c->y1 = y > c->y1 ? y : c->y1;
        }
    }
}

/* The extent [*x0, *x1] of component k's pixels on rows y0..y1 (0 when
 * none). */
static int rows_extent(const int *lab, int w, int y0, int y1, int k, int *x0, int *x1)
{
    *x0 = w;
    *x1 = -1;
    for (int y = y0; y <= y1; y++)
        for (int x = 0; x < w; x++)
            if (lab[(size_t)y * w + x] == k) {
                *x0 = x < *x0 ? x : *x0;
                *x1 = x > *x1 ? x : *x1;
            }
    return *x1 >= 0;
}

/* A band painted across the vessel as light as the backdrop (a white line
 * round a neck) cuts the object in two: component k continues the vessel v
 * across such a band when it lies just above or below it (a gap of at most
 * `gap` rows) and their facing ends (their extents over the `gap` rows next
 * to the gap: the band's edges are ragged) are one
 * outline interrupted: the same centre (the same axis) and the same width,
 * each within a tenth of the width (and a pixel). Then the gap's rows are filled
 * between the two facing rows' ends, interpolated, and k joins v. Returns
 * 1 when merged. */
static int join_across_band(int *lab, int w, int h, int gap, component *v, int best, component *c, int k)
{
    int above = c->y1 < v->y0, ya = above ? c->y1 : v->y1, yb = above ? v->y0 : c->y0;
    if (yb - ya - 1 > gap || yb <= ya)
        return 0;
    int ka = above ? k : best, kb = above ? best : k, a0, a1, b0, b1;
    if (!rows_extent(lab, w, ya - gap + 1 > 0 ? ya - gap + 1 : 0, ya, ka, &a0, &a1) ||
        !rows_extent(lab, w, yb, yb + gap - 1 < h ? yb + gap - 1 : h - 1, kb, &b0, &b1))
        return 0;
    double wa = a1 - a0 + 1, wb = b1 - b0 + 1, tol = 0.1 * fmax(wa, wb) + 1;
    if (fabs(0.5 * (a0 + a1) - 0.5 * (b0 + b1)) > tol || fabs(wa - wb) > tol)
        return 0;
    for (int y = ya + 1; y < yb; y++) {
        double t = (double)(y - ya) / (yb - ya);
        int x0 = (int)lround(a0 + t * (b0 - a0)), x1 = (int)lround(a1 + t * (b1 - a1));
        for (int x = x0; x <= x1; x++)
            lab[(size_t)y * w + x] = best;
    }
    for (size_t p = 0; p < (size_t)w * (c->y1 + 1); p++)
        if (lab[p] == k)
            lab[p] = best;
    v->area += c->area + (long)(yb - ya - 1) * (long)(0.5 * (wa + wb));
    v->x0 = c->x0 < v->x0 ? c->x0 : v->x0;
    v->x1 = c->x1 > v->x1 ? c->x1 : v->x1;
    v->y0 = c->y0 < v->y0 ? c->y0 : v->y0;
    v->y1 = c->y1 > v->y1 ? c->y1 : v->y1;
    c->area = 0;
    return 1;
}

/* Joins to component best every component that continues it across a band,
 * until none does. */
static void join_all(int *lab, int w, int h, int gap, component *comp, int n, int best)
{
    for (int merged = 1; merged;) {
        merged = 0;
        for (int k = 1; k <= n; k++)
            if (k != best && comp[k].area > 0 && !is_border_strip(&comp[k], w, h))
                merged |= join_across_band(lab, w, h, gap, &comp[best], best, &comp[k], k);
    }
}

int recon_mask_join_bands(uint8_t *mask, int w, int h, int gap)
{
    /* one object (the common case) has nothing to join: no per-pixel labels */
    int nc = recon_mask_components(mask, w, h);
    if (nc <= 1)
        return nc < 0 ? -1 : 0;
    int *lab = malloc((size_t)w * h * sizeof *lab);
    long *area = NULL;
    component *comp = NULL;
    int n = lab ? recon_mask_label(mask, w, h, lab, &area) : -1;
    if (n < 0 || !(comp = calloc((size_t)n + 1, sizeof *comp))) {
        free(lab);
        free(area);
        return -1;
    }
    boxes(lab, w, h, area, n, comp);
    int best = 0;
    for (int k = 1; k <= n; k++)
        if (!is_border_strip(&comp[k], w, h) && (!best || comp[k].area > comp[best].area))
            best = k;
    if (best) {
        join_all(lab, w, h, gap, comp, n, best);
        for (size_t p = 0; p < (size_t)w * h; p++)
            mask[p] = mask[p] || lab[p] == best;
    }
    free(comp);
    free(area);
    free(lab);
    return 0;
}

recon_status recon_select_object(uint8_t *mask, int w, int h, int *dropped, recon_excluded *stand, char *why,
                                 size_t len)
{
    *dropped = 0;
    *stand = (recon_excluded){.what = RECON_PART_STAND, .row1 = -1};
    int *lab = malloc((size_t)w * h * sizeof *lab);
    long *area = NULL;
    component *comp = NULL;
    recon_status st = RECON_ERR_INTERNAL;
    int n = lab ? recon_mask_label(mask, w, h, lab, &area) : -1;
    if (n < 0 || !(comp = calloc((size_t)n + 1, sizeof *comp))) {
        snprintf(why, len, "out of memory");
        goto out;
    }
    boxes(lab, w, h, area, n, comp);
    int best = 0;
    for (int k = 1; k <= n; k++)
        if (!is_border_strip(&comp[k], w, h) && (!best || comp[k].area > comp[best].area))
            best = k;
    if (!best) {
        st = RECON_ERR_NO_OBJECT;
        snprintf(why, len, "no object found: nothing in the photo stands out from its backdrop");
        goto out;
    }
    component *v = &comp[best];
    join_all(lab, w, h, RECON_BAND_MAX_ROWS, comp, n, best);
    /* A second object of a quarter of the vessel's size or more is another
     * vessel (or a lid set beside it), unless it is a stand: under the vessel,
     * running to the bottom of the photo. */
    for (int k = 1; k <= n; k++) {
        const component *c = &comp[k];
        if (k == best || c->area == 0 || c->area < v->area / 4 || is_border_strip(c, w, h))
            continue;
        int under = c->y0 >= v->y1 - 1 && c->y1 == h - 1 && c->x0 <= (v->x0 + v->x1) / 2 &&
                    c->x1 >= (v->x0 + v->x1) / 2;
        if (under) {
            *stand = (recon_excluded){.what = RECON_PART_STAND, .row0 = c->y0, .row1 = c->y1};
            continue;
        }
        st = RECON_ERR_SHAPE;
        snprintf(why, len,
                 "two objects: beside the largest (%ld px at this scale) there is another of %.0f%% of its size; "
                 "photograph one vessel at a time",
                 v->area, 100.0 * c->area / v->area);
        goto out;
    }
    for (size_t p = 0; p < (size_t)w * h; p++)
        mask[p] = lab[p] == best;
    for (int k = 1; k <= n; k++)
        *dropped += k != best && comp[k].area > 0;
    st = RECON_OK;
out:
    free(comp);
    free(area);
    free(lab);
    return st;
}
