/* recon_cut_support: where the vessel's foot ends. A stand under the vessel
 * or a shadow joined to its foot belongs to the segmentation's object but not
 * to the vessel: a second min-cut, inside the object, between seeds that are
 * surely vessel (the upper body around the axis) and seeds that are surely
 * not (where the object runs into the bottom of the photo; its lowest pixels
 * that have no mirror image in the object). The cut settles where it is
 * cheapest: across a narrowing (a waist is short) and along a change of
 * colour (contrast-sensitive links are weak there), and the colour models of
 * the two seed sets decide the pixels between. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/maxflow.h"
#include "recon/recon_internal.h"
#include "recon/segment.h"

/* Seeds are hard: a capacity no cut can afford. */
#define HARD 1e9
enum { SEED_COMPONENTS = 3 };

/* The mask dilated by a (2r+1)^2 square. */
static void dilate(const uint8_t *m, int w, int h, int r, uint8_t *out)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t v = 0;
            for (int j = y - r; j <= y + r && !v; j++)
                for (int i = x - r; i <= x + r && !v; i++)
                    v = i >= 0 && j >= 0 && i < w && j < h && m[(size_t)j * w + i];
            out[(size_t)y * w + x] = v;
        }
}

/* Marks the support seeds: the object's pixels on the bottom border rows (a
 * stand running off the photo), and, in the lowest eighth of its rows, those
 * whose mirror image lies 2 px or more outside it (a shadow on one side).
 * Returns the count; *stand is set when the first kind exists. */
static int support_seeds(const recon_segmentation *seg, const uint8_t *m, int top, int bottom, uint8_t *seed,
                         int *stand)
{
    const int w = seg->w, h = seg->h;
    uint8_t *dil = malloc((size_t)w * h);
    if (!dil)
        return -1;
    dilate(m, w, h, 2, dil);
    int n = 0, low = bottom - (bottom - top) / 8;
    *stand = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            seed[p] = 0;
            if (!m[p])
                continue;
            if (y >= h - 2) {
                seed[p] = 1;
                *stand = 1;
            } else if (y >= low && seg->have_axis) {
                int q = recon_segment_mirror(seg, p);
                seed[p] = q < 0 || !dil[q];
            }
            n += seed[p];
        }
    free(dil);
    return n;
}

int recon_cut_support(recon_segmentation *seg, uint8_t *m, recon_excluded *part)
{
    const int w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    memset(part, 0, sizeof *part);
    int top = h, bottom = -1;
    for (int y = 0; y < h; y++)
        if (memchr(m + (size_t)y * w, 1, (size_t)w)) {
            top = y < top ? y : top;
            bottom = y;
        }
    if (bottom - top < 8)
        return 0;
    uint8_t *seed = malloc(n * 2);
    int *idx = malloc(n * 2 * sizeof *idx);
    maxflow_graph *g = maxflow_create((int)n, (int)(4 * n));
    recon_gmm vessel;
    int rc = -1, stand = 0;
    if (!seed || !idx || !g)
        goto out;
    int ns = support_seeds(seg, m, top, bottom, seed, &stand);
    if (ns < 0)
        goto out;
    rc = 0;
    if (ns == 0)
        goto out;
    /* Vessel seeds: the upper half of the object, within half the row's
     * half-width of the axis. */
    uint8_t *vseed = seed + n;
    int nv = 0, nsup = 0, *sidx = idx + n;
    memset(vseed, 0, n);
    for (int y = top; y <= top + (bottom - top) / 2; y++) {
        const uint8_t *row = m + (size_t)y * w, *a = memchr(row, 1, (size_t)w);
        if (!a)
            continue;
        int l = (int)(a - row), r = (int)((const uint8_t *)memrchr(row, 1, (size_t)w) - row);
        double c = seg->have_axis ? seg->axis_x0 + seg->axis_slope * (y + 0.5) : 0.5 * (l + r + 1);
        double half = 0.25 * (r - l + 1);
        for (int x = l; x <= r; x++)
            if (row[x] && fabs(x + 0.5 - c) < half && !seed[(size_t)y * w + x]) {
                vseed[(size_t)y * w + x] = 1;
                idx[nv++] = y * w + x;
            }
    }
    for (size_t p = 0; p < n; p++)
        if (seed[p])
            sidx[nsup++] = (int)p;
    int colours = recon_gmm_fit(&vessel, seg->rgb, idx, nv, SEED_COMPONENTS, 2) == 0 &&
                  recon_gmm_fit(&seg->model.support, seg->rgb, sidx, nsup, SEED_COMPONENTS, 2) == 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            if (!m[p])
                continue;
            if (vseed[p])
                maxflow_add_terminals(g, p, HARD, 0);
            else if (seed[p])
                maxflow_add_terminals(g, p, 0, HARD);
            else if (colours) {
                double cv = -recon_gmm_log_density(&vessel, seg->rgb + 3 * (size_t)p);
                double cs = -recon_gmm_log_density(&seg->model.support, seg->rgb + 3 * (size_t)p);
                double lo = cv < cs ? cv : cs;
                maxflow_add_terminals(g, p, cs - lo, cv - lo);
            }
            static const int off[4][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};
            for (int k = 0; k < 4; k++) {
                int qx = x + off[k][0], qy = y + off[k][1];
                if (qx < 0 || qx >= w || qy >= h || !m[qy * w + qx])
                    continue;
                double wt = recon_segment_link(seg, p, qy * w + qx, k >= 2);
                maxflow_add_edge(g, p, qy * w + qx, wt, wt);
            }
        }
    maxflow_solve(g);
    /* The support: the sink side's pixels connected to its seeds. */
    uint8_t *sup = vseed; /* reused */
    for (size_t p = 0; p < n; p++)
        sup[p] = m[p] && !maxflow_source_side(g, (int)p);
    int *lab = idx;
    long *area = NULL;
    int nc = recon_mask_label(sup, w, h, lab, &area);
    free(area);
    if (nc < 0) {
        rc = -1;
        goto out;
    }
    uint8_t *keep = calloc((size_t)nc + 1, 1);
    if (!keep) {
        rc = -1;
        goto out;
    }
    for (size_t p = 0; p < n; p++)
        if (seed[p] && lab[p])
            keep[lab[p]] = 1;
    int y0 = h, y1 = -1;
    double side_sum = 0;
    long count = 0;
    for (size_t p = 0; p < n; p++)
        if (lab[p] && keep[lab[p]]) {
            m[p] = 0;
            int y = (int)(p / w);
            y0 = y < y0 ? y : y0;
            y1 = y > y1 ? y : y1;
            double c = seg->have_axis ? seg->axis_x0 + seg->axis_slope * (y + 0.5) : w / 2.0;
            side_sum += (p % w + 0.5 - c) > 0 ? 1 : -1;
            count++;
        }
    free(keep);
    if (count > 0) {
        seg->model.have_support = colours;
        part->what = stand ? RECON_PART_STAND : RECON_PART_SHADOW;
        part->row0 = y0 * seg->factor;
        part->row1 = (y1 + 1) * seg->factor - 1;
        part->side = stand || fabs(side_sum) < 0.5 * count ? 0 : (side_sum > 0 ? 1 : -1);
        rc = 1;
    }
out:
    maxflow_destroy(g);
    free(idx);
    free(seed);
    return rc;
}
