/* Reconstruction from one photograph, up to the profile polyline: mask,
 * outer contour (Suzuki–Abe), Douglas–Peucker, 7x7 Gaussian, Shi–Tomasi
 * corners, axis of revolution (PCA + corner pairs), sub-pixel silhouette and
 * the one-sided profile polyline in the (r, h) frame of docs/conventions.md. */
#ifndef CELADON_RECON_H
#define CELADON_RECON_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/image.h"
#include "celadon/profile.h"
#include "celadon/vecmath.h"

typedef enum { RECON_SIDE_AUTO = 0, RECON_SIDE_LEFT, RECON_SIDE_RIGHT } recon_side;

typedef struct {
    int threshold;   /* 0..255 forces the gray threshold; -1 = automatic */
    recon_side side;
} recon_options;

/* How the mask was made. */
typedef enum {
    RECON_MASK_ALPHA = 0,      /* alpha channel, background transparent */
    RECON_MASK_BACKGROUND,     /* automatic: |gray - background model| above an Otsu threshold */
    RECON_MASK_GRAY_BELOW,     /* forced threshold, object darker than the background */
    RECON_MASK_GRAY_ABOVE      /* forced threshold, object lighter than the background */
} recon_mask_mode;

/* Why an image was refused (all of these are bad input: exit code 2). */
typedef enum {
    RECON_OK = 0,
    RECON_ERR_NO_OBJECT,
    RECON_ERR_TOUCHES_BORDER,
    RECON_ERR_CORNERS,
    RECON_ERR_SIZE,
    RECON_ERR_INTERNAL /* allocation failure and the like: exit code 1 */
} recon_status;

typedef struct {
    int width, height;
    uint8_t *mask;           /* width*height, 1 = vessel: largest object, closed (radius 4), holes
                                and rows filled, floor shadow trimmed at the foot */
    recon_mask_mode mask_mode;
    int threshold_used;      /* 0..255: on gray when forced, on |gray - background| when automatic;
                                -1 when the mask came from alpha */
    int dropped_objects;     /* other connected objects removed from the mask */
    int holes_filled;        /* background regions enclosed by the object, filled */
    int n_contour;
    vec2 *contour;           /* outer border, pixel centres, as traced (closed, no repeat) */
    int n_approx;
    vec2 *approx;            /* Douglas–Peucker approximation of the contour */
    vec2 corners[CORNER_COUNT]; /* snapped to the original contour */
    vec2 pca_mean;
    vec2 pca_axes[2];        /* unit eigenvectors, major first */
    double pca_eigenvalues[2];
    vec2 axis_origin, axis_direction; /* docs/conventions.md: origin at h = 0, unit toward the rim */
    double tilt_deg;         /* angle of the axis from the image vertical; positive: rim leans right */
    recon_side side_used;
    double edge_noise_px[2];  /* per side [0] left, [1] right: median |2nd difference| of the edge */
    double edge_contrast[2];  /* per side: 10th percentile of |fg - bg| along the edge */
    int axis_from_symmetry;   /* 1 when the axis was refined by left/right symmetry */
    int n_silhouette[2];     /* sub-pixel outline points, [0] left, [1] right, image coords */
    vec2 *silhouette[2];     /* at most one point per pixel row (y = row centre, x the sub-pixel
                                outline), rim corner row to base corner row, top to bottom */
    int n_polyline;
    vec2 *polyline;          /* (r, h), px, on side_used: (r, 0), the sub-pixel outline points with
                                0 < h < H in increasing h, (r, H); H = rim corners' height */
    double ms_image_processing;
} recon_result;

/* Runs the image stages on a decoded photo (opt may be NULL: automatic
 * threshold, automatic side). On failure returns the status, writes a one-line
 * reason (without the file name) to err and leaves res without arrays (the
 * scalars reached so far, e.g. threshold_used and dropped_objects, stay set);
 * either way recon_result_free releases it. See docs/algorithms-recon.md. */
recon_status recon_extract(const image_t *img, const recon_options *opt, recon_result *res, char *err,
                           size_t errlen);
void recon_result_free(recon_result *res);

/* Image point of a profile point (r, h) on the given side (+1 right, -1 left). */
vec2 recon_profile_to_image(vec2 axis_origin, vec2 axis_direction, double r, double h, int side_sign);

#endif
