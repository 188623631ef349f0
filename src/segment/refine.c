/* recon_refine_mask: the vessel's mask at full resolution. The low-resolution
 * cut settles what is object to within a cell; the same energy (colour
 * models, contrast-sensitive links, symmetry links) is minimised again on the
 * full-resolution pixels of a band around its outline, the rest held at the
 * low-resolution labels.
 *
 * The band: the two cells of every coarse edge, one on each side, and of
 * the cells next to those (the wide band, a cell more on each side) the ones
 * whose own colour does not favour their coarse label by SURE_NATS (a low
 * contrast outline: the coarse cut may be a cell or more off there). Held
 * cells are then the ones the colour models are sure of. Where the cut still
 * reaches the band's edge (a band pixel labelled otherwise than a neighbour
 * at its coarse label) the band takes in the cells there, within the wide
 * band, and the energy is minimised again over those cells and the band's
 * cells around them, the rest held at the labels they have (each such cut
 * lowers the energy of the whole). On a catalogue photo the band holds about
 * half the wide band's pixels. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "segment/maxflow.h"
#include "segment/segment.h"

/* Cuts: the band's, then at most two more where it grew. */
enum { REFINE_PASSES = 3 };

static void pixel_rgb(const image_t *img, size_t p, float out[3])
{
    const float *v = img->data + p * (size_t)img->channels;
    int colour = img->channels >= 3;
    for (int c = 0; c < 3; c++) {
        float x = v[colour ? c : 0];
        out[c] = x > 0 ? (x < 1 ? x : 1) : 0;
    }
}

/* The backdrop's basis at every full-resolution column and row: the surface
 * at pixel (X, Y) is the low-resolution one at ((X + 0.5) / f, (Y + 0.5) / f). */
static recon_backdrop_basis *backdrop_bases(const recon_segmentation *seg, int W, int H)
{
    recon_backdrop_basis *bb = malloc(((size_t)W + H) * sizeof *bb);
    if (!bb)
        return NULL;
    for (int X = 0; X < W; X++)
        recon_backdrop_basis_x(&seg->model.backdrop, (X + 0.5) / seg->factor, &bb[X]);
    for (int Y = 0; Y < H; Y++)
        recon_backdrop_basis_y(&seg->model.backdrop, (Y + 0.5) / seg->factor, &bb[W + Y]);
    return bb;
}

/* Marks in edge the cells whose label differs from a 4-neighbour's, and in
 * wide the 4x4 cells around each such pair (the cells within one cell of
 * either, and one more row and column on the far side). */
static void boundary_bands(const uint8_t *m, int w, int h, uint8_t *edge, uint8_t *wide)
{
    memset(edge, 0, (size_t)w * h);
    memset(wide, 0, (size_t)w * h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            int right = x + 1 < w && m[p] != m[p + 1], down = y + 1 < h && m[p] != m[p + w];
            if (right)
                edge[p] = edge[p + 1] = 1;
            if (down)
                edge[p] = edge[p + w] = 1;
            if (!right && !down)
                continue;
            for (int j = y - 1; j <= y + 2; j++)
                for (int i = x - 1; i <= x + 2; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h)
                        wide[(size_t)j * w + i] = 1;
        }
}

/* The full-resolution pixel mirrored across the axis, or -1 outside. */
static long mirror_full(const recon_segmentation *seg, int W, int H, int X, int Y)
{
    double f = seg->factor, x0 = f * seg->axis_x0, dx = seg->axis_slope;
    double px = X + 0.5, py = Y + 0.5, inv = 1 / (dx * dx + 1);
    double t = ((px - x0) * dx + py) * inv;
    double qx = x0 + 2 * t * dx - (px - x0), qy = 2 * t - py;
    long x = (long)floor(qx), y = (long)floor(qy);
    return x < 0 || y < 0 || x >= W || y >= H ? -1 : y * W + x;
}

