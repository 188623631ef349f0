/* recon_cut_support: where the vessel's foot ends. A floor shadow joined to
 * the foot, or a stand under it, belongs to the segmentation's object but not
 * to the vessel. Each is a hypothesis tested by a second min-cut inside the
 * object, between seeds that are surely vessel (the upper body around the
 * axis) and seeds of the hypothesised part; the cut settles where it is
 * cheapest, across a narrowing (a waist is short) and along a change of
 * colour (contrast-sensitive links are weak there), with the colour models of
 * the two seed sets deciding the pixels between. Then the evidence decides:
 *
 *   shadow   seeds: the object's lowest pixels that have no mirror image in it
 *            (a shadow is darker floor on one side). Accepted when most of
 *            what the cut takes mirrors onto the backdrop.
 *   stand    seeds: where the object runs into the bottom of the photo. A stand
 *            is a separate body: accepted when the cut follows an edge; a
 *            cut through an even body means the vessel itself runs off the
 *            photo, which the quality gate refuses.
 *   plinth   a stand short of the border, seen from above: the object ends
 *            in a straight column (a box's front face or its top face's
 *            front edge: rows within a pixel of the lowest row's extent).
 *            Seeds: its two lowest rows and its pixels beyond the row above
 *            it. Cut in rounds (the front face, then the top face), each
 *            along an edge; accepted once the vessel's base lies below the
 *            part's top (the top face shows around the foot: the camera is
 *            above, where a revolved base would end in a curved near arc,
 *            not on a straight column) and the outline steps out onto the
 *            part on both sides (a plinth is wider than its foot). A band
 *            painted round a body leaves the outline smooth, an L's foot
 *            steps out on one side, a disc foot seen level has the body end
 *            on its top: none is cut.
 *
 * See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "segment/maxflow.h"
#include "segment/segment.h"

/* Seeds are hard: a capacity no cut can afford. */
#define HARD 1e9
enum { SEED_COMPONENTS = 3 };
/* A cut follows an edge when, on average over its links, the neighbours
 * across it differ by as much as exp(-beta d^2) <= 0.3, i.e. by about 1.5
 * times the image's typical neighbour difference (beta is 1 / (2 <d^2>)). */
#define EDGE_LINK_MAX 0.3
/* A shadow's colours lie on the line of its backdrop darkened, their
 * misfit about chi-square with 2 degrees of freedom under the shadow's
 * noise (median 1.4): a median over 16 (4 sigmas) is a colour of its own. */
#define SHADOW_MAX_MISFIT 16.0
/* A plinth's column is at least 3 rows high, the outline steps out onto it
 * by at least 2 px on each side, and the vessel's base reaches at least 2
 * rows below its top (at the working resolution 2 rows are 1% of the
 * photo's longer side); at most 3 rounds of cuts. */
enum { PLINTH_MIN_ROWS = 3, PLINTH_MIN_STEP = 2, PLINTH_MIN_OVERLAP = 2, PLINTH_MAX_ROUNDS = 3 };

typedef enum { HYPO_SHADOW, HYPO_STAND, HYPO_PLINTH } hypothesis;

/* A plinth's column in the object: rows top..bottom of the same extent as
 * the lowest row, under the row top - 1, which spans l..r. */
typedef struct {
    int top, bottom, l, r;
} plinth_column;

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

/* The object's rows span [*top, *bottom]; 0, or -1 when it has none. */
static int row_span(const uint8_t *m, int w, int h, int *top, int *bottom)
{
    *top = h;
    *bottom = -1;
    for (int y = 0; y < h; y++)
        if (memchr(m + (size_t)y * w, 1, (size_t)w)) {
            *top = y < *top ? y : *top;
            *bottom = y;
        }
    return *bottom >= 0 ? 0 : -1;
}

/* The extent [*l, *r] of a row's object pixels; 0 when it has none. */
static int row_extent(const uint8_t *row, int w, int *l, int *r)
{
    const uint8_t *a = memchr(row, 1, (size_t)w);
    if (!a)
        return 0;
    *l = (int)(a - row);
    *r = (int)((const uint8_t *)memrchr(row, 1, (size_t)w) - row);
    return 1;
}

/* The first row of the straight column that rises from row y: the rows
 * whose object extent stays within a pixel, on each side, of row y's. */
