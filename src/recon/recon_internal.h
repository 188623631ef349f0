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

/* Fills gray (w*h floats, the signal the silhouette is measured on: alpha
 * when the image has a transparent background, else luminance). With alpha,
 * or a forced threshold (0..255; -1 = automatic), also fills mask (w*h, 1 =
 * object, before component filtering) and returns how; otherwise returns
 * RECON_MASK_GRAPH_CUT and leaves mask to the segmentation (segment.h).
 * *threshold_used: the forced threshold, else -1. */
recon_mask_mode recon_mask_threshold(const image_t *img, int threshold, float *gray, uint8_t *mask,
                                     int *threshold_used);

/* Keeps the largest 8-connected object, fills its holes (background parts not
 * 4-connected to the image border; counted) and then each row between its
 * outermost object pixels (a vessel's outline meets a row once on each side).
 * Returns the object's pixel count, or -1 when out of memory. */
long recon_mask_clean(uint8_t *mask, int w, int h, int *dropped_objects, int *holes_filled);

/* Labels the 8-connected components of mask: lab[p] (w*h ints) = 1..n, 0 for
 * background; *area (malloc'd, n + 1 entries, [0] unused) their pixel counts.
 * Returns n, or -1 when out of memory. */
int recon_mask_label(const uint8_t *mask, int w, int h, int *lab, long **area);

/* Morphological closing with a (2r+1)^2 square of a row-convex mask (one
 * interval per row, as recon_mask_clean leaves it), computed on the row
 * intervals: bridges slits narrower than 2r+1 px (a decoration line as light
 * as the backdrop that reaches the outline). Returns 0, or -1 when out of
 * memory. */
int recon_mask_close(uint8_t *mask, int w, int h, int r);
/* Opening, likewise: removes slivers thinner than 2r+1 px. */
int recon_mask_open(uint8_t *mask, int w, int h, int r);

/* ---- the vessel among the segmentation's objects (object_select.c) */

/* Keeps in the low-resolution mask only the vessel: the largest component
 * that is not a strip along the image border (a frame line, a caption bar).
 * Another component of a quarter of its size or more is a second object and
 * refuses the photo, unless it lies under the vessel and runs to the bottom
 * border: a stand, reported in *stand (what = RECON_PART_STAND, rows at low
 * resolution; row1 = -1 when none) and dropped. *dropped counts the removed
 * components. Returns RECON_OK or the refusal with its reason in why. */
recon_status recon_select_object(uint8_t *mask, int w, int h, int *dropped, recon_excluded *stand, char *why,
                                 size_t len);

/* ---- stands and shadows at the foot (support.c) */

struct recon_segmentation_s;
/* Cuts off the low-resolution vessel mask m a floor shadow joined to its
 * foot (its lowest pixels have no mirror image), then a stand under it (the
 * object runs into the bottom border, or steps out below the foot), each
 * found by a min-cut between seeds and kept only when the evidence holds
 * (support.c). Appends each part cut (rows at full resolution) to parts. A
 * stand's colours join the segmentation's not-object model. Returns 0, or -1
 * when out of memory. */
int recon_cut_support(struct recon_segmentation_s *seg, uint8_t *m, recon_excluded *parts, int max_parts,
                      int *n_parts);

/* ---- the full-resolution mask (refine.c) */

/* The vessel's mask at full resolution (img's size) from the low-resolution
 * one: coarse labels held fixed except on a band of full-resolution pixels
 * three cells wide around their outline, where the segmentation's energy is
 * minimised again. Returns 0, or -1 when out of memory. */
int recon_refine_mask(const image_t *img, const struct recon_segmentation_s *seg, const uint8_t *coarse,
                      uint8_t *mask);

/* ---- the caps: where the outline meets its top and bottom (caps.c) */

/* The four corners (CORNER_ order) of the closed contour in the frame of the
 * axis (origin on it, unit direction toward the top): on each side, the point
 * that turns most within the top (bottom) zone, half the radius of the
 * outline's last 5% of height deep; where none turns much more than the rest
 * of the zone (a dome), the extreme point, its pole. Returns 0, or -1 when out
 * of memory. */
int recon_find_caps(const vec2 *contour, int n, vec2 origin, vec2 dir, vec2 corners[CORNER_COUNT]);

/* ---- parts that are not revolved (parts.c) */

typedef struct {
    double h, r; /* axis frame, px */
    double y;    /* image row (centre line) the point was measured on */
    int gap;     /* background lies beyond this point on its row, then object again (a handle's loop) */
} recon_outline_point;

/* The profile's radius per row of the main side's outline (sorted by h),
 * written over main_side[].r: the mean of the two sides where they agree
 * within tol; over a handle's rows (a window, and its attachments) the side
 * that the handle does not hide; over the other runs of rows where they
 * disagree, the side that continues the rows around the run smoothly; NAN
 * (bridged) where no side serves. Appends one entry per such run to parts,
 * and gives the mean |r_main - r_other| over the rows both sides keep as a
 * fraction of the largest radius, and the fraction of rows not kept on both
 * sides. Returns 0, or -1 when out of memory. */
int recon_resolve_parts(recon_outline_point *main_side, int n, const recon_outline_point *other, int n_other,
                        int main_is_right, double tol, recon_excluded *parts, int max_parts, int *n_parts,
                        double *lr_disagreement, double *excluded_fraction);

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

#endif
