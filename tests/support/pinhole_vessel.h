/* Synthetic vessel photographs through a pinhole camera, for the perspective
 * tests: the solid of revolution of a synth_vessel.h profile (height 1,
 * base at y = 0, axis along y) seen from a camera at finite distance, above
 * or below it, anti-aliased by exact area coverage along each of `subrows`
 * horizontal lines per pixel row.
 *
 * The solid is the union of its cross-section discs, so its image is the
 * union of their images, filled ellipses; on an image line each meets an
 * interval, and the solid's interval runs from the smallest left end to the
 * largest right end over the heights (a scan of 512 heights refined by
 * golden-section search; the union is one interval for these profiles).
 * Colours: fg, or with a checkerboard a pattern of bands in height x
 * sectors in the angle around the axis (fg / fg2) on the wall; fg on the
 * base cap, `mouth` on the mouth cap; sampled by casting 2x2 rays per
 * covered pixel (one colour: no rays).
 *
 * Camera (as in ../shared/data/synth-dev): at
 *     location = (0, look_at_height, 0) + distance (0, sin e, -cos e),
 * looking at (look_at_side, look_at_height, 0), right = up_world x forward
 * normalised, up = forward x right, then turned by roll_deg about the
 * optical axis (positive: the vessel's top leans right); square pixels,
 * principal point at the image centre:
 *     x = W/2 + f xc/zc,   y = H/2 - f yc/zc.
 * The angle phi of the texture convention (docs/conventions.md) is atan2(-z, x):
 * phi = pi/2 faces the camera. */
#ifndef CELADON_TESTS_PINHOLE_VESSEL_H
#define CELADON_TESTS_PINHOLE_VESSEL_H

#include <stdint.h>

#include "celadon/bspline.h"
#include "celadon/image.h"
#include "celadon/recon.h"
#include "celadon/recon_camera.h"
#include "celadon/vecmath.h"
#include "synth_vessel.h"

typedef struct {
    synth_shape shape;     /* the profile r(t), in units of the height ... */
    double (*radius)(double t); /* ... or this one when not NULL */
    int width, height;     /* px */
    double focal_px;
    double elevation_deg;  /* the camera looks down by this much (at look_at_side = 0) */
    double roll_deg;
    double distance;       /* camera to (0, look_at_height, 0), in vessel heights */
    double look_at_height; /* fraction of the height */
    double look_at_side;   /* sideways offset of the point looked at, heights (a yawed camera) */
    float fg[3], fg2[3], bg[3];
    float mouth[3];        /* the mouth cap: a vessel's inside seen from above is shaded otherwise */
    int checker_bands, checker_sectors; /* both > 0: the checkerboard */
    int subrows;           /* lines per pixel row (0: 24) */
} pinhole_params;

/* 600 x 800 px, focal length 2000 px (17 deg across), looking at
 * mid-height from the given elevation, at the distance where the vessel
 * spans about 70% of the image's height or width. */
pinhole_params pinhole_defaults(synth_shape shape, double elevation_deg);

/* Sets p->distance so that the larger of the vessel's height and width, at
 * the axis, is 70% of the image's (pinhole_defaults' framing), for p's
 * size, focal length and profile. */
void pinhole_frame(pinhole_params *p);

/* The distance of curve ((r, h), h from 0 to its rim) from p's true profile
 * over 3-97% of the height, mean and max, in units of the height. */
void pinhole_profile_error(const pinhole_params *p, const bspline_t *curve, double *mean, double *max);

/* Profile radius at t in [0, 1], in heights. */
double pinhole_radius(const pinhole_params *p, double t);

/* Image point of a vessel point (x, y, z), heights. */
vec2 pinhole_project(const pinhole_params *p, vec3 q);

/* The camera's position, heights (the point it looks at is
 * (look_at_side, look_at_height, 0)). */
vec3 pinhole_camera_location(const pinhole_params *p);

/* The elevation of the optical axis (degrees, + looking down). */
double pinhole_elevation(const pinhole_params *p);

/* The solid's extent on the image line y (continuous coordinate): 1 and
 * the leftmost and rightmost x, or 0 when the line misses it. */
int pinhole_line_extent(const pinhole_params *p, double y, double *x_left, double *x_right);

/* Draws into a fresh 3-channel image; mask (width x height, may be NULL)
 * receives 1 where a pixel is at least half covered. Returns 0, or -1 when
 * out of memory. */
int pinhole_draw(const pinhole_params *p, image_t *img, uint8_t *mask);

/* What recon_extract would find in the drawn image, with the geometry taken
 * from the truth instead of the corner and axis stages (whose perspective
 * corners, where the wall meets a nearly round base ellipse tangentially,
 * come and go with the elevation): mask (as drawn), the true corners (where
 * the wall's apparent contour meets the base and rim circles) and imaged
 * axis, the sub-pixel silhouettes of both sides measured on the image like
 * recon_extract's (recon_subpixel_edge on the colours, from the mask's
 * outermost pixel of each row, rim corner row to base corner row), the
 * right side as side_used and its profile polyline. Returns 0, or -1 when
 * out of memory; free with recon_result_free. */
int pinhole_extraction(const pinhole_params *p, const image_t *img, const uint8_t *mask, recon_result *res);

/* pinhole_draw, then pinhole_extraction: the photo and what the image
 * stages would find in it. Returns 0, or -1 when out of memory. */
int pinhole_photo(const pinhole_params *p, image_t *img, recon_result *res);

/* A drawn photo with what the image stages and the camera stage find. */
typedef struct {
    image_t img;
    recon_result res;
    recon_camera cam;
    recon_meridian mer;
} pinhole_shot;

/* pinhole_photo, then recon_camera_meridian (no options). Returns 0, or -1
 * with a reason in err; free with pinhole_shot_free either way. */
int pinhole_camera(const pinhole_params *p, pinhole_shot *s, char *err, size_t errlen);
void pinhole_shot_free(pinhole_shot *s);

#endif