/* What the passes share. A cut's nodes are its pixels row by row, each
 * row's active cells left to right: the node of pixel (X, Y) is
 * row_base[Y] + first[its cell] + X - (its cell's first column), without a
 * W*H table (whose pages cost more than the lookups). */
typedef struct {
    const image_t *img;
    const recon_segmentation *seg;
    int W, H;
    int *col_cell, *row_cell; /* W, H: the cell column of each pixel column, the cell row of each row */
    int *first;    /* w*h: offset of an active cell's first pixel in its rows' nodes, or -1 */
    int *row_base; /* H: the node of each row's first active pixel */
    uint8_t *mask;
    const uint8_t *band; /* w*h: the cells that have been in a cut (the rest hold coarse labels) */
    double beta;         /* of the contrast links: from the first cut's pixels */
    recon_backdrop_basis *bb;
    recon_cost_memo *memo;
} refine_work;

/* The cell of full-resolution row Y or column X (pixels past the last full
 * cell belong to it). */
static inline int cell_of(int X, int f, int n) { return X / f < n ? X / f : n - 1; }

/* The node of pixel (X, Y) in the current cut, or -1 when it is held. */
static inline int node_at(const refine_work *r, int X, int Y)
{
    const int cx = r->col_cell[X], off = r->first[(size_t)r->row_cell[Y] * r->seg->w + cx];
    return off < 0 ? -1 : r->row_base[Y] + off + X - cx * r->seg->factor;
}

/* Pixel (X, Y)'s eight neighbours lie in its own cell (it is on neither its
 * cell's border nor the image's): a node's neighbours are then nodes too,
 * found from its own index. */
static inline int inside_cell(const refine_work *r, int X, int Y)
{
    if (X == 0 || Y == 0 || X + 1 == r->W || Y + 1 == r->H)
        return 0;
    const int cx = r->col_cell[X], cy = r->row_cell[Y];
    return r->col_cell[X - 1] == cx && r->col_cell[X + 1] == cx && r->row_cell[Y - 1] == cy &&
           r->row_cell[Y + 1] == cy;
}

static const int OFF[8][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}, {-1, 0}, {0, -1}, {-1, -1}, {1, -1}};

/* One cut on the pixels of the cells marked in active, the others held at
 * their labels in mask. Then marks in grow the cells not in the band whose
 * pixels neighbour a cut pixel labelled otherwise. Returns the number of
 * cells marked, or -1 when out of memory. */
