/* The stages of recon_extract, exposed for the tests. Image buffers are
 * row-major, width w, height h; masks hold 0/1 bytes. */
#ifndef CELADON_RECON_INTERNAL_H
#define CELADON_RECON_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/recon.h"

/* On x86-64 the build targets the baseline (SSE2); the whole-row filter
 * loops also get an AVX2 clone, picked at load time when the CPU has it
 * (GCC/Clang function multiversioning). No FMA: both clones round alike. */
#if defined(__x86_64__) && defined(__GNUC__)
#define RECON_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RECON_VECTOR_CLONES
#endif

/* ---- mask (mask.c) */

/* Fills gray (w*h floats, the signal the silhouette is measured on: alpha when
 * the image has a transparent background, else luminance) and mask (w*h, 1 =
 * object, before component filtering). threshold: -1 = automatic. Returns the
 * mode used and writes the 0..255 threshold to *threshold_used (-1 for alpha). */
recon_mask_mode recon_mask_threshold(const image_t *img, int threshold, float *gray, uint8_t *mask,
                                     int *threshold_used);

/* Keeps the largest 8-connected object, fills its holes (background parts not
 * 4-connected to the image border; counted) and then each row between its
 * outermost object pixels (a vessel's outline meets a row once on each side).
 * Returns the object's pixel count, or -1 when out of memory. */
long recon_mask_clean(uint8_t *mask, int w, int h, int *dropped_objects, int *holes_filled);

/* Morphological closing with a (2r+1)^2 square of a row-convex mask (one
 * interval per row, as recon_mask_clean leaves it), computed on the row
 * intervals: bridges slits narrower than 2r+1 px (a decoration line as light
 * as the backdrop that reaches the outline). Returns 0, or -1 when out of
 * memory. */
int recon_mask_close(uint8_t *mask, int w, int h, int r);
/* Opening, likewise: removes slivers thinner than 2r+1 px. */
int recon_mask_open(uint8_t *mask, int w, int h, int r);

/* Floor shadows are soft and touch the vessel only at its foot: on the rows
 * of the object's lowest eighth, top to bottom, an end of the row that juts
 * out more than 3 px past the (trimmed) row above moves inward to the first
 * sharp step along the row (over two pixels, at least step; none: it stays). A vessel's outline changes smoothly from row to
 * row; a shadow that joined the mask does not. Returns 1 when anything
 * changed. */
int recon_mask_trim_soft(uint8_t *mask, const float *gray, int w, int h, float step);

/* ---- Suzuki–Abe border following (border_follow.c) */

typedef struct {
    int start, count; /* points[start .. start+count) */
    int is_hole;
    int parent;       /* index of the enclosing border, -1 for the image frame */
} recon_border;

typedef struct {
    int n_borders;
    recon_border *borders;
    int n_points;
    int *points; /* x, y pairs (pixel indices) in tracing order */
} recon_border_set;

/* Traces every border of the 8-connected objects of mask (Suzuki & Abe 1985,
 * algorithm 1), outer borders and hole borders, with their hierarchy.
 * Returns 0, or -1 when out of memory. */
int recon_border_follow(const uint8_t *mask, int w, int h, recon_border_set *out);
void recon_border_set_free(recon_border_set *s);

/* ---- Douglas–Peucker (douglas_peucker.c) */

/* Approximates the closed polygon pts[0..n) so that every input point lies
 * within eps of the output polygon. Writes vertex indices (increasing) to
 * keep and returns their count (>= 1; 2 or more when n >= 2). */
int recon_douglas_peucker_closed(const vec2 *pts, int n, double eps, int *keep);

/* ---- 7x7 Gaussian and Shi–Tomasi (shi_tomasi.c) */

/* 7x7 Gaussian blur (sigma 1.4, OpenCV's default for that size), separable,
 * replicated border. tmp: 8 w + 6 floats of scratch. In place on img. */
void recon_gaussian7(float *img, float *tmp, int w, int h);

/* Shi–Tomasi response: the smaller eigenvalue of the structure tensor of 3x3
 * Sobel gradients summed over a 3x3 window, at every pixel (in float).
 * Returns 0, or -1 when out of memory. */
