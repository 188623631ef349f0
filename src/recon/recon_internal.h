/* The stages of recon_extract, exposed for the tests (the sub-pixel edge is
 * in recon/recon.h, the folder's interface). Image buffers are row-major,
 * width w, height h; masks hold 0/1 bytes. */
#ifndef CELADON_RECON_INTERNAL_H
#define CELADON_RECON_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/recon.h"
#include "recon/recon.h"
#include "segment/segment.h"

/* ---- the caps: where the outline meets its top and bottom (caps.c) */

/* The four corners (CORNER_ order) of the closed contour in the frame of the
 * axis (origin on it, unit direction toward the top): on each side, the point
 * that turns most within the top (bottom) zone, half the radius of the
 * outline's last 5% of height deep (at the top, twice the base's ellipse's
 * b/a times that radius when deeper: a rim's near half seen from above); where none turns much more than the rest
 * of the zone (a dome), the extreme point, its pole; also at the top when it
 * lies deeper below the top than the base's ellipse allows (a knob), unless
 * base_is_cut (a stand or a shadow cut it) or the photo img (may be NULL)
 * shows an open mouth there (recon_mouth_open). A corner that turns most is
 * then found again on outline[s] (s 0 left, 1 right: the sides' sub-pixel
 * outlines, n_outline[s] points, one per row) by recon_corner_knot, except
 * at a base that is cut. Returns 0, or -1 when out of memory. */
int recon_find_caps(const image_t *img, const vec2 *contour, int n, const vec2 *const outline[2],
                    const int n_outline[2], vec2 origin, vec2 dir, int base_is_cut, vec2 corners[CORNER_COUNT]);

/* 1 when the closed contour's top (its highest point h_top along dir from
 * origin, on the axis; its points down to depth px below it searched) is the
 * far arc of an ellipse about the axis whose near arc shows in img as a step
 * (the lip or the interior above it, the outer wall below): an open mouth
 * seen from above, whose rim is that ellipse (its half-axes across and
 * along the axis in ellipse[0], ellipse[1]; its top on the contour's; mouth.c).
 * 0 for a dome, a knob, or an arc that is no ellipse. */
int recon_mouth_open(const image_t *img, const vec2 *contour, int n, vec2 origin, vec2 dir, double h_top,
                     double depth, double ellipse[2]);

/* The corner *corner (a point of the closed contour, on the side of the axis
 * of outline[0..n), that side's sub-pixel outline, one point per row) moved
 * to where that outline leaves the wall's line onto its end's ellipse
 * (toward_top: the rim, else the base), the knot of a quadratic spline fitted
 * to the outline's points within window px of its height (corner_knot.c).
 * Returns 1 when moved, 0 when the outline shows no such junction there (or
 * out of memory). */
int recon_corner_knot(const vec2 *outline, int n, vec2 origin, vec2 dir, int toward_top, double window,
                      vec2 *corner);

/* ---- whether the mask can be a surface of revolution's silhouette
 * (sor_silhouette.c) */

/* The two figures a surface of revolution's silhouette has at zero, for
 * mask and its axis (origin on it, unit direction toward the top), as
 * fractions of the object's height along the axis.
 * recon_axis_gap: the rows (from the first that holds the axis in the
 * object, downward) whose axis pixel is backdrop open to the outside with
 * the object on both sides of it; on the object as segmented, before any
 * gap is filled. Returns 0, or -1 when out of memory.
 * recon_base_asymmetry: how much farther the lowest 3% of the object reach
 * on one side of the axis than on the other; about the body's axis (from
 * its outline's mirror symmetry: a part standing out on one side over most
 * of the height moves the rows' midpoints). */
int recon_axis_gap(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir, double *axis_gap);
double recon_base_asymmetry(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir);

/* ---- parts that are not revolved (parts.c) */

typedef struct {
    double h, r; /* axis frame, px */
    double y;    /* image row (centre line) the point was measured on */
    int gap;     /* background lies beyond this point on its row, then object again (a handle's loop) */
} recon_outline_point;

/* The points of one side's outline sil[0..n) (side -1 left, +1 right; gap as
 * recon_outline_point's) in the frame of the axis (origin on it at the base,
 * unit direction toward the rim), between heights 0 and H exclusive, sorted
 * by height (a point not above the last is dropped). Returns their count. */
int recon_outline_points(const vec2 *sil, const uint8_t *gap, int n, vec2 origin, vec2 dir, int side, double H,
                         recon_outline_point *out);

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

/* How recon_axis_symmetry reads the two outlines. */
typedef struct {
    int suspect;     /* +1 when the left outline may be washed out (a highlight along it lowers its edge contrast;
                      * its outline then lies inside the true one), -1 for the right, 0 for neither */
    double noise_px; /* the clean side's edge noise (sigma), px */
    int limb;        /* the suspect side's points are its limb (recon_limb_points): one per row, pixel-rough,
                      * the true outline on scattered rows only */
} recon_symmetry_fit;

/* Refines the axis (origin on it, unit direction toward the rim) so that the
 * left and right outlines are mirror images: Gauss–Newton on offset and angle
 * with trimmed residuals, between the heights h_lo and h_hi. When most rows
 * are not symmetric, the suspect side is taken as washed out and the fit
 * rests on the rows that a one-sided consensus finds symmetric (at least 15%
 * of them; for a limb at least 20 rows that give the tilt within 0.05 deg);
 * *washed_side is then the suspect side, else 0, whether or not the axis
 * moves. Returns 1 when refined, 0 when the outlines disagree too much to
 * trust (axis unchanged). */
int recon_axis_symmetry(const vec2 *left, int nl, const vec2 *right, int nr, vec2 *origin, vec2 *dir, double h_lo,
                        double h_hi, const recon_symmetry_fit *fit, int *washed_side);

/* ---- the limb (limb.c) */

/* Where a washed-out side really ends. A highlight can make a glossy glaze
 * as light as the backdrop (clipped white) for many pixels inside the true
 * outline, so the mask's outline lies inside it; yet the object's last
 * pixel (the limb, a thin line of glaze seen edge-on, the anti-aliased
 * border) often still departs from the backdrop. Per row that has body on
 * both sides (ext: row_extents' layout, [0, h) left body, [h, 2h) right),
 * the outermost pixel on each side whose colour differs from the backdrop
 * beyond it (the pixel 12 px plus a tenth of the row's width outside the
 * farther of the side's mask extent and the other side's mirror image
 * across the axis origin + t dir) by more than t = max(delta, twice the
 * backdrop's departure 3-9 px beside the clean side's edge, 90th percentile
 * over its rows: JPEG ringing); the mask's extent where none does. The
 * outline's sub-pixel position in that pixel, one point per row on the
 * clean side; on the washed-out side only where the departure is sharp, as
 * an outline is (a highlight's soft inner boundary is not). washed: +1 when
 * the left side is washed out, -1 the right. buf: as recon_signal_row's.
 * Returns 0, or -1 when out of memory. */
int recon_limb_points(const image_t *img, const float *gray, int alpha, const int *ext, vec2 origin, vec2 dir,
                      int washed, double delta, float *buf, vec2 *left, int *nl, vec2 *right, int *nr);

#endif
