/* recon_select_object: which of the segmentation's objects is the vessel.
 * See recon_internal.h. */
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
    for (int k = 1; k <= n; k++)
        comp[k] = (component){area[k], w, h, -1, -1};
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            component *c = &comp[lab[(size_t)y * w + x]];
            c->x0 = x < c->x0 ? x : c->x0;
            c->x1 = x > c->x1 ? x : c->x1;
            c->y0 = y < c->y0 ? y : c->y0;
            c->y1 = y > c->y1 ? y : c->y1;
        }
    int best = 0;
    for (int k = 1; k <= n; k++)
        if (!is_border_strip(&comp[k], w, h) && (!best || comp[k].area > comp[best].area))
            best = k;
    if (!best) {
        st = RECON_ERR_NO_OBJECT;
        snprintf(why, len, "no object found: nothing in the photo stands out from its backdrop");
        goto out;
    }
    const component *v = &comp[best];
    /* A second object of a quarter of the vessel's size or more is another
     * vessel (or a lid set beside it), unless it is a stand: under the vessel,
     * running to the bottom of the photo. */
    for (int k = 1; k <= n; k++) {
        const component *c = &comp[k];
        if (k == best || c->area < v->area / 4 || is_border_strip(c, w, h))
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
    *dropped = n - 1;
    st = RECON_OK;
out:
    free(comp);
    free(area);
    free(lab);
    return st;
}
