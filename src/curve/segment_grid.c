/* A uniform grid of buckets over polyline segments. Each segment is listed
 * in every cell its bounding box touches; a query visits square rings of
 * cells around its own cell and stops once the best distance is no larger
 * than the distance to any unvisited cell (r cells away after ring r). A
 * query outside the box starts from the nearest cell: projecting onto the box
 * brings a point no closer to anything inside it, so the bound still holds. */
#include "segment_grid.h"

#include <stdlib.h>
#include <string.h>

/* Squared distance from q to segment a b and the parameter of the nearest
 * point (squared: no hypot in the inner loop of a query). */
static double point_segment_distance2(vec2 q, vec2 a, vec2 b, double *t)
{
    vec2 ab = v2_sub(b, a);
    double l2 = v2_dot(ab, ab), s = l2 > 0.0 ? v2_dot(v2_sub(q, a), ab) / l2 : 0.0;
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    *t = s;
    vec2 e = v2_sub(q, v2_add(a, v2_scale(ab, s)));
    return v2_dot(e, e);
}

static int n_segments(const segment_grid *g) { return g->n > 1 ? g->n - 1 : 1; }

static void segment_cells(const segment_grid *g, int s, int *x0, int *y0, int *x1, int *y1)
{
    vec2 a = g->p[s], b = g->p[g->n > 1 ? s + 1 : s];
    *x0 = (int)((fmin(a.x, b.x) - g->lo.x) / g->cell);
    *x1 = (int)((fmax(a.x, b.x) - g->lo.x) / g->cell);
    *y0 = (int)((fmin(a.y, b.y) - g->lo.y) / g->cell);
    *y1 = (int)((fmax(a.y, b.y) - g->lo.y) / g->cell);
    *x1 = *x1 < g->nx ? *x1 : g->nx - 1;
    *y1 = *y1 < g->ny ? *y1 : g->ny - 1;
}

int segment_grid_build(segment_grid *g, const vec2 *p, int n)
{
    memset(g, 0, sizeof *g);
    if (n < 1)
        return -1;
    g->p = p;
    g->n = n;
    vec2 lo = p[0], hi = p[0];
    double total = 0.0;
    for (int i = 0; i < n; i++) {
        lo = v2(fmin(lo.x, p[i].x), fmin(lo.y, p[i].y));
        hi = v2(fmax(hi.x, p[i].x), fmax(hi.y, p[i].y));
        if (i > 0)
            total += v2_len(v2_sub(p[i], p[i - 1]));
    }
    int ns = n_segments(g);
    /* Cells about twice the mean segment length, and no more than ~4 cells
     * per segment over the box. */
    double w = hi.x - lo.x, h = hi.y - lo.y;
    double cell = fmax(2.0 * total / ns, sqrt(w * h / (4.0 * ns)));
    cell = fmax(cell, 1e-9 * fmax(fmax(w, h), 1.0));
    g->lo = lo;
    g->cell = cell;
    g->nx = (int)(w / cell) + 1;
    g->ny = (int)(h / cell) + 1;
    size_t ncell = (size_t)g->nx * (size_t)g->ny;
    g->start = calloc(ncell + 1, sizeof *g->start);
    if (!g->start)
        return -1;
    size_t count = 0;
    for (int s = 0; s < ns; s++) {
        int x0, y0, x1, y1;
        segment_cells(g, s, &x0, &y0, &x1, &y1);
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++)
                g->start[(size_t)y * g->nx + x + 1]++;
        count += (size_t)(x1 - x0 + 1) * (size_t)(y1 - y0 + 1);
    }
    g->items = malloc((count ? count : 1) * sizeof *g->items);
    int *fill = malloc(ncell * sizeof *fill);
    if (!g->items || !fill) {
        free(fill);
        segment_grid_free(g);
        return -1;
    }
    for (size_t c = 0; c < ncell; c++)
        g->start[c + 1] += g->start[c];
    memcpy(fill, g->start, ncell * sizeof *fill);
    for (int s = 0; s < ns; s++) {
        int x0, y0, x1, y1;
        segment_cells(g, s, &x0, &y0, &x1, &y1);
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++)
                g->items[fill[(size_t)y * g->nx + x]++] = s;
    }
    free(fill);
    return 0;
}

void segment_grid_free(segment_grid *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

static void visit_cell(const segment_grid *g, int x, int y, vec2 q, double *best2, int *seg, double *t)
{
    if (x < 0 || y < 0 || x >= g->nx || y >= g->ny)
        return;
    size_t c = (size_t)y * g->nx + x;
    for (int k = g->start[c]; k < g->start[c + 1]; k++) {
        int s = g->items[k];
        double ts, d2 = point_segment_distance2(q, g->p[s], g->p[g->n > 1 ? s + 1 : s], &ts);
        if (d2 < *best2) {
            *best2 = d2;
            *seg = s;
            *t = ts;
        }
    }
}

double segment_grid_nearest(const segment_grid *g, vec2 q, int *seg, double *t)
{
    int cx = (int)((q.x - g->lo.x) / g->cell), cy = (int)((q.y - g->lo.y) / g->cell);
    cx = cx < 0 ? 0 : (cx >= g->nx ? g->nx - 1 : cx);
    cy = cy < 0 ? 0 : (cy >= g->ny ? g->ny - 1 : cy);
    double best = INFINITY, bt = 0.0; /* squared */
    int bs = 0, rmax = g->nx > g->ny ? g->nx : g->ny;
    for (int r = 0; r <= rmax; r++) {
        if (r == 0)
            visit_cell(g, cx, cy, q, &best, &bs, &bt);
        else {
            for (int x = cx - r; x <= cx + r; x++) {
                visit_cell(g, x, cy - r, q, &best, &bs, &bt);
                visit_cell(g, x, cy + r, q, &best, &bs, &bt);
            }
            for (int y = cy - r + 1; y <= cy + r - 1; y++) {
                visit_cell(g, cx - r, y, q, &best, &bs, &bt);
                visit_cell(g, cx + r, y, q, &best, &bs, &bt);
            }
        }
        if (best <= (r * g->cell) * (r * g->cell))
            break;
    }
    if (seg)
        *seg = bs;
    if (t)
        *t = bt;
    return sqrt(best);
}
