/* The reconstructed profile of one vessel: profile.json (its fields:
 * docs/user-guide.md#profilejson; its frames: docs/conventions.md). */
#ifndef CELADON_PROFILE_H
#define CELADON_PROFILE_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/vecmath.h"

enum { CORNER_RIM_LEFT, CORNER_RIM_RIGHT, CORNER_BASE_LEFT, CORNER_BASE_RIGHT, CORNER_COUNT };

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
} profile_t;

/* The most elements an array of profile.json may hold (control points,
 * polyline, domains): far more than any photo gives (tens of control
 * points), and the SOR of this many builds in seconds. */
#define PROFILE_MAX_POINTS 100000

/* Writes atomically. Returns 0, or -1 with a one-line reason. */
int profile_write_json(const char *path, const profile_t *p, char *err, size_t errlen);
/* Reads and validates (version, finite numbers, a valid clamped cubic B-spline
 * that sor_profile_check accepts, increasing domains in [0,1], at most
 * PROFILE_MAX_POINTS elements per array). Returns 0, or -1 with a one-line
 * reason. */
int profile_read_json(const char *path, profile_t *p, char *err, size_t errlen);
void profile_free(profile_t *p);

#endif