int recon_shi_tomasi(const float *img, int w, int h, float *response);
/* The same response at one pixel (replicated border). */
float recon_shi_tomasi_at(const float *img, int w, int h, int x, int y);

/* ---- corners (corners.c) */

/* Finds the four corners on the closed contour (pixel centres): rasterises the
 * Douglas–Peucker approximation (approx_idx into contour) around each vertex,
 * blurs it (7x7 Gaussian) and takes the Shi–Tomasi response there; among the
 * convex, corner-like vertices of each quadrant of the PCA frame (up =
 * axis_up, split at mean) picks the highest (rim) or lowest (base), then the
 * outermost near that height; snapped to the contour point of sharpest turn.
 * Returns a bit set of the corners found (bit q for CORNER_q; all: 0xF);
 * corner_idx holds contour indices. */
int recon_find_corners(const vec2 *contour, int n, const int *approx_idx, int n_approx, vec2 mean, vec2 axis_up,
                       int corner_idx[CORNER_COUNT]);

/* ---- vessel shape (vessel_check.c) */

/* Checks that the corners (CORNER_ order) and the final axis (unit direction
 * toward the rim) describe a vessel: axis within 30° of the image vertical;
 * rim and base corner pairs distinct, level within 10° and at the top
 * (bottom) fifth of the outline; the outline not widening right below both
 * rim corners (a disc, an ellipse, a rounded box). ext: the mask's outermost
 * object pixel per row, left (ext[0..h)) and right (ext[h..2h)), -1 where
 * none. Returns 1, or 0 with the reason in why. */
int recon_check_vessel(const vec2 *corners, vec2 dir, const vec2 *contour, int n, const int *ext,
                       int h, char *why, size_t len);

/* ---- axis (axis.c) */

/* PCA of points: mean, unit eigenvectors (major first) and eigenvalues. */
void recon_pca(const vec2 *pts, int n, vec2 *mean, vec2 axes[2], double eig[2]);

/* Refines the axis (origin on it, unit direction toward the rim) so that the
 * left and right outlines are mirror images: Gauss–Newton on offset and angle
 * with trimmed residuals, between the heights h_lo and h_hi. suspect: +1 when
 * the left outline may be washed out (a highlight along it lowers its edge
 * contrast; its outline then lies inside the true one), -1 for the right, 0
 * for neither. When most rows are not symmetric, the suspect side is taken
 * as washed out and the fit rests on the rows that a one-sided consensus
 * finds symmetric; *washed_side is then the suspect side, else 0. Returns 1
 * when refined, 0 when the outlines disagree too much to trust (axis
 * unchanged). */
int recon_axis_symmetry(const vec2 *left, int nl, const vec2 *right, int nr, vec2 *origin, vec2 *dir, double h_lo,
                        double h_hi, int suspect, double noise_px, int *washed_side);

/* ---- sub-pixel silhouette (subpixel_edge.c) */

typedef struct {
    double x;        /* edge position on the row's centre line, px */
    double contrast; /* |fg - bg| at the edge, signal units */
    int ok;
} recon_edge;

/* Sub-pixel position of the outermost edge of the object on row j, on side
 * (-1 left, +1 right), from the gray ramp: the fraction of each pixel covered
 * by the object, (v - bg)/(fg - bg), summed over the pixels the edge crosses,
 * is the object's length in that window (exact for a straight edge under box
 * anti-aliasing). The search starts at i0, the mask's outermost object pixel
 * on that side of the row; slope is the outline's dx per row (from the
 * neighbouring rows); delta the smallest difference from the background that
 * counts as object. */
recon_edge recon_subpixel_edge(const float *gray, int w, int h, int j, int i0, int side, double slope, double delta);
/* The same without following a glaze's drift toward the backdrop: fg is the
 * pixel just inside. For the outline's top and bottom arcs, where a thin
 * band of another colour (the lip, the mouth seen from above) lies just
 * inside the edge and the drift rule would read it as a glaze. */
recon_edge recon_subpixel_edge_flat(const float *gray, int w, int h, int j, int i0, int side, double slope,
                                    double delta);

#endif
