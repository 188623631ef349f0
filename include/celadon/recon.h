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
    const float *object_prior; /* NULL, or the object's probability at each pixel (width * height), a term
                                  of the segmentation's energy (docs/algorithms-recon.md, "Learned object prior") */
} recon_options;

/* How the mask was made. */
typedef enum {
    RECON_MASK_GRAPH_CUT = 0,  /* automatic: colour models of object and backdrop, min-cut with a symmetry prior */
    RECON_MASK_ALPHA,          /* alpha channel, background transparent */
    RECON_MASK_GRAY_BELOW,     /* forced threshold, object darker than the background */
    RECON_MASK_GRAY_ABOVE      /* forced threshold, object lighter than the background */
} recon_mask_mode;

/* Why an image was refused (all of these are bad input: exit code 2). */
typedef enum {
    RECON_OK = 0,
    RECON_ERR_NO_OBJECT,
    RECON_ERR_SHAPE, /* two objects, no height between base and rim, lying down */
    RECON_ERR_SIZE,
    RECON_ERR_INTERNAL /* allocation failure and the like: exit code 1 */
} recon_status;

/* Parts of the photographed object that are not the vessel's surface of
 * revolution, and what the profile does over their rows. */
typedef enum {
    RECON_PART_SHADOW = 0,  /* a floor shadow joined to the foot (cut off) */
    RECON_PART_STAND,       /* a stand or plinth under the foot (cut off) */
    RECON_PART_HANDLE,      /* a part on one side with background behind it (a handle's loop) */
    RECON_PART_ASYMMETRY,   /* a run of rows where one side departs from the body (a lug, a spout, a chip) */
    RECON_PART_KIND_COUNT
} recon_part_kind;

typedef enum {
    RECON_PROFILE_NONE = 0, /* the rows lie outside the profile (below the foot) */
    RECON_PROFILE_LEFT,     /* the profile takes the left outline there */
    RECON_PROFILE_RIGHT,    /* ... the right outline */
    RECON_PROFILE_BRIDGED   /* neither: the B-spline bridges the rows */
} recon_profile_source;

typedef struct {
    recon_part_kind what;
    int row0, row1;   /* image rows spanned, inclusive */
    int side;         /* -1 left, +1 right, 0 both */
    recon_profile_source profile;
} recon_excluded;

enum { RECON_MAX_EXCLUDED = 16 };

/* The limits of a surface of revolution's silhouette (recon_result's
 * axis_gap and base_asymmetry; docs/algorithms-recon.md, "Not a vessel"). */
#define RECON_MAX_AXIS_GAP 0.05
#define RECON_MAX_BASE_ASYMMETRY 0.10

/* Names used in profile.json and messages. */
const char *recon_part_name(recon_part_kind k);
const char *recon_profile_source_name(recon_profile_source s);

typedef struct {
    int width, height;
    uint8_t *mask;           /* width*height, 1 = vessel: largest object, closed (radius 4), holes
                                and rows filled, floor shadow trimmed at the foot */
    recon_mask_mode mask_mode;
    int threshold_used;      /* 0..255 gray threshold when forced; -1 otherwise */
    int dropped_objects;     /* other connected objects removed from the mask */
    int holes_filled;        /* background regions enclosed by the object, filled */
    int n_contour;
    vec2 *contour;           /* outer border, pixel centres, as traced (closed, no repeat) */
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
    vec2 *polyline;          /* (r, h), px: (r, 0), the sub-pixel outline points with 0 < h < H in
                                increasing h, (r, H); H = rim corners' height. Taken on side_used,
                                except over the rows of excluded parts (see excluded[].profile) */
    uint8_t *polyline_bridge; /* per polyline point: 1 when the rows up to the next point were left out
                                 (the B-spline bridges them) */
    int n_excluded;
    recon_excluded excluded[RECON_MAX_EXCLUDED];
    /* Confidence figures (the quality gate, include/celadon/reconstruct.h) */
    unsigned border_contact; /* bit 0 top, 1 bottom, 2 left, 3 right: the vessel touches that border */
    double lr_disagreement;  /* mean |r_left - r_right| over the profile rows where both sides are kept,
                                as a fraction of the largest radius */
    double excluded_fraction; /* fraction of the profile's rows taken from one side only or bridged */
    double r_max;            /* largest radius of the polyline, px */
    /* What a surface of revolution's silhouette has at zero (refused over
     * RECON_MAX_AXIS_GAP, RECON_MAX_BASE_ASYMMETRY: not a vessel), fractions of
     * the object's height: rows whose axis lies on the backdrop between object
     * on both sides; how much farther the base reaches on one side (0 when
     * the outline's symmetry gave no axis) */
    double axis_gap, base_asymmetry;
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