static int column_from(const uint8_t *m, int w, int y)
{
    int l0, r0, l, r;
    if (!row_extent(m + (size_t)y * w, w, &l0, &r0))
        return y + 1;
    while (y > 0 && row_extent(m + (size_t)(y - 1) * w, w, &l, &r) && abs(l - l0) <= 1 && abs(r - r0) <= 1)
        y--;
    return y;
}

/* The first row of the straight column that rises from the bottom border
 * (a stand's cylinder or box, or a vessel's wall cut by the border: nothing
 * there is surely the vessel). bottom + 1 when the object does not reach
 * the border. */
static int column_top(const uint8_t *m, int w, int h, int bottom)
{
    return bottom < h - 1 ? bottom + 1 : column_from(m, w, h - 1);
}

/* A plinth's column under the object (plinth_column): at least
 * PLINTH_MIN_ROWS rows with the object above it. 1 when the object ends in
 * one. */
static int find_plinth_column(const uint8_t *m, int w, int bottom, plinth_column *pc)
{
    pc->bottom = bottom;
    pc->top = column_from(m, w, bottom);
    return pc->top >= 1 && bottom - pc->top + 1 >= PLINTH_MIN_ROWS &&
           row_extent(m + (size_t)(pc->top - 1) * w, w, &pc->l, &pc->r);
}

/* Does the part cut off show beside the vessel's base? The vessel's lowest
 * row lies at least PLINTH_MIN_OVERLAP rows below the part's top: the
 * plinth's top face is seen around the foot (from above), where a disc foot
 * seen level has the body end on its top. */
static int part_beside_base(const uint8_t *m, const uint8_t *sup, int w, int h)
{
    int part_top = h, low = -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            part_top = sup[p] && y < part_top ? y : part_top;
            low = m[p] && !sup[p] ? y : low;
        }
    return low >= part_top + PLINTH_MIN_OVERLAP;
}

/* Does the object's outline step out onto the part on both sides? A plinth
 * is a body wider than the foot: somewhere on each side the outline's
 * outermost pixel moves out by PLINTH_MIN_STEP px or more from a row where
 * it is the vessel's to the next row down where it is the part's (the
 * plinth's top edge). A band painted round a body, cut along, leaves the
 * outline running on smoothly; an L's foot steps out on one side. */
static int part_steps_out(const uint8_t *m, const uint8_t *sup, int w, int h)
{
    int found[2] = {0, 0}, prev[2] = {0, 0}, prev_vessel[2] = {0, 0};
    for (int y = 0; y < h; y++) {
        int l, r;
        if (!row_extent(m + (size_t)y * w, w, &l, &r)) {
            prev_vessel[0] = prev_vessel[1] = 0;
            continue;
        }
        int edge[2] = {l, r}, reach[2] = {-l, r}; /* how far out, per side */
        for (int s = 0; s < 2; s++) {
            int on_part = sup[(size_t)y * w + edge[s]];
            found[s] |= on_part && prev_vessel[s] && reach[s] - prev[s] >= PLINTH_MIN_STEP;
            prev[s] = reach[s];
            prev_vessel[s] = !on_part;
        }
    }
    return found[0] && found[1];
}

/* Marks the seeds of a hypothesis; returns their count, or -1. */
static int part_seeds(const recon_segmentation *seg, const uint8_t *m, hypothesis hyp, const plinth_column *pc,
                      uint8_t *seed)
{
    const int w = seg->w, h = seg->h;
    int top, bottom, n = 0;
    memset(seed, 0, (size_t)w * h);
    if (row_span(m, w, h, &top, &bottom) != 0)
        return 0;
    uint8_t *dil = NULL;
    if (hyp == HYPO_SHADOW) {
        if (!seg->have_axis)
            return 0;
        if (!(dil = malloc((size_t)w * h)))
            return -1;
        dilate(m, w, h, 2, dil);
    }
    int low = bottom - (bottom - top) / 8;
    for (int y = top; y <= bottom; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            if (!m[p])
                continue;
            if (hyp == HYPO_STAND)
                seed[p] = y >= h - 2;
            else if (hyp == HYPO_PLINTH)
                seed[p] = y >= pc->top && (y >= bottom - 1 || x < pc->l - 1 || x > pc->r + 1);
            else if (y >= low) {
                int q = recon_segment_mirror(seg, p);
                seed[p] = q < 0 || !dil[q];
            }
            n += seed[p];
        }
    free(dil);
    return n;
}

