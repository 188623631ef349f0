/* The stages of recon_camera_meridian (src/perspective/), exposed for the
 * tests. Frames as in
 * include/celadon/recon_camera.h. */
#ifndef CELADON_PERSPECTIVE_INTERNAL_H
#define CELADON_PERSPECTIVE_INTERNAL_H

#include "celadon/recon_camera.h"

/* ---- conic_fit.c */

/* Signed orthogonal distance from p = (u, w) to the ellipse
 * (u/a)^2 + ((w - w0)/b)^2 = 1 (positive outside); *foot receives the
 * nearest ellipse point when foot is not NULL. a, b > 0. */
double recon_ellipse_distance(double w0, double a, double b, vec2 p, vec2 *foot);

/* Robust fit of an ellipse symmetric about the line u = 0 to the points
 * (u, w) of an arc of it on its upper half (half = +1: w >= w0), lower half
 * (-1) or anywhere (0): a consensus of exact three-point conics picks the
 * start, then Levenberg–Marquardt on the orthogonal distances from that
 * half, reweighted with Tukey's biweight (scale: 1.4826 MAD), rejects
 * outliers. When no ellipse fits, or the points show no significant
 * curvature (an F-test against the line), the result is the line w = w0
 * (b = 0, a half the points' u span). Returns 0, or -1 when there are fewer
 * than 6 points or memory runs out. */
int recon_fit_axis_ellipse(const vec2 *pts, int n, int half, recon_ellipse *out);

/* recon_fit_axis_ellipse, the line when the ellipse is wider than a_max:
 * a circle's whole image lies inside the silhouette, so an ellipse wider
 * than the silhouette is not the arc's circle (a nearly straight arc, a
 * circle near the camera's height, fits a flat ellipse of any width). */
int recon_fit_axis_ellipse_within(const vec2 *pts, int n, int half, double a_max, recon_ellipse *out);

/* ---- cross_section_arcs.c */

/* Sub-pixel points of the outline's top arc (the image of the rim circle,
 * between the rim corners) and bottom arc (the base circle, between the base
 * corners), image coordinates, one per pixel column: the area-based edge of
 * recon_subpixel_edge along the column, from the mask's topmost (bottommost)
 * pixel. *top and *bottom are malloc'd. Returns 0, or -1 when out of memory. */
int recon_outline_arcs(const image_t *img, const recon_result *res, vec2 **top, int *n_top, vec2 **bottom,
                       int *n_bottom);

/* The same measure on the columns i0..i1 (clamped to the image) on side
 * -1 (the outline's top) or +1 (its bottom): out (room for i1 - i0 + 1
 * points) receives a point per column where an edge is found. Returns their
 * number, or -1 when out of memory. */
int recon_outline_columns(const image_t *img, const recon_result *res, int i0, int i1, int side, vec2 *out);

/* ---- camera_from_sor.c */

/* Image point -> camera frame (u, w), and back. */
vec2 recon_camera_to_frame(const recon_camera *cam, vec2 image_pt);
vec2 recon_camera_to_image(const recon_camera *cam, vec2 frame_pt);

/* World point (X, Y, Z) -> camera frame. */
vec2 recon_camera_frame_of(const recon_camera *cam, vec3 p);

/* The viewing ray through a camera-frame point: origin and direction (world). */
ray3 recon_camera_ray(const recon_camera *cam, vec2 frame_pt);

/* The candidate horizons (vanishing lines of the cross-section planes,
 * w = w_h[k]) and squared focal lengths f2[k] of two ellipses symmetric
 * about the axis: the lines through their common complex points
 * u = +-i k, w = w_h, one of which holds the imaged circular points (the
 * image of the absolute conic through them gives f^2 = k^2 - w_h^2, the
 * principal point being the origin). Only candidates with f^2 > 0 and the
 * line outside both ellipses are kept. Returns their number (0..2). Two
 * views explain the two ellipses (and any outline between them) equally
 * well: one with the camera between the two circles' heights, whose
 * horizon separates the ellipses, one with the camera above (or below)
 * both. */
int recon_horizon_candidates(const recon_ellipse *base, const recon_ellipse *rim, double w_h[2], double f2[2]);

/* The image (w0, a, b) of the circle at height y with radius r (world). */
void recon_circle_image(const recon_camera *cam, double y, double r, double out[3]);

/* The circle (y, r) whose image best matches the ellipse (its centre, half
 * width and half height, weighted by their standard errors); returns the
 * weighted sum of squares, or INFINITY when no circle in front of the
 * camera fits. */
double recon_circle_of_ellipse(const recon_camera *cam, const recon_ellipse *e, double *y, double *r);

/* ---- cross_section_arcs.c (needs the camera frame) */

/* Whether the camera sees the top of the rim or into the mouth: the photo
 * then steps at the rim ellipse's near (lower) half, from the outer wall
 * below to the lip or the mouth above; from below the rim the wall goes on
 * across it. 1 yes (the camera is above the rim), 0 no, -1 when the ellipse
 * is too thin to tell (b under 1.5 px). */
int recon_rim_near_arc_visible(const image_t *img, const recon_camera *cam, const recon_ellipse *rim);

/* Builds the camera from the arcs (image coordinates) and recon's axis. */
int recon_camera_solve(const image_t *img, const recon_result *res, const recon_camera_options *opt,
                       const vec2 *top, int n_top, const vec2 *bottom, int n_bottom, recon_camera *cam, char *err,
                       size_t errlen);

/* ---- meridian.c */

/* The meridian point (r, Y) of the outline point p (camera frame) whose
 * outline tangent is t: on the viewing ray, where the plane through the ray
 * and t (the tangent plane of the surface there) has its normal in the
 * meridian plane of the point. Returns 0, or -1 when degenerate. */
int recon_envelope_point(const recon_camera *cam, vec2 p, vec2 t, double *r, double *y);

/* The meridian from the outline of res->side_used. Returns 0 or -1. */
int recon_meridian_from_outline(const recon_camera *cam, const recon_result *res, double smoothing_px,
                                recon_meridian *mer, char *err, size_t errlen);

#endif
