/* recon_refine_mask: the vessel's mask at full resolution. The low-resolution
 * cut settles what is object to within a cell; the same energy (colour
 * models, contrast-sensitive links, symmetry links) is minimised again on the
 * full-resolution pixels of a band around its outline, three cells wide, the
 * rest held at the low-resolution labels. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "segment/maxflow.h"
#include "segment/segment.h"

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

/* The modelled backdrop colour at full-resolution pixel (X, Y). */
static void backdrop_at(const recon_segmentation *seg, const recon_backdrop_basis *bb, int W, int X, int Y,
                        float out[3])
{
    double bg[3];
    recon_backdrop_at_basis(&seg->model.backdrop, &bb[X], &bb[W + Y], bg);
    for (int c = 0; c < 3; c++)
        out[c] = (float)bg[c];
}

/* Marks the cells within one cell (8-neighbourhood) of a cell whose label
 * differs from a 4-neighbour's. */
static void boundary_band(const uint8_t *m, int w, int h, uint8_t *band)
{
    memset(band, 0, (size_t)w * h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            int edge = (x + 1 < w && m[p] != m[p + 1]) || (y + 1 < h && m[p] != m[p + w]);
            if (!edge)
                continue;
            for (int j = y - 1; j <= y + 2; j++)
                for (int i = x - 1; i <= x + 2; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h)
                        band[(size_t)j * w + i] = 1;
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

int recon_refine_mask(const image_t *img, const recon_segmentation *seg, const uint8_t *coarse, uint8_t *mask)
{
    const int W = img->width, H = img->height, f = seg->factor, w = seg->w, h = seg->h;
    uint8_t *band = malloc((size_t)w * h);
    int *node = malloc((size_t)W * H * sizeof *node);
    int rc = -1, nn = 0;
    maxflow_graph *g = NULL;
    float *col = NULL;
    recon_backdrop_basis *bb = NULL;
    recon_cost_memo *memo = NULL;
    if (!band || !node)
        goto out;
    boundary_band(coarse, w, h, band);
    /* Fixed pixels take their cell's label (pixels past the last full cell
     * take the nearest cell's); band pixels become nodes. */
    for (int Y = 0; Y < H; Y++) {
        int y = Y / f < h ? Y / f : h - 1;
        for (int x = 0; x < w; x++) { /* the cell's columns; the last cell's run to the border */
            size_t p = (size_t)y * w + x, P0 = (size_t)Y * W + (size_t)x * f;
            int run = x + 1 < w ? f : W - x * f;
            memset(mask + P0, coarse[p], (size_t)run);
            for (int i = 0; i < run; i++)
                node[P0 + i] = band[p] ? nn++ : -1;
        }
    }
    if (nn == 0) {
        rc = 0;
        goto out;
    }
    /* each node's colour and modelled backdrop colour (a node's mirror is
     * mostly a node too) */
    col = malloc((size_t)nn * 6 * sizeof *col);
    g = maxflow_create(nn, 5 * nn);
    bb = backdrop_bases(seg, W, H);
    memo = calloc(1, sizeof *memo);
    if (!col || !g || !bb || !memo)
        goto out;
    float *bgn = col + 3 * (size_t)nn;
    for (int Y = 0; Y < H; Y++)
        for (int X = 0; X < W; X++) {
            size_t P = (size_t)Y * W + X;
            if (node[P] >= 0) {
                pixel_rgb(img, P, col + 3 * (size_t)node[P]);
                backdrop_at(seg, bb, W, X, Y, bgn + 3 * (size_t)node[P]);
            }
        }
    double beta = 0;
    {
        double s = 0;
        long k = 0;
        for (int Y = 0; Y < H; Y++)
            for (int X = 0; X + 1 < W; X++) {
                int a = node[(size_t)Y * W + X], b = node[(size_t)Y * W + X + 1];
                if (a < 0 || b < 0)
                    continue;
                for (int c = 0; c < 3; c++) {
                    double d = col[3 * (size_t)a + c] - col[3 * (size_t)b + c];
                    s += d * d;
                }
                k++;
            }
        beta = s > 0 ? k / (2 * s) : 0;
    }
    const double lambda = log((1 - SYMMETRY_EPS) / SYMMETRY_EPS);
    static const int off[8][2] = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}, {-1, 0}, {0, -1}, {-1, -1}, {1, -1}};
    for (int Y = 0; Y < H; Y++)
        for (int X = 0; X < W; X++) {
            size_t P = (size_t)Y * W + X;
            int a = node[P];
            if (a < 0)
                continue;
            const float *ca = col + 3 * (size_t)a;
            double co, cb;
            float mc_fixed[3], mbgf_fixed[3];
            const float *mc = NULL, *mbgf = NULL;
            long M = seg->have_axis ? mirror_full(seg, W, H, X, Y) : -1;
            if (M >= 0 && node[M] >= 0) {
                mc = col + 3 * (size_t)node[M];
                mbgf = bgn + 3 * (size_t)node[M];
            } else if (M >= 0) {
                pixel_rgb(img, (size_t)M, mc_fixed);
                backdrop_at(seg, bb, W, (int)(M % W), (int)(M / W), mbgf_fixed);
                mc = mc_fixed;
                mbgf = mbgf_fixed;
            }
            recon_colour_costs(&seg->model, memo, ca, bgn + 3 * (size_t)a, mc, mbgf, &co, &cb);
            double src = cb, snk = co; /* the cost of ending as backdrop / as object */
            /* Links: to band neighbours once (forward half), to fixed
             * neighbours as terminal costs (all eight directions). */
            for (int k = 0; k < 8; k++) {
                int QX = X + off[k][0], QY = Y + off[k][1];
                if (QX < 0 || QY < 0 || QX >= W || QY >= H)
                    continue;
                size_t Q = (size_t)QY * W + QX;
                int b = node[Q];
                if (b >= 0 && k >= 4)
                    continue;
                float cq[3];
                if (b >= 0)
                    memcpy(cq, col + 3 * (size_t)b, sizeof cq);
                else
                    pixel_rgb(img, Q, cq);
                double wt = recon_contrast_link(ca, cq, beta, off[k][0] && off[k][1]);
                if (b >= 0)
                    maxflow_add_edge(g, a, b, wt, wt);
                else if (mask[Q])
                    src += wt;
                else
                    snk += wt;
            }
            if (seg->have_axis) {
                if (M >= 0 && node[M] < 0) {
                    if (mask[M])
                        src += lambda;
                    else
                        snk += lambda;
                } else if (M >= 0 && node[M] > a) { /* each band pair once */
                    maxflow_add_edge(g, a, node[M], lambda, lambda);
                }
            }
            double lo = src < snk ? src : snk;
            maxflow_add_terminals(g, a, src - lo, snk - lo);
        }
    maxflow_solve(g);
    for (size_t P = 0; P < (size_t)W * H; P++)
        if (node[P] >= 0)
            mask[P] = (uint8_t)maxflow_source_side(g, node[P]);
    rc = 0;
out:
    maxflow_destroy(g);
    free(memo);
    free(bb);
    free(col);
    free(node);
    free(band);
    return rc;
}