static long cut_cells(refine_work *r, const uint8_t *active, uint8_t *grow)
{
    const int W = r->W, H = r->H, f = r->seg->factor, w = r->seg->w, h = r->seg->h;
    const recon_segmentation *seg = r->seg;
    uint8_t *mask = r->mask;
    /* the cut's pixels, row by row: each cell row's layout of nodes */
    int nn = 0;
    for (int y = 0; y < h; y++) {
        const uint8_t *act = active + (size_t)y * w;
        int *first = r->first + (size_t)y * w, in_row = 0;
        for (int x = 0; x < w; x++) { /* the cell's columns; the last cell's run to the border */
            first[x] = act[x] ? in_row : -1;
            in_row += act[x] ? (x + 1 < w ? f : W - x * f) : 0;
        }
        for (int Y = y * f, Y1 = y + 1 < h ? Y + f : H; Y < Y1; Y++, nn += in_row)
            r->row_base[Y] = nn;
    }
    if (nn == 0)
        return 0;
    long grown = -1;
    int *pix = malloc((size_t)nn * sizeof *pix);
    float *col = malloc((size_t)nn * 6 * sizeof *col);
    maxflow_graph *g = maxflow_create(nn, 5 * nn);
    if (!pix || !col || !g)
        goto out;
    /* each node's pixel, colour and modelled backdrop colour (the surface
     * collapsed along the row once per row; a node's mirror is mostly a node
     * too) */
    float *bgn = col + 3 * (size_t)nn;
    for (int Y = 0, a = 0; Y < H; Y++) {
        const uint8_t *act = active + (size_t)cell_of(Y, f, h) * w;
        double rowcol[RECON_BACKDROP_MAX_GRID][3];
        int collapsed = 0;
        for (int x = 0; x < w; x++) {
            if (!act[x])
                continue;
            if (!collapsed) {
                recon_backdrop_collapse_row(&seg->model.backdrop, &r->bb[W + Y], rowcol);
                collapsed = 1;
            }
            for (int i = 0, run = x + 1 < w ? f : W - x * f; i < run; i++, a++) {
                size_t P = (size_t)Y * W + (size_t)x * f + i;
                pix[a] = (int)P;
                pixel_rgb(r->img, P, col + 3 * (size_t)a);
                recon_backdrop_at_collapsed(rowcol, &r->bb[x * f + i], bgn + 3 * (size_t)a);
            }
        }
    }
    if (r->beta < 0) {
        double s = 0;
        long k = 0;
        for (int a = 0; a < nn; a++) {
            int X = pix[a] % W;
            int b = X + 1 < W ? node_at(r, X + 1, pix[a] / W) : -1;
            if (b < 0)
                continue;
            for (int c = 0; c < 3; c++) {
                double d = col[3 * (size_t)a + c] - col[3 * (size_t)b + c];
                s += d * d;
            }
            k++;
        }
        r->beta = s > 0 ? k / (2 * s) : 0;
    }
    const double beta = r->beta;
    const double lambda = log((1 - SYMMETRY_EPS) / SYMMETRY_EPS);
    for (int a = 0; a < nn; a++) {
        const int X = pix[a] % W, Y = pix[a] / W;
        const float *ca = col + 3 * (size_t)a;
        double co, cb;
        float mc_fixed[3], mbgf_fixed[3];
        const float *mc = NULL, *mbgf = NULL;
        long M = seg->have_axis ? mirror_full(seg, W, H, X, Y) : -1;
        const int m_node = M >= 0 ? node_at(r, (int)(M % W), (int)(M / W)) : -1;
        if (m_node >= 0) {
            mc = col + 3 * (size_t)m_node;
            mbgf = bgn + 3 * (size_t)m_node;
        } else if (M >= 0) {
            double bg[3];
            pixel_rgb(r->img, (size_t)M, mc_fixed);
            recon_backdrop_at_basis(&seg->model.backdrop, &r->bb[M % W], &r->bb[W + M / W], bg);
            for (int c = 0; c < 3; c++)
                mbgf_fixed[c] = (float)bg[c];
            mc = mc_fixed;
            mbgf = mbgf_fixed;
        }
        recon_colour_costs(&seg->model, r->memo, ca, bgn + 3 * (size_t)a, mc, mbgf, &co, &cb);
        double src = cb, snk = co; /* the cost of ending as backdrop / as object */
        /* Links: to band neighbours once (forward half), to fixed neighbours
         * as terminal costs (all eight directions). Inside a cell the
         * neighbour below is as many nodes on as the row holds. */
        const int inner = inside_cell(r, X, Y), down = inner ? r->row_base[Y + 1] - r->row_base[Y] : 0;
        for (int k = 0; k < 8; k++) {
            int QX = X + OFF[k][0], QY = Y + OFF[k][1], b;
            if (inner) {
                if (k >= 4)
                    break;
                b = a + OFF[k][0] + (OFF[k][1] ? down : 0);
            } else {
                if (QX < 0 || QY < 0 || QX >= W || QY >= H)
                    continue;
                b = node_at(r, QX, QY);
                if (b >= 0 && k >= 4)
                    continue;
            }
            size_t Q = (size_t)QY * W + QX;
            float cq[3];
            if (b >= 0)
                memcpy(cq, col + 3 * (size_t)b, sizeof cq);
            else
                pixel_rgb(r->img, Q, cq);
            double wt = recon_contrast_link(ca, cq, beta, OFF[k][0] && OFF[k][1]);
            if (b >= 0)
                maxflow_add_edge(g, a, b, wt, wt);
            else if (mask[Q])
                src += wt;
            else
                snk += wt;
        }
        if (seg->have_axis) {
            if (M >= 0 && m_node < 0) {
                if (mask[M])
                    src += lambda;
                else
                    snk += lambda;
            } else if (M >= 0 && m_node > a) { /* each band pair once */
                maxflow_add_edge(g, a, m_node, lambda, lambda);
            }
        }
        double lo = src < snk ? src : snk;
        maxflow_add_terminals(g, a, src - lo, snk - lo);
    }
    maxflow_solve(g);
    for (int a = 0; a < nn; a++)
        mask[pix[a]] = (uint8_t)maxflow_source_side(g, a);
    /* where the cut met the band's edge */
    grown = 0;
    for (int a = 0; a < nn; a++) {
        const int X = pix[a] % W, Y = pix[a] / W;
        if (inside_cell(r, X, Y)) /* its neighbours are in its cell, which is in the band */
            continue;
        for (int k = 0; k < 8; k++) {
            int QX = X + OFF[k][0], QY = Y + OFF[k][1];
            if (QX < 0 || QY < 0 || QX >= W || QY >= H)
                continue;
            size_t Q = (size_t)QY * W + QX, q = (size_t)r->row_cell[QY] * w + r->col_cell[QX];
            if (r->band[q] || mask[Q] == mask[pix[a]])
                continue;
            grown += !grow[q];
            grow[q] = 1;
        }
    }
out:
    maxflow_destroy(g);
    free(col);
    free(pix);
    return grown;
}

