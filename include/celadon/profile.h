/* The reconstructed profile of one vessel: profile.json (its fields:
 * docs/user-guide.md#profilejson; its frames: docs/conventions.md). */
#ifndef CELADON_PROFILE_H
#define CELADON_PROFILE_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

enum { CORNER_RIM_LEFT, CORNER_RIM_RIGHT, CORNER_BASE_LEFT, CORNER_BASE_RIGHT, CORNER_COUNT };

/* A fitted outline arc of a perspective reconstruction: the ellipse of the
 * base (conics[0]) or the rim (conics[1]) in the camera's frame. */
typedef struct {
    vec2 center_px;           /* the ellipse's centre, image point */
    double semi_axes_px[2];   /* across and along the imaged axis */
    double rms_px, max_px;    /* orthogonal residuals of the inliers */
    int points, inliers;
} profile_conic;

/* The camera of a perspective reconstruction (profile.json "camera"). */
typedef struct {
    char method[16];          /* "ellipses", "exif", "flag" or "orthographic" */
    double elevation_deg;     /* the optical axis below the horizontal */
    double focal_px;          /* 0 for the orthographic model */
    double roll_deg;
    vec2 principal_point;
    char note[200];           /* why the orthographic model, or empty */
    profile_conic conics[2];  /* base, rim */
} profile_camera;

typedef struct {
    char source_path[4096];
    int source_width, source_height;
    vec2 axis_origin;    /* image point on the axis at h = 0 (the base) */
    vec2 axis_direction; /* unit, base toward rim */
    double tilt_deg;
    vec2 corners[CORNER_COUNT];
    char side[8];        /* "left" or "right" */
    int n_polyline;
    vec2 *polyline;      /* (r, h) in pixels */
    bspline_t curve;     /* clamped cubic, u from base (0) to rim (1), (r, h) in pixels */
    int n_domains;
    double *domains;     /* increasing u values from 0 to 1 */
    double err_curve_to_polyline, err_polyline_to_curve; /* one-sided Hausdorff, px */
    int contour_points;
    double ms_image_processing, ms_bspline, ms_texture, ms_mesh;
    /* What the reconstruction left out of the surface of revolution (written
     * by `reconstruct`, ignored by readers): a stand, a shadow, a handle...,
     * the image rows it spans, its side (-1 left, +1 right, 0 both) and what
     * the profile takes there ("none", "left", "right", "bridged"). */
    int n_excluded;
    struct {
        char what[16];
        int rows[2];
        int side;
        char profile[12];
    } excluded[16];
    /* The quality gate's figures (present = 0: none recorded). */
    struct {
        int present, passed;
        double hausdorff_px, lr_disagreement, excluded_fraction;
        unsigned border_contact; /* bits: 1 top, 2 bottom, 4 left, 8 right */
    } quality;
    /* Perspective reconstructions only (has_camera, has_meridian: 0 when
     * the file has no such block). */
    int has_camera;
    profile_camera camera;
    int has_meridian;
    bspline_t meridian;       /* the true profile, clamped cubic, (r, h) with h 0 at the base and 1 at the rim */
    int n_meridian_domains;
    double *meridian_domains; /* its curvature domains, increasing u values from 0 to 1 */
} profile_t;

/* The most elements an array of profile.json may hold (control points,
 * polyline, domains): far more than any photo gives (tens of control
 * points), and the SOR of this many builds in seconds. */
#define PROFILE_MAX_POINTS 100000

/* The curvature domains of a profile (docs/user-guide.md#profilejson): each
 * piece within this many pixels of its chord and its tangent within this many
 * degrees of turning at a constant rate (curve_domains.h). */
#define PROFILE_DOMAIN_TOL_PX 0.25
#define PROFILE_DOMAIN_TOL_DEG 0.25

/* Writes atomically. Returns 0, or -1 with a one-line reason. */
int profile_write_json(const char *path, const profile_t *p, char *err, size_t errlen);
/* The text profile_write_json writes, malloc'd (the caller frees it);
 * NULL with a one-line reason. */
char *profile_json_text(const profile_t *p, char *err, size_t errlen);

/* The radius of the profile's shape (profile_shape) at height h, both in the
 * units of a mesh revolved to height 1 (mesh_revolve: the rim at 1, the
 * base's height as the curve has it, normally 0): the largest radius where
 * the shape crosses that height (the outer wall, where a lid or an inner
 * lip crosses it too). Returns 0, or -1 when no point of the shape is at
 * height h. */
int profile_radius(const profile_t *p, double h, double *radius);

/* Reads and validates (version, finite numbers, a valid clamped cubic B-spline
 * that sor_profile_check accepts, increasing domains in [0,1], at most
 * PROFILE_MAX_POINTS elements per array). Only `version` and `bspline` are
 * required: every other field is checked when present; absent `domains` are
 * computed from the B-spline (PROFILE_DOMAIN_TOL_*), an absent `side` is
 * "right", an absent `axis.direction` (0, -1), the rest zero. Returns 0, or
 * -1 with a one-line reason. */
int profile_read_json(const char *path, profile_t *p, char *err, size_t errlen);
void profile_free(profile_t *p);

/* The profile a surface of revolution is built from: the meridian when the
 * file has one (a perspective reconstruction: the vessel's true profile),
 * else the B-spline (the image outline); *domains and *n_domains receive
 * its curvature domains. Both run from the base (u = 0) to the rim (u = 1)
 * and are scaled by whoever revolves them so that the rim is at the height
 * asked for, so their units (height, pixels) do not matter. `mesh` and the
 * renderer's `sor` shape take the profile from here. */
const bspline_t *profile_shape(const profile_t *p, const double **domains, int *n_domains);

#endif