/* The vessel's seeds: the upper half of the object above the column that
 * rises from the bottom border (all of it when that column is all), within a
 * quarter of the row's width of the axis (and not a part seed). A stand
 * taller than the vessel (a bowl on a pillar) put the upper half's lower
 * rows on the stand. */
static int vessel_seeds(const recon_segmentation *seg, const uint8_t *m, const uint8_t *part, uint8_t *seed,
                        int *idx)
{
    const int w = seg->w, h = seg->h;
    int top, bottom, n = 0;
    memset(seed, 0, (size_t)w * h);
    if (row_span(m, w, h, &top, &bottom) != 0)
        return 0;
    int end = column_top(m, w, h, bottom);
    end = end > top ? end : bottom + 1;
    for (int y = top; y <= top + (end - 1 - top) / 2; y++) {
        const uint8_t *row = m + (size_t)y * w;
        int l, r;
        if (!row_extent(row, w, &l, &r))
            continue;
        double c = seg->have_axis ? seg->axis_x0 + seg->axis_slope * (y + 0.5) : 0.5 * (l + r + 1);
        double half = 0.25 * (r - l + 1);
        for (int x = l; x <= r; x++)
            if (row[x] && fabs(x + 0.5 - c) < half && !part[(size_t)y * w + x]) {
                seed[(size_t)y * w + x] = 1;
                idx[n++] = y * w + x;
            }
    }
    return n;
}

/* The min-cut between the seeds inside the object m: on return sup holds the
 * part (the sink side's pixels connected to its seeds), *edge the mean of
 * exp(-beta d^2) over the links the cut crosses (0: a sharp colour edge, 1:
 * none). Fits the part's colour model into *part_gmm (sets *colours). Returns
 * the part's pixel count, or -1. */
static long seeded_cut(const recon_segmentation *seg, const uint8_t *m, const uint8_t *pseed, uint8_t *sup,
                       double *edge, recon_gmm *part_gmm, int *colours)
{
    const int w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    uint8_t *vseed = malloc(n);
    int *idx = malloc(n * 2 * sizeof *idx), *lab = NULL;
    long *area = NULL, count = -1;
    maxflow_graph *g = maxflow_create((int)n, (int)(4 * n));
    recon_gmm vessel;
    if (!vseed || !idx || !g)
        goto out;
    int nv = vessel_seeds(seg, m, pseed, vseed, idx), np = 0, *pidx = idx + n;
    for (size_t p = 0; p < n; p++)
        if (pseed[p])
            pidx[np++] = (int)p;
    *colours = recon_gmm_fit(&vessel, seg->rgb, idx, nv, SEED_COMPONENTS, 2) == 0 &&
               recon_gmm_fit(part_gmm, seg->rgb, pidx, np, SEED_COMPONENTS, 2) == 0;
    static const int off[4][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            if (!m[p])
                continue;
            if (vseed[p])
                maxflow_add_terminals(g, p, HARD, 0);
            else if (pseed[p])
                maxflow_add_terminals(g, p, 0, HARD);
            else if (*colours) {
                double cv = -recon_gmm_log_density(&vessel, seg->rgb + 3 * (size_t)p);
                double cs = -recon_gmm_log_density(part_gmm, seg->rgb + 3 * (size_t)p);
                double lo = cv < cs ? cv : cs;
                maxflow_add_terminals(g, p, cs - lo, cv - lo);
            }
            for (int k = 0; k < 4; k++) {
                int qx = x + off[k][0], qy = y + off[k][1];
                if (qx < 0 || qx >= w || qy >= h || !m[qy * w + qx])
                    continue;
                double wt = recon_segment_link(seg, p, qy * w + qx, k >= 2);
                maxflow_add_edge(g, p, qy * w + qx, wt, wt);
            }
        }
    maxflow_solve(g);
    for (size_t p = 0; p < n; p++)
        sup[p] = m[p] && !maxflow_source_side(g, (int)p);
    lab = idx; /* reused: n ints */
    int nc = recon_mask_label(sup, w, h, lab, &area);
    if (nc < 0)
        goto out;
    uint8_t *keep = calloc((size_t)nc + 1, 1);
    if (!keep)
        goto out;
    for (size_t p = 0; p < n; p++)
        if (pseed[p] && lab[p])
            keep[lab[p]] = 1;
    count = 0;
    for (size_t p = 0; p < n; p++) {
        sup[p] = lab[p] && keep[lab[p]];
        count += sup[p];
    }
    free(keep);
    /* The links across the cut: between the part and the rest of the object. */
    double s = 0;
    long links = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int p = y * w + x;
            for (int k = 0; k < 4 && m[p]; k++) {
                int qx = x + off[k][0], qy = y + off[k][1], q = qy * w + qx;
                if (qx < 0 || qx >= w || qy >= h || !m[q] || sup[p] == sup[q])
                    continue;
                s += recon_segment_link(seg, p, q, 0) / recon_segment_link(seg, p, p, 0);
                links++;
            }
        }
    *edge = links ? s / links : 1;