/* The margin, in nats, by which a low-resolution cell's colour must favour
 * its label for the cell to stay out of the band. */
#define SURE_NATS 3.0

/* Low-resolution cell (x, y)'s colour favours its coarse label by
 * SURE_NATS or more (its data term; the mirror cell's colour counts as in
 * the low-resolution rounds). */
static int cell_sure(const recon_segmentation *seg, recon_cost_memo *memo, const uint8_t *coarse, int x, int y)
{
    const recon_backdrop *b = &seg->model.backdrop;
    int p = y * seg->w + x, q = seg->have_axis ? recon_segment_mirror(seg, p) : -1;
    double bg[3], mbg[3];
    float bc[3], mbc[3];
    recon_backdrop_at(b, x + 0.5, y + 0.5, bg);
    if (q >= 0)
        recon_backdrop_at(b, q % seg->w + 0.5, q / seg->w + 0.5, mbg);
    for (int c = 0; c < 3; c++) {
        bc[c] = (float)bg[c];
        mbc[c] = q >= 0 ? (float)mbg[c] : 0;
    }
    double o, k;
    recon_colour_costs(&seg->model, memo, seg->rgb + 3 * (size_t)p, bc, q >= 0 ? seg->rgb + 3 * (size_t)q : NULL,
                       q >= 0 ? mbc : NULL, &o, &k);
    return coarse[p] ? k - o >= SURE_NATS : o - k >= SURE_NATS;
}

/* Adds to band the cells of the wide band that hold the mirror image of a
 * band cell's pixels (the bounding box of its mirrored corners): a band
 * pixel's symmetry link then goes to a pixel that is free too, not to one
 * held at a coarse label. tmp: w*h bytes. */
