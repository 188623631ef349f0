/* Internal to the curve module: nearest-segment queries on an open polyline
 * through a bounding-box tree over its segments. */
#ifndef CELADON_CURVE_SEGMENT_TREE_H
#define CELADON_CURVE_SEGMENT_TREE_H

#include "celadon/vecmath.h"

typedef struct {
    vec2 lo, hi;     /* bounds of the segments below */
    int first, count; /* leaf: seg[first .. first+count-1]; inner: count = 0, children first, first+1 */
} segment_node;

typedef struct {
    const vec2 *p; /* the polyline (not owned) */
    int n;         /* points; segments are p[i] p[i+1], or the single point when n == 1 */
    int *seg;      /* segment indices, grouped by leaf */
    segment_node *node;
    int n_nodes;
} segment_tree;

/* Builds the tree. Returns 0, or -1 (n < 1, allocation failure). */
int segment_tree_build(segment_tree *t, const vec2 *p, int n);
void segment_tree_free(segment_tree *t);

/* Distance from q to the nearest segment; *seg and *s (may be NULL) receive
 * the segment and the parameter in [0,1] on it. */
double segment_tree_nearest(const segment_tree *t, vec2 q, int *seg, double *s);

#endif