out:
    maxflow_destroy(g);
    free(area);
    free(idx);
    free(vseed);
    return count;
}

/* The median over the part's pixels of their colour's misfit as the
 * backdrop darkened (recon_shadow_misfit). */
static double part_shadow_misfit(const recon_segmentation *seg, const uint8_t *sup)
{
    const int w = seg->w;
    long n = 0;
    for (size_t p = 0; p < (size_t)w * seg->h; p++)
        n += sup[p];
    double *q = malloc((size_t)(n > 0 ? n : 1) * sizeof *q);
    if (!q)
        return 0; /* out of memory: the mirror test alone, as before */
    long k = 0;
    for (size_t p = 0; p < (size_t)w * seg->h; p++)
        if (sup[p]) {
            double bd[3];
            recon_backdrop_at(&seg->model.backdrop, p % w + 0.5, p / w + 0.5, bd);
            float bc[3] = {(float)bd[0], (float)bd[1], (float)bd[2]};
            q[k++] = recon_shadow_misfit(&seg->model, seg->rgb + 3 * p, bc);
        }
    double med = n > 0 ? gsl_stats_median(q, 1, (size_t)n) : 0;
    free(q);
    return med;
}

/* Does the cut-off part pass its hypothesis's test? A shadow has no mirror
 * image: most of its pixels lie beyond the object's reach on the other side
 * of the axis, mirrored (the row's extent, not the mirror pixel: a highlight
 * as light as the backdrop leaves holes in the other side, not a shorter
 * row). A symmetric part mirrors onto itself: a stand, not a shadow. And a
 * shadow is the backdrop darkened: a part of a colour of its own (the foot
 * of an L in the object's glaze) is none, whatever its outline
 * (SHADOW_MAX_MISFIT). A stand is another body: the cut follows an edge. */
static int accepted(const recon_segmentation *seg, hypothesis hyp, const uint8_t *m, const uint8_t *sup, double edge)
{
    const int w = seg->w;
    if (hyp == HYPO_STAND)
        return edge <= EDGE_LINK_MAX;
    long part = 0, unmirrored = 0;
    for (int y = 0; y < seg->h; y++) {
        const uint8_t *row = m + (size_t)y * w, *srow = sup + (size_t)y * w;
        double c = seg->have_axis ? seg->axis_x0 + seg->axis_slope * (y + 0.5) : w / 2.0;
        double reach[2] = {-1, -1}; /* the object's farthest pixel edge from the axis, left and right */
        for (int x = 0; x < w; x++)
            if (row[x] && !srow[x]) {
                int s = x + 0.5 > c;
                reach[s] = fmax(reach[s], s ? x + 1 - c : c - x);
            }
        for (int x = 0; x < w; x++)
            if (srow[x]) {
                int s = x + 0.5 > c;
                part++;
                unmirrored += fabs(x + 0.5 - c) > reach[1 - s] + 1;
            }
    }
    return 2 * unmirrored > part && part_shadow_misfit(seg, sup) <= SHADOW_MAX_MISFIT;
}

/* The plinth hypothesis, in rounds: each cuts the column the object ends in
 * (a box's front face, then its top face seen from above, ...) between the
 * vessel's seeds and the column's; every cut must follow an edge, and the
 * rounds stop, accepted, once the plinth shows beside the vessel's base
 * (part_beside_base), or give up after PLINTH_MAX_ROUNDS. On acceptance sup
 * holds all the rounds' parts and *part_gmm their colours. Returns the
 * part's pixel count, 0 when refused, or -1. */
