/* The camera of a vessel photograph and the vessel's true meridian, from one
 * perspective photo (docs/algorithms-recon.md, "Perspective").
 *
 * A camera at finite distance, slightly above or below the vessel, sees the
 * base and the rim as ellipses, and the outline is the envelope of the imaged
 * cross-section circles, not the meridian. recon_camera_meridian fits the
 * outline's top and bottom arcs with ellipses, finds from them the vanishing
 * line of the cross-section planes and its imaged circular points, hence the
 * camera's focal length and elevation (square pixels, principal point at the
 * image centre, no lens distortion; the camera looks at the vessel's axis
 * from any side); then solves, for each outline point, which cross-section
 * circle the outline touches there (its height and radius): the meridian
 * r(h). With them, the texture is taken along the imaged cross-sections
 * and the overlay draws the fitted ellipses.
 *
 * Frames. The camera frame (u, w) is the image rectified so that the imaged
 * axis passes through the principal point (a virtual rotation of the camera
 * about its optical centre; none when it already does), with its origin at
 * the principal point, w along the imaged axis toward the rim and u to its
 * right, in pixels. (For the orthographic model the origin is the axis
 * origin of recon_result instead.) The world frame: Y along the vessel's
 * axis, the origin on the axis at the camera's height, the camera at
 * (0, 0, -D) with D = focal_px (so a world unit is about a pixel at the
 * axis), its optical axis pitched down by the elevation; X to the right. The
 * meridian's (r, h) has h = 0 at the base, 1 at the rim, r in the same
 * unit. */
#ifndef CELADON_RECON_CAMERA_H
#define CELADON_RECON_CAMERA_H

#include <stddef.h>

#include <stdint.h>

#include "celadon/bspline.h"
#include "celadon/image.h"
#include "celadon/recon.h"
#include "celadon/recon_texture.h"
#include "celadon/vecmath.h"

typedef struct {
    double fov_deg;         /* > 0: horizontal field of view over the image width (--fov); 0: unknown */
    double focal_35mm;      /* > 0: the photo's EXIF 35 mm equivalent focal length, mm; 0: none */
    double smoothing_px;    /* the meridian B-spline's largest deviation, px at the axis (0: 1 px) */
} recon_camera_options;

/* How the focal length was found. */
typedef enum {
    RECON_CAMERA_ELLIPSES = 0, /* from the imaged base and rim circles */
    RECON_CAMERA_EXIF,         /* from the EXIF 35 mm focal length; elevation from the ellipses */
    RECON_CAMERA_FLAG,         /* from the given field of view; elevation from the ellipses */
    RECON_CAMERA_ORTHOGRAPHIC  /* the ellipses are too flat to give a focal length: orthographic model */
} recon_camera_method;

/* An ellipse symmetric about the imaged axis, in the camera frame:
 * (u / a)^2 + ((w - w0) / b)^2 = 1; b = 0 is the line w = w0. */
typedef struct {
    double w0, a, b;
    double sigma_w0, sigma_a, sigma_b; /* standard errors of the fit */
    double rms_px, max_px;             /* orthogonal residuals of the inliers */
    int n_points, n_inliers;
} recon_ellipse;

typedef struct {
    recon_camera_method method;
    char note[200];          /* one line: why the orthographic model, or empty */
    double focal_px;         /* perspective: focal length in pixels; 0 when orthographic */
    double sigma_focal_px;   /* its standard error when it came from the ellipses, else 0 */
    double elevation_deg;    /* the optical axis below the horizontal (+: looking down) */
    double sigma_elevation_deg;
    double roll_deg;         /* in-plane rotation of the imaged axis from the image vertical (+: rim leans right) */
    vec2 principal_point;    /* image centre */
    /* image -> camera frame: the rectifying homography (row-major 3x3,
     * identity when the imaged axis passes through the principal point),
     * then the frame's origin and unit up vector in the rectified image. */
    double rectify[9], unrectify[9]; /* unrectify: the inverse */
    vec2 origin, up;
    double pitch;            /* radians: the elevation of the rectified camera */
    recon_ellipse base, rim; /* the fitted outline arcs */
    double base_y, base_r, rim_y, rim_r; /* the base and rim circles, world units */
} recon_camera;

typedef struct {
    bspline_t curve;         /* clamped cubic, (r, h), h = 0 at the base, 1 at the rim */
    int n_domains;
    double *domains;         /* curvature domains of curve, as profile.json's */
    int n_points;
    vec2 *points;            /* the envelope samples (r, h) the curve was fitted to, base to rim */
    double height_px;        /* base-to-rim height in world units (about px at the axis) */
} recon_meridian;

