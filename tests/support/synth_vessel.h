/* Synthetic vessel photographs with exactly known geometry, for tests and demos.
 *
 * A vessel is a solid of revolution with an analytic profile r(h) (closed-form,
 * smooth) between a flat base (h = 0) and a flat rim (h = H), seen in
 * orthographic projection: its image is the set of points
 *     p = base_center + s·n + h·d,   0 <= h <= H,  |s| <= r(h),
 * with d the axis direction (unit, base toward rim) and n = (-d.y, d.x) the
 * right-hand normal of docs/conventions.md. The in-plane tilt turns d away from the
 * image vertical: d = (sin t, -cos t), so a positive tilt leans the rim to
 * the right.
 *
 * Pixel convention: pixel (i, j) covers [i, i+1) x [j, j+1), centre
 * (i + 0.5, j + 0.5). Drawing is anti-aliased by area coverage: each pixel is
 * split into `subrows` horizontal lines; on each the vessel's exact x-interval
 * (root-polished to 1e-9 px) is clipped to the pixel, so coverage is exact
 * along x and a midpoint rule along y. This is the level-camera case of
 * synth_body.h and synth_raster.h; synth_scene.h composes whole photographs
 * (backdrops, shadows, stands, handles, lids, elevated cameras) from them.
 *
 * Usage:
 *     synth_params p = synth_defaults(SYNTH_VASE, 300, 400);
 *     p.tilt_deg = 3;
 *     image_t img;  synth_draw(&p, &img);       // float image like image_read
 *     synth_truth t = synth_truth_of(&p);       // axis, corners
 *     double r = synth_radius(&p, h);            // exact profile, px
 *     synth_silhouette_x(&p, y, &xl, &xr);       // exact outline on line y
 *     synth_write("v.jpg", &img, 8, err, sizeof err);
 */
#ifndef CELADON_TESTS_SYNTH_VESSEL_H
#define CELADON_TESTS_SYNTH_VESSEL_H

#include <stddef.h>

#include "celadon/image.h"
#include "celadon/profile.h"
#include "celadon/vecmath.h"

/* The four shapes, in units of the height H (t = h/H in [0, 1]); they are the
 * first four synth_profile values (synth_profile.c holds the formulas):
 *  VASE    r = 0.17 + 0.09 sin(2π(0.85 t + 0.08)): belly, narrow neck, flared mouth
 *  BOWL    r = 0.50 + 0.70 t - 0.25 t²: wide and flaring, wider than tall
 *  BOTTLE  r = 0.08 + 0.17 (1 - tanh((t - 0.6)/0.07))/2: round body, narrow neck
 *  JAR     r = 0.32 + 0.04 sin(π t) - 0.02 t: nearly a cylinder */
typedef enum { SYNTH_VASE, SYNTH_BOWL, SYNTH_BOTTLE, SYNTH_JAR, SYNTH_SHAPE_COUNT } synth_shape;

typedef struct {
    synth_shape shape;
    int width, height;  /* image size, px */
    double height_px;   /* H: vessel height, base to rim, px */
    vec2 base_center;   /* image point of the axis at the base (h = 0) */
    double tilt_deg;    /* in-plane rotation of the axis; positive: rim leans right */
    float fg[3], bg[3]; /* vessel and background colours, encoded values in [0, 1] */
    int textured;       /* checkerboard of 10 height bands x 45° meridian stripes of fg and fg2 */
    float fg2[3];
    int rgba;           /* 4 channels: colour = fg (bg where uncovered), alpha = coverage */
    int subrows;        /* vertical samples per pixel row (0: 16) */
} synth_params;

/* Defaults: dark green vessel on a near-white background, untextured, RGB,
 * upright, centred, height_px chosen so the vessel fills ~70% of the image. */
synth_params synth_defaults(synth_shape shape, int width, int height);

typedef struct {
    vec2 axis_origin;    /* = base_center */
    vec2 axis_direction; /* unit, base toward rim */
    vec2 corners[CORNER_COUNT];
    double height_px;
    double tilt_deg;
} synth_truth;

synth_truth synth_truth_of(const synth_params *p);

/* Exact profile radius at height h in [0, H], px. */
double synth_radius(const synth_params *p, double h);

/* Exact extent of the vessel on the horizontal line y (continuous image
 * coordinate; row j's centre line is y = j + 0.5). Returns 1 and the
 * leftmost/rightmost x, or 0 when the line misses the vessel. Assumes the
 * vessel meets the line in one interval (true for these profiles and tilts
 * below ~20°); slivers under 0.5 px at the cap ends may be missed. */
int synth_silhouette_x(const synth_params *p, double y, double *x_left, double *x_right);

/* Draws into a fresh image (channels 3, or 4 with rgba; bits = 8). Returns 0,
 * or -1 when out of memory or the parameters are invalid. */
int synth_draw(const synth_params *p, image_t *img);

/* Writes img rounded to `bits` (8 or 16) per channel; the format follows the
 * extension (JPEG needs 8 bits, written at OpenImageIO's default quality).
 * Returns 0, or -1 with a reason in err. */
int synth_write(const char *path, const image_t *img, int bits, char *err, size_t errlen);

#endif
