/* A solid of revolution seen in a synthetic photograph, with its exact image.
 *
 * The solid is { (X, Y, Z): 0 <= Y <= H, X² + Z² <= r(Y)² }, Y up its axis,
 * with r(Y) = H · radius_scale · synth_profile_radius(Y / H). The camera is
 * orthographic, looking at the solid from elevation e above its base plane
 * (Z points toward the camera when e = 0). A point projects to
 *     q = base_center + X·n + (Y cos e - Z sin e)·d
 * with d the image direction of the axis (unit, base toward rim: d = (sin t,
 * -cos t) for the in-plane tilt t, so a positive tilt leans the rim right)
 * and n = (-d.y, d.x) its right-hand normal. Image coordinates are x right,
 * y down; pixel (i, j) covers [i, i+1) x [j, j+1).
 *
 * The "axis frame" of an image point q is (s, w) = ((q - base_center)·n,
 * (q - base_center)·d). The disc at height h projects to the filled ellipse
 * centred at (0, h cos e) with half-axes r(h) across and r(h) sin e along
 * the axis, and the solid's image is the union of these ellipses; every line
 * w = const meets it in one interval [-X(w), X(w)] (all ellipses are centred
 * on the axis). X(w) = max over h of sqrt(r(h)² - ((w - h cos e)/sin e)²):
 * where the maximum is inside (0, H) the outline is the wall's occluding
 * contour, where it is at h = 0 or H it is the base or rim ellipse.
 *
 * A camera both tilted in-plane and elevated is not supported (the rows of a
 * tilted image would need X along slanted lines): synth_body_valid refuses it. */
#ifndef CELADON_TESTS_SYNTH_BODY_H
#define CELADON_TESTS_SYNTH_BODY_H

#include "celadon/profile.h"
#include "celadon/vecmath.h"

#include "synth_profile.h"

typedef struct {
    synth_profile profile;
    double height_px;     /* H: base to rim along the axis, px (the 3D height) */
    double radius_scale;  /* widens (>1) or narrows the profile; 1 draws it as defined */
    vec2 base_center;     /* image point of the base disc's centre */
    double tilt_deg;      /* in-plane rotation of the axis (only with elevation 0) */
    double elevation_deg; /* camera above the base plane, in [0, 60); 0 is level */
} synth_body;

/* 1 when the body can be drawn: H > 0, radius_scale > 0, elevation in
 * [0, 60), |tilt| < 45, and not both tilted and elevated. */
int synth_body_valid(const synth_body *b);

/* Exact radius at height h, px (the formula is evaluated outside [0, H] too). */
double synth_body_radius(const synth_body *b, double h);

/* d: unit image direction of the axis, base toward rim. */
vec2 synth_body_axis(const synth_body *b);

/* Image point of the rim disc's centre: base_center + H cos e · d. */
vec2 synth_body_rim_center(const synth_body *b);

/* X(w): the half-width of the image on the axis-frame line w, or -1 when the
 * line misses it. Exact: the maximum over h is bracketed on a 1 px grid and
 * each local maximum polished by golden section to 1e-7 px in h (an interior
 * maximum's value is then exact to ~1e-12 px², the cap ends are evaluated
 * exactly); with e = 0, X(w) = r(w) on [0, H]. */
double synth_body_half_width(const synth_body *b, double w);

/* The extent of the image along the axis: the lowest and highest w of its
 * outline (0 and H cos e when level; the caps' ellipses below and above). */
void synth_body_axis_extent(const synth_body *b, double *w_bottom, double *w_top);

/* Exact extent of the image on the horizontal line y (row j's centre line is
 * y = j + 0.5): returns 1 and the leftmost and rightmost x, or 0 when the
 * line misses it. Untilted: direct from X(w). Tilted (level camera): the
 * line is scanned at 0.5 px and both ends bisected to 1e-10 px, so slivers
 * under 0.5 px at the cap ends may be missed; it assumes one interval (true
 * for these profiles and tilts below ~20°). */
int synth_body_outline_x(const synth_body *b, double y, double *x_left, double *x_right);

/* The image's vertical extent: exact (the outline's highest and lowest y)
 * when untilted, a bound when tilted. */
void synth_body_y_extent(const synth_body *b, double *y_top, double *y_bottom);

/* The four corners where the outline leaves the base and rim ellipses for the
 * wall's contour (CORNER_* order): level, (±r(0), 0) and (±r(H), H) in the
 * axis frame; elevated, the point of the cap ellipse where the wall's
 * contour is tangent to it, at w = h cos e - r r' sin² e / cos e (h = 0 or H). */
void synth_body_corners(const synth_body *b, vec2 corners[CORNER_COUNT]);

/* The visible surface point under image point q, for shading: its height h
 * (px) and angle phi around the axis (0 faces the camera, positive toward
 * +n). Returns 1 on the wall, 2 on the rim disc (top), 0 when q is outside
 * (h and phi are then the nearest silhouette's: h = w / cos e clamped to
 * [0, H], phi = ±π/2). The wall point is found on a 2 px scan down the
 * viewing ray and bisected: exact to ~2e-6 px except where the ray crosses
 * the solid over less than the scan step (a grazing ray within a fraction of
 * a pixel of the outline, which then gets the fallback): shading only. */
int synth_body_surface(const synth_body *b, vec2 q, double *h, double *phi);

#endif
