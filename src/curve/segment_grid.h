/* Internal to the curve module: nearest-segment queries on an open polyline
 * through a uniform grid of buckets. */
#ifndef CELADON_CURVE_SEGMENT_GRID_H
#define CELADON_CURVE_SEGMENT_GRID_H

#include "celadon/vecmath.h"

typedef struct {
    const vec2 *p; /* the polyline (not owned) */
    int n;         /* points; segments are p[i] p[i+1], or the single point when n == 1 */
    vec2 lo;       /* grid origin */
    double cell;
    int nx, ny;
    int *start; /* nx*ny + 1 offsets into items */
    int *items; /* segment indices per cell */
} segment_grid;

/* Builds the grid over the polyline's bounding box. Returns 0 or -1. */
int segment_grid_build(segment_grid *g, const vec2 *p, int n);
void segment_grid_free(segment_grid *g);

/* Distance from q (anywhere) to the nearest segment; *seg and *t
 * (may be NULL) receive the segment and the parameter in [0,1] on it. */
double segment_grid_nearest(const segment_grid *g, vec2 q, int *seg, double *t);

#endif
