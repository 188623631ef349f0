/* Object/backdrop segmentation of a catalogue photograph: a model of the
 * image and a min-cut, GrabCut-style, at a reduced resolution, with what is
 * known of the scene built into the energy:
 *
 *   backdrop   a smooth colour field (backdrop.h) plus pixel noise; a floor
 *              shadow is that field darkened (same chromaticity);
 *   object     a Gaussian mixture of colours (gmm.h), refitted each round;
 *   border     the image border is backdrop (a prior, not a constraint: an
 *              object that runs off the image still shows as object there);
 *   smoothness contrast-sensitive Potts links between 8-neighbours;
 *   symmetry   once an axis is known, a link between each pixel and its
 *              mirror image across it: the vessel is mirror-symmetric, its
 *              shadow is not.
 *
 * docs/algorithms-recon.md ("Segmentation") derives the weights. */
#ifndef CELADON_RECON_SEGMENT_H
#define CELADON_RECON_SEGMENT_H

#include <stdint.h>

#include "celadon/image.h"
#include "recon/backdrop.h"
#include "recon/gmm.h"

/* The colour models that decide what a pixel is; shared by the low-resolution
 * rounds and the full-resolution refinement. */
typedef struct {
    recon_gmm object;
    recon_backdrop backdrop;   /* in low-resolution pixel units */
    double bg_icov[9], bg_lognorm;     /* backdrop residual: the noise Gaussian (with its prior weight) */
    double tail_icov[9], tail_lognorm; /* ... and the wide one of the surface's misfit */
    double shadow_icov[9], shadow_lognorm;
    int have_support;          /* a stand's colours (support.c) also count as not-object */
    recon_gmm support;
} recon_colour_model;

typedef struct recon_segmentation_s {
    int factor;         /* full-resolution pixels per low-resolution pixel, per side */
    int w, h;           /* low-resolution size */
    float *rgb;         /* w*h*3 box-filtered colour (gray photos: three equal channels) */
    uint8_t *object;    /* w*h: 1 = object after the last round (every component) */
    recon_colour_model model;
    int have_axis;      /* the symmetry links were used */
    double axis_x0, axis_slope; /* the axis at low resolution: x = axis_x0 + axis_slope * (y + 0.5) */
    double beta;        /* of the contrast-sensitive links: 1 / (2 <|dc|^2>) over neighbour pairs */
    int rounds;
} recon_segmentation;

/* Costs of one colour c whose backdrop colour is backdrop_c: -log p(c |
 * object) and -log p(c | not object). mirror_c and its backdrop colour (both
 * NULL when unknown) are the pixel's mirror image across the axis: a shadow
 * is unlikely where the mirror is darkened alike. */
void recon_colour_costs(const recon_colour_model *m, const float *c, const float *backdrop_c, const float *mirror_c,
                        const float *mirror_backdrop_c, double *cost_object, double *cost_backdrop);

/* Sets the backdrop and shadow terms of m from its backdrop's residual
 * covariance and the priors (which depend on have_support). Returns 0, or -1
 * for a singular covariance. */
int recon_colour_model_prepare(recon_colour_model *m);

/* beta of the contrast-sensitive links of a colour image (w*h*3). */
double recon_contrast_beta(const float *rgb, int w, int h);
/* The contrast-sensitive smoothness link between two colours, in nats:
 * gamma exp(-beta |a - b|^2), divided by sqrt 2 between diagonal neighbours. */
double recon_contrast_link(const float *a, const float *b, double beta, int diagonal);
/* The same between low-resolution pixels p and q. */
double recon_segment_link(const recon_segmentation *seg, int p, int q, int diagonal);

/* Runs the segmentation. Returns 0, 1 when nothing in the photo differs from
 * its backdrop, or -1 when out of memory. */
int recon_segment(const image_t *img, recon_segmentation *seg);
void recon_segmentation_free(recon_segmentation *seg);

/* The mirror image of low-resolution pixel p across the axis, or -1 outside. */
int recon_segment_mirror(const recon_segmentation *seg, int p);

/* The robust axis of a low-resolution object mask: the line x = x0 + slope * (y
 * + 0.5) through the midpoints of its rows, fitted by least median of squares
 * (a handle or a shadow on one side moves the midpoints of its rows; up to
 * half the rows may be such) and polished by Tukey-weighted least squares.
 * Returns 0, or -1 when the mask has fewer than 4 rows. */
int recon_mask_axis(const uint8_t *mask, int w, int h, double *x0, double *slope);

#endif