static long plinth_cut(const recon_segmentation *seg, const uint8_t *m, uint8_t *seed, uint8_t *sup,
                       recon_gmm *part_gmm, int *colours)
{
    const int w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    uint8_t *work = malloc(n * 2), *part = work ? work + n : NULL;
    int *idx = malloc(n * sizeof *idx);
    long count = -1;
    if (!work || !idx)
        goto out;
    memcpy(work, m, n);
    memset(part, 0, n);
    count = 0;
    for (int round = 0; round < PLINTH_MAX_ROUNDS; round++) {
        int top, bottom;
        plinth_column pc;
        if (row_span(work, w, h, &top, &bottom) != 0 || bottom - top < 8 || !find_plinth_column(work, w, bottom, &pc))
            break;
        double edge;
        long cut = part_seeds(seg, work, HYPO_PLINTH, &pc, seed) > 0
                       ? seeded_cut(seg, work, seed, sup, &edge, part_gmm, colours)
                       : 0;
        if (cut < 0) {
            count = -1;
            goto out;
        }
        if (cut == 0 || edge > EDGE_LINK_MAX)
            break;
        for (size_t p = 0; p < n; p++) {
            part[p] |= sup[p];
            work[p] &= !sup[p];
        }
        if (!part_beside_base(m, part, w, h) || !part_steps_out(m, part, w, h))
            continue;
        int np = 0;
        for (size_t p = 0; p < n; p++)
            if ((sup[p] = part[p]))
                idx[np++] = (int)p;
        *colours = recon_gmm_fit(part_gmm, seg->rgb, idx, np, SEED_COMPONENTS, 2) == 0;
        count = np;
        break;
    }
out:
    free(idx);
    free(work);
    return count;
}

int recon_cut_support(recon_segmentation *seg, uint8_t *m, recon_excluded *parts, int max_parts, int *n_parts)
{
    const int w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    uint8_t *seed = malloc(n * 2), *sup = seed ? seed + n : NULL;
    int rc = -1, top, bottom;
    if (!seed)
        return -1;
    int border = 0;
    for (int x = 0; x < w && !border; x++)
        border = m[(size_t)(h - 1) * w + x];
    /* shadow first; then a stand at the border, or a plinth short of it */
    hypothesis order[2] = {HYPO_SHADOW, border ? HYPO_STAND : HYPO_PLINTH};
    for (int k = 0; k < 2; k++) {
        if (row_span(m, w, h, &top, &bottom) != 0 || bottom - top < 8)
            break;
        double edge;
        recon_gmm part_gmm;
        int colours;
        long count;
        if (order[k] == HYPO_PLINTH) {
            count = plinth_cut(seg, m, seed, sup, &part_gmm, &colours);
        } else {
            int ns = part_seeds(seg, m, order[k], NULL, seed);
            if (ns < 0)
                goto out;
            if (ns == 0)
                continue;
            count = seeded_cut(seg, m, seed, sup, &edge, &part_gmm, &colours);
            if (count > 0 && !accepted(seg, order[k], m, sup, edge))
                count = 0;
        }
        if (count < 0)
            goto out;
        if (count == 0)
            continue;
        int y0 = h, y1 = -1;
        double side_sum = 0;
        for (size_t p = 0; p < n; p++)
            if (sup[p]) {
                m[p] = 0;
                int y = (int)(p / w);
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
                double c = seg->have_axis ? seg->axis_x0 + seg->axis_slope * (y + 0.5) : w / 2.0;
                side_sum += (p % w + 0.5 - c) > 0 ? 1 : -1;
            }
        if (order[k] != HYPO_SHADOW && colours) { /* a stand's colours are not the vessel's */
            seg->model.support = part_gmm;
            seg->model.have_support = 1;
        }
        if (*n_parts < max_parts)
            parts[(*n_parts)++] = (recon_excluded){
                .what = order[k] == HYPO_SHADOW ? RECON_PART_SHADOW : RECON_PART_STAND,
                .row0 = y0 * seg->factor,
                .row1 = (y1 + 1) * seg->factor - 1,
                .side = order[k] != HYPO_SHADOW || fabs(side_sum) < 0.5 * count ? 0 : (side_sum > 0 ? 1 : -1),
                .profile = RECON_PROFILE_NONE,
            };
    }
    rc = 0;
out:
    free(seed);
    return rc;
}
