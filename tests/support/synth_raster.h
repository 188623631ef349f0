/* Anti-aliased coverage of synthetic shapes: a coverage buffer holds one
 * float per pixel in [0, 1] (row-major, width x height, pixel (i, j) covering
 * [i, i+1) x [j, j+1)). Each function unites its shape into the buffer
 * (cov = max(cov, coverage)), so a caller zeroes the buffer first and may
 * draw several disjoint shapes into one layer. */
#ifndef CELADON_TESTS_SYNTH_RASTER_H
#define CELADON_TESTS_SYNTH_RASTER_H

/* A shape that meets every horizontal line y in at most one interval:
 * returns 1 and its ends, or 0 when the line misses it. */
typedef int (*synth_span_fn)(const void *shape, double y, double *x_left, double *x_right);

/* Coverage of a span shape lying within y_top <= y <= y_bottom (pass
 * ±INFINITY when unknown) over pixel rows [row0, row1] (clipped to the
 * image): the part of each row within [y_top, y_bottom] is cut into
 * `subrows` equal strips, sampled on their middle lines; on each line the
 * exact interval is clipped to every pixel. Exact along x, midpoint rule
 * along y (error O(curvature / subrows²) per pixel), and exact for a
 * horizontal top or bottom edge at y_top or y_bottom. Returns 0, or -1 when
 * out of memory. */
int synth_cover_spans(float *cov, int width, int height, int row0, int row1, double y_top, double y_bottom,
                      int subrows, synth_span_fn span, const void *shape);

/* A signed distance bound: negative inside the shape, positive outside, and
 * |f(p) - f(q)| <= lipschitz · |p - q|. */
typedef double (*synth_sdf_fn)(const void *shape, double x, double y);

/* Coverage of an sdf shape over the pixel box [x0, x1] x [y0, y1] (inclusive,
 * clipped to the image) by n x n supersampling (n >= 8). A pixel whose centre
 * is farther from the boundary than the Lipschitz bound allows across its
 * half-diagonal is taken as wholly in or out without sampling. */
void synth_cover_sdf(float *cov, int width, int height, int x0, int y0, int x1, int y1, int n, double lipschitz,
                     synth_sdf_fn sdf, const void *shape);

/* Exact coverage of the axis-aligned rectangle [x0, x1) x [y0, y1). */
void synth_cover_rect(float *cov, int width, int height, double x0, double y0, double x1, double y1);

#endif