/* Camera and meridian from the photo and what recon_extract found in it
 * (axis, corners, mask, sub-pixel silhouettes, side_used). opt may be NULL
 * (no focal length known, 1 px smoothing). Returns 0; or -1 with a one-line
 * reason in err (the outline's arcs could not be measured or fitted, the
 * meridian is degenerate, out of memory), leaving both outputs empty. When
 * the ellipses cannot give a focal length and none is given, the camera is
 * orthographic (method RECON_CAMERA_ORTHOGRAPHIC, the reason in note): with
 * a level camera that gives the image outline itself as the meridian.
 * Free the meridian with recon_meridian_free. */
int recon_camera_meridian(const image_t *img, const recon_result *res, const recon_camera_options *opt,
                          recon_camera *cam, recon_meridian *mer, char *err, size_t errlen);
void recon_meridian_free(recon_meridian *m);

/* Fills profile.json's camera and meridian blocks of p (has_camera,
 * camera, has_meridian, meridian, meridian domains) from a result of
 * recon_camera_meridian. The meridian's curve and domains are borrowed,
 * not copied: p must not outlive mer, and profile_free(p) must not run on
 * them (clear has_meridian first, as for the other borrowed arrays). */
void recon_camera_fill_profile(const recon_camera *cam, const recon_meridian *mer, profile_t *p);

/* Focal length in pixels of a photo width x height for a horizontal field of
 * view (degrees), and for an EXIF 35 mm equivalent focal length (mm; by the
 * diagonal, 43.27 mm on the 35 mm frame). */
double recon_focal_from_fov(int width, double fov_deg);
double recon_focal_from_35mm(int width, int height, double focal_35mm);

/* Image point of the vessel point at meridian height h, radius r (meridian
 * units) and angle phi around the axis (phi = pi/2 faces the camera, 0 is to
 * the right: the texture convention of docs/conventions.md). */
vec2 recon_camera_project(const recon_camera *cam, const recon_meridian *mer, double r, double h, double phi);

/* 1 when the camera sees the outside of the wall at that point: the surface
 * normal (from the meridian's slope dr/dh there) faces the camera by more
 * than min_cos (the cosine between the normal and the direction to the camera). */
int recon_camera_sees(const recon_camera *cam, const recon_meridian *mer, double r, double h, double phi,
                      double dr_dh, double min_cos);

/* ---- the texture by the camera (recon_texture_camera.c) */

/* Builds the texture by the camera (recon_camera.h): row j is the meridian
 * height v = 1 - (j + 0.5) / height, column i the angle phi = pi (1 - u),
 * u = (i + 0.5) / width (docs/conventions.md: 0 the left outline, 0.5 facing the
 * camera, 1 the right one), and each texel the photo's colour (bilinear)
 * where the camera images the wall point (r(v), v, phi): the imaged
 * cross-section ellipses, not horizontal scanlines (those are its special
 * case for a level orthographic camera). Texels the camera did not see (the
 * wall turned away from it, or so obliquely that they lie within half a
 * pixel of the outline) have seen = 0 and the colour of the nearest seen
 * texel of their row (of the nearest row with one, if none). One row per
 * pixel of the meridian's height, the widest cross-section's width in
 * pixels. With parts (the extraction of the photo; NULL for none), what the
 * parts left out of the profile cover is filled from the body
 * (recon_texture_covered_rows, recon_texture_fill_parts: a row's image row
 * and its body's outline are where the camera images its generators). Returns 0, or -1 with a one-line reason in err. */
int recon_texture_from_camera(const image_t *photo, const recon_camera *cam, const recon_meridian *mer,
                              const recon_result *parts,
                              recon_texture_t *out, char *err, size_t errlen);

/* ---- the overlay's perspective layers (overlay_camera.c): what
 * recon_camera_meridian found, drawn over overlay_render's picture */

typedef enum {
    OVERLAY_CAMERA_ELLIPSES, /* the fitted base and rim ellipses, whole */
    OVERLAY_CAMERA_SECTIONS, /* cross-sections of the meridian: the near half solid, the far half dashed */
    OVERLAY_CAMERA_LAYER_COUNT
} overlay_camera_layer;

/* Okabe–Ito bluish green and sky blue, apart from overlay_colours. */
extern const uint8_t overlay_camera_colours[OVERLAY_CAMERA_LAYER_COUNT][3];

/* Draws both layers onto rgb (8-bit RGB, width x height, row-major: the
 * buffer overlay_render returns) in overlay_line_width: the two ellipses,
 * then the imaged cross-sections at n_sections heights evenly spaced
 * between the base and the rim (1/(n+1), ..., n/(n+1) of the meridian's
 * height). Returns 0, or -1 when out of memory (rgb unchanged). */
int overlay_draw_camera(uint8_t *rgb, int width, int height, const recon_camera *cam, const recon_meridian *mer,
                        int n_sections);

#endif
