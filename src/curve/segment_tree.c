/* A bounding-box tree over polyline segments: each inner node splits its
 * segments at the median of their midpoints along the longer side of its box;
 * leaves hold up to LEAF segments. A query descends nearer child first and
 * skips any node whose box is no nearer than the best segment so far, so it
 * costs about O(log n) whatever the scale of the data (a uniform grid does
 * not: a few far points stretch its cells over everything else). */
#include "segment_tree.h"

#include <stdlib.h>
#include <string.h>

enum { LEAF = 4, MAX_STACK = 128 };

static int n_segments(const segment_tree *t) { return t->n > 1 ? t->n - 1 : 1; }
static vec2 seg_a(const segment_tree *t, int s) { return t->p[s]; }
static vec2 seg_b(const segment_tree *t, int s) { return t->p[t->n > 1 ? s + 1 : s]; }

static double mid_along(const segment_tree *t, int s, int axis)
{
    vec2 a = seg_a(t, s), b = seg_b(t, s);
    return axis ? 0.5 * (a.y + b.y) : 0.5 * (a.x + b.x);
}

/* Quickselect: puts the k-th smallest midpoint (along axis) of idx[0..n-1] at k. */
static void select_median(const segment_tree *t, int *idx, int n, int k, int axis)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = mid_along(t, idx[(lo + hi) / 2], axis);
        int i = lo, j = hi;
        while (i <= j) {
            while (mid_along(t, idx[i], axis) < pivot)
                i++;
            while (mid_along(t, idx[j], axis) > pivot)
                j--;
            if (i <= j) {
                int tmp = idx[i];
                idx[i++] = idx[j];
                idx[j--] = tmp;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            break;
    }
}

/* Builds node `at` over seg[first .. first+count-1]. */
static void build(segment_tree *t, int at, int first, int count)
{
    segment_node *nd = &t->node[at];
    nd->lo = nd->hi = seg_a(t, t->seg[first]);
    for (int i = first; i < first + count; i++) {
        vec2 a = seg_a(t, t->seg[i]), b = seg_b(t, t->seg[i]);
        nd->lo = v2(fmin(nd->lo.x, fmin(a.x, b.x)), fmin(nd->lo.y, fmin(a.y, b.y)));
        nd->hi = v2(fmax(nd->hi.x, fmax(a.x, b.x)), fmax(nd->hi.y, fmax(a.y, b.y)));
    }
    if (count <= LEAF) {
        nd->first = first;
        nd->count = count;
        return;
    }
    int axis = nd->hi.y - nd->lo.y > nd->hi.x - nd->lo.x, half = count / 2;
    select_median(t, t->seg + first, count, half, axis);
    int child = t->n_nodes;
    t->n_nodes += 2;
    nd->first = child;
    nd->count = 0;
    build(t, child, first, half);
    build(t, child + 1, first + half, count - half);
}

int segment_tree_build(segment_tree *t, const vec2 *p, int n)
{
    memset(t, 0, sizeof *t);
    if (n < 1)
        return -1;
    t->p = p;
    t->n = n;
    int ns = n_segments(t);
    t->seg = malloc((size_t)ns * sizeof *t->seg);
    t->node = malloc((size_t)(2 * ns) * sizeof *t->node); /* a binary tree with <= ns leaves */
    if (!t->seg || !t->node) {
        segment_tree_free(t);
        return -1;
    }
    for (int s = 0; s < ns; s++)
        t->seg[s] = s;
    t->n_nodes = 1;
    build(t, 0, 0, ns);
    return 0;
}

void segment_tree_free(segment_tree *t)
{
    free(t->seg);
    free(t->node);
    memset(t, 0, sizeof *t);
}

/* Squared distance from q to segment a b and the parameter of the nearest point. */
static double point_segment_distance2(vec2 q, vec2 a, vec2 b, double *s)
{
    vec2 ab = v2_sub(b, a);
    double l2 = v2_dot(ab, ab), u = l2 > 0.0 ? v2_dot(v2_sub(q, a), ab) / l2 : 0.0;
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    *s = u;
    vec2 e = v2_sub(q, v2_add(a, v2_scale(ab, u)));
    return v2_dot(e, e);
}

static double box_distance2(const segment_node *nd, vec2 q)
{
    double dx = fmax(0.0, fmax(nd->lo.x - q.x, q.x - nd->hi.x));
    double dy = fmax(0.0, fmax(nd->lo.y - q.y, q.y - nd->hi.y));
    return dx * dx + dy * dy;
}

double segment_tree_nearest(const segment_tree *t, vec2 q, int *seg, double *s)
{
    double best = INFINITY, bs = 0.0; /* squared distance, parameter */
    int bseg = t->seg[0], stack[MAX_STACK], top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const segment_node *nd = &t->node[stack[--top]];
        if (box_distance2(nd, q) > best)
            continue;
        if (nd->count > 0) {
            for (int i = nd->first; i < nd->first + nd->count; i++) {
                double u, d2 = point_segment_distance2(q, seg_a(t, t->seg[i]), seg_b(t, t->seg[i]), &u);
                if (d2 < best)
                    best = d2, bs = u, bseg = t->seg[i];
            }
            continue;
        }
        /* Depth is ~log2(n) (median splits), so the stack cannot overflow. */
        int c = nd->first;
        double d0 = box_distance2(&t->node[c], q), d1 = box_distance2(&t->node[c + 1], q);
        stack[top++] = d0 <= d1 ? c + 1 : c; /* farther first: popped last */
        stack[top++] = d0 <= d1 ? c : c + 1;
    }
    if (seg)
        *seg = bseg;
    if (s)
        *s = bs;
    return sqrt(best);
}