static void add_mirror_cells(const recon_segmentation *seg, const uint8_t *wide, uint8_t *band, uint8_t *tmp)
{
    const int w = seg->w, h = seg->h;
    const double x0 = seg->axis_x0, dx = seg->axis_slope, inv = 1 / (dx * dx + 1);
    memcpy(tmp, band, (size_t)w * h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (!tmp[(size_t)y * w + x])
                continue;
            double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
            for (int k = 0; k < 4; k++) { /* the cell's corners, mirrored (low-resolution units) */
                double px = x + (k & 1), py = y + (k >> 1);
                double t = ((px - x0) * dx + py) * inv;
                double qx = x0 + 2 * t * dx - (px - x0), qy = 2 * t - py;
                lo_x = fmin(lo_x, qx);
                hi_x = fmax(hi_x, qx);
                lo_y = fmin(lo_y, qy);
                hi_y = fmax(hi_y, qy);
            }
            for (int j = (int)floor(lo_y); j < hi_y; j++)
                for (int i = (int)floor(lo_x); i < hi_x; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h && wide[(size_t)j * w + i])
                        band[(size_t)j * w + i] = 1;
        }
}

int recon_refine_mask(const image_t *img, const recon_segmentation *seg, const uint8_t *coarse, uint8_t *mask)
{
    const int W = img->width, H = img->height, f = seg->factor, w = seg->w, h = seg->h;
    const size_t n = (size_t)w * h;
    uint8_t *band = malloc(4 * n);
    uint8_t *wide = band ? band + n : NULL, *active = band ? band + 2 * n : NULL, *grow = band ? band + 3 * n : NULL;
    int *cells = malloc(((size_t)W + 2 * H + n) * sizeof *cells);
    refine_work r = {img,  seg,  W, H, cells, cells ? cells + W : NULL, cells ? cells + W + H : NULL,
                     cells ? cells + W + H + n : NULL, mask, band, -1, backdrop_bases(seg, W, H),
                     calloc(1, sizeof(recon_cost_memo))};
    int rc = -1;
    if (!band || !cells || !r.bb || !r.memo)
        goto out;
    for (int X = 0; X < W; X++)
        r.col_cell[X] = cell_of(X, f, w);
    for (int Y = 0; Y < H; Y++)
        r.row_cell[Y] = cell_of(Y, f, h);
    /* every pixel its cell's label to start with: a cell row's first
     * full-resolution row, copied to the others */
    for (int Y = 0; Y < H; Y++) {
        uint8_t *row = mask + (size_t)Y * W;
        if (Y > 0 && cell_of(Y, f, h) == cell_of(Y - 1, f, h)) {
            memcpy(row, row - W, (size_t)W);
            continue;
        }
        const uint8_t *c = coarse + (size_t)cell_of(Y, f, h) * w;
        for (int X = 0; X < W; X++)
            row[X] = c[cell_of(X, f, w)];
    }
    boundary_bands(coarse, w, h, band, wide);
    /* the wide band's other cells join the band unless their colour alone
     * says surely what their coarse label says */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            if (wide[p] && !band[p] && !cell_sure(seg, r.memo, coarse, x, y))
                band[p] = 1;
        }
    if (seg->have_axis)
        add_mirror_cells(seg, wide, band, active);
    memcpy(active, band, n);
    for (int pass = 0; pass < REFINE_PASSES; pass++) {
        memset(grow, 0, n);
        long grown = cut_cells(&r, active, grow);
        if (grown < 0)
            goto out;
        if (grown == 0)
            break;
        /* the band takes in the cells the cut reached, within the wide band;
         * the next cut is on them and the band's cells around them */
        long added = 0;
        for (size_t p = 0; p < n; p++) {
            grow[p] = grow[p] && wide[p];
            band[p] |= grow[p];
            added += grow[p];
        }
        if (added == 0)
            break;
        memset(active, 0, n);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                if (!grow[(size_t)y * w + x])
                    continue;
                for (int j = y - 1; j <= y + 1; j++)
                    for (int i = x - 1; i <= x + 1; i++)
                        if (i >= 0 && j >= 0 && i < w && j < h)
                            active[(size_t)j * w + i] = band[(size_t)j * w + i];
            }
    }
    rc = 0;
out:
    free(r.memo);
    free(r.bb);
    free(cells);
    free(band);
    return rc;
}
