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
} profile_t;

/* The curvature domains of a profile (docs/user-guide.md#profilejson): each
 * piece within this many pixels of its chord and its tangent within this many
 * degrees of turning at a constant rate (curve_domains.h). */
#define PROFILE_DOMAIN_TOL_PX 0.25
#define PROFILE_DOMAIN_TOL_DEG 0.25

/* Writes atomically. Returns 0, or -1 with a one-line reason. */
int profile_write_json(const char *path, const profile_t *p, char *err, size_t errlen);
/* Reads and validates (version, finite numbers, a valid clamped cubic B-spline,
 * increasing domains in [0,1]). Only `version` and `bspline` are required:
 * every other field is checked when present; absent `domains` are computed
 * from the B-spline (PROFILE_DOMAIN_TOL_*), an absent `side` is "right", an
 * absent `axis.direction` (0, -1), the rest zero. Returns 0, or -1 with a
 * one-line reason. */
int profile_read_json(const char *path, profile_t *p, char *err, size_t errlen);
void profile_free(profile_t *p);

#endif
