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
 *              shadow is not;
 *   prior      optionally, a learned object prior (prior/prior.h): the
 *              network's probability as a likelihood ratio on each pixel,
 *              and the initial object it sees.
 *
 * docs/algorithms-recon.md ("Segmentation") derives the weights. */
#ifndef CELADON_SEGMENT_SEGMENT_H
#define CELADON_SEGMENT_SEGMENT_H

#include <stdint.h>

#include "celadon/image.h"
#include "celadon/recon.h"
#include "segment/backdrop.h"
#include "segment/gmm.h"

/* The symmetry link, of the low-resolution rounds and the full-resolution
 * refinement alike: the prior probability that a pixel and its mirror image
 * across the axis differ is eps = 2%, so a differing pair costs
 * log((1 - eps) / eps) = 3.9 nats. A cast shadow or a reflection of the room
 * in the backdrop, which the colour models leave nearly undecided, goes with
 * its mirror; a handle, whose colours are plainly the object's, stays. */
#define SYMMETRY_EPS 0.02

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

typedef struct recon_segment_work recon_segment_work;

typedef struct recon_segmentation_s {
    int factor;         /* full-resolution pixels per low-resolution pixel, per side */
    int w, h;           /* low-resolution size */
    float *rgb;         /* w*h*3 box-filtered colour (gray photos: three equal channels) */
    float *prior;       /* w*h box-filtered object prior, or NULL without one */
    uint8_t *object;    /* w*h: 1 = object after the last round (every component) */
    recon_colour_model model;
    int have_axis;      /* the symmetry links were used */
    double axis_x0, axis_slope; /* the axis at low resolution: x = axis_x0 + axis_slope * (y + 0.5) */
    double beta;        /* of the contrast-sensitive links: 1 / (2 <|dc|^2>) over neighbour pairs */
    int rounds;
    recon_segment_work *work; /* the rounds' buffers and graph, between the steps below */
} recon_segmentation;

/* The object's costs of the colours seen so far under one colour model, by
 * colour: the cost is a function of the colour alone, and a photo repeats
 * colours (8-bit channels, flat backdrops), while the mixture's exp and log
 * are most of a pixel's data term. Direct-mapped; all zero is empty (calloc,
 * or memset when the model changes). */
enum { RECON_COST_MEMO_BITS = 12 };
typedef struct {
    struct {
        float c[3];
        int used;
        double cost;
    } e[1 << RECON_COST_MEMO_BITS];
} recon_cost_memo;

/* Costs of one colour c whose backdrop colour is backdrop_c: -log p(c |
 * object) and -log p(c | not object). mirror_c and its backdrop colour (both
 * NULL when unknown) are the pixel's mirror image across the axis: a shadow
 * is unlikely where the mirror is darkened alike. memo: NULL, or the object
 * costs already computed under m. */
void recon_colour_costs(const recon_colour_model *m, recon_cost_memo *memo, const float *c, const float *backdrop_c,
                        const float *mirror_c, const float *mirror_backdrop_c, double *cost_object,
                        double *cost_backdrop);

/* How far the colour c lies off the line of its backdrop colour bc
 * darkened (k bc, any k): the squared Mahalanobis distance under the
 * shadow's noise, about chi-square with 2 degrees of freedom for a shadow
 * (it keeps the backdrop's chromaticity), large for a colour of its own. */
double recon_shadow_misfit(const recon_colour_model *m, const float *c, const float *bc);

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

/* Runs the segmentation. prior: NULL, or the object's probability at each
 * of img's pixels (prior/prior.h). Returns 0, 1 when nothing in the photo
 * differs from its backdrop, or -1 when out of memory. */
int recon_segment(const image_t *img, const float *prior, recon_segmentation *seg);

/* recon_segment's steps, in order (bench/bench_recon.c times each; seg is
 * freed by recon_segmentation_free whatever they return):
 *   start       the box-filtered colours, the backdrop fitted on the border
 *               ring, the initial object (what the backdrop cannot explain;
 *               with a prior, what the network sees), the contrast-sensitive
 *               link weights; 0, or -1;
 * then per round
 *   models      the object's colour mixture from the largest component of
 *               the current labels (the first round also fixes the symmetry
 *               axis from it); 0, 1 when there is no object, or -1;
 *   data_terms  every pixel's t-links from the colour models;
 *   cut         the min-cut: the first round builds the graph, the later
 *               ones change its t-links and go on from the last flow;
 *               updates object and rounds; 0, or -1. */
int recon_segment_start(const image_t *img, const float *prior, recon_segmentation *seg);
int recon_segment_models(recon_segmentation *seg);
void recon_segment_data_terms(recon_segmentation *seg);
int recon_segment_cut(recon_segmentation *seg);
void recon_segmentation_free(recon_segmentation *seg);

/* The mirror image of low-resolution pixel p across the axis, or -1 outside. */
int recon_segment_mirror(const recon_segmentation *seg, int p);

/* The robust axis of a low-resolution object mask: the line x = x0 + slope * (y
 * + 0.5) through the midpoints of its rows, fitted by least median of squares
 * (a handle or a shadow on one side moves the midpoints of its rows; up to
 * half the rows may be such) and polished by Tukey-weighted least squares.
 * Returns 0, or -1 when the mask has fewer than 4 rows. */
int recon_mask_axis(const uint8_t *mask, int w, int h, double *x0, double *slope);

/* ---- masks (mask.c) */

/* Fills gray (w*h floats, the signal the silhouette is measured on: alpha
 * when the image has a transparent background, else luminance). With alpha,
 * or a forced threshold (0..255; -1 = automatic), also fills mask (w*h, 1 =
 * object, before component filtering) and returns how; otherwise returns
 * RECON_MASK_GRAPH_CUT and leaves mask to the segmentation (segment.h), and
 * gray unset for a colour photo (three channels or more: its outline is
 * measured on the colours).
 * *threshold_used: the forced threshold, else -1. */
recon_mask_mode recon_mask_threshold(const image_t *img, int threshold, float *gray, uint8_t *mask,
                                     int *threshold_used);

/* Keeps the largest 8-connected object, fills its holes (background parts not
 * 4-connected to the image border; counted) and then each row between its
 * outermost object pixels (a vessel's outline meets a row once on each side).
 * Returns the object's pixel count, or -1 when out of memory. */
long recon_mask_clean(uint8_t *mask, int w, int h, int *dropped_objects, int *holes_filled);

/* The object's bounding box in mask: box = {x0, y0, x1, y1}, inclusive.
 * Returns 0 when the mask is empty (box unset), else 1. */
int recon_mask_box(const uint8_t *mask, int w, int h, int box[4]);

/* The number of 8-connected components of mask, or -1 when out of memory
 * (over runs: no per-pixel labels). */
int recon_mask_components(const uint8_t *mask, int w, int h);

/* Labels the 8-connected components of mask: lab[p] (w*h ints) = 1..n, 0 for
 * background; *area (malloc'd, n + 1 entries, [0] unused) their pixel counts.
 * Returns n, or -1 when out of memory. */
int recon_mask_label(const uint8_t *mask, int w, int h, int *lab, long **area);

/* Morphological closing with a (2r+1)^2 square of a row-convex mask (one
 * interval per row, as recon_mask_clean leaves it), computed on the row
 * intervals: bridges slits narrower than 2r+1 px (a decoration line as light
 * as the backdrop that reaches the outline). Returns 0, or -1 when out of
 * memory. */
int recon_mask_close(uint8_t *mask, int w, int h, int r);
/* Opening, likewise: removes slivers thinner than 2r+1 px. */
int recon_mask_open(uint8_t *mask, int w, int h, int r);

/* ---- the vessel among the segmentation's objects (object_select.c) */

/* Keeps in the low-resolution mask only the vessel: the largest component
 * that is not a strip along the image border (a frame line, a caption bar),
 * with the components that continue it across a band (recon_mask_join_bands).
 * Another component of a quarter of its size or more is a second object and
 * refuses the photo, unless it lies under the vessel and runs to the bottom
 * border: a stand, reported in *stand (what = RECON_PART_STAND, rows at low
 * resolution; row1 = -1 when none) and dropped. *dropped counts the removed
 * components. Returns RECON_OK or the refusal with its reason in why. */
recon_status recon_select_object(uint8_t *mask, int w, int h, int *dropped, recon_excluded *stand, char *why,
                                 size_t len);
/* Joins to the largest object of a mask each object that continues it above
 * or below across a band at most `gap` rows high (a decoration line as light
 * as the backdrop painted round the vessel): same axis, same width at the
 * facing ends; the band's rows are filled between them. recon_select_object
 * does the same at the segmentation's scale, where a band is at most
 * RECON_BAND_MAX_ROWS rows. Returns 0, or -1 when out of memory. */
enum { RECON_BAND_MAX_ROWS = 3 };
int recon_mask_join_bands(uint8_t *mask, int w, int h, int gap);

/* ---- stands and shadows at the foot (support.c) */

/* Cuts off the low-resolution vessel mask m a floor shadow joined to its
 * foot (its lowest pixels have no mirror image), then a stand under it (the
 * object runs into the bottom border, or steps out below the foot), each
 * found by a min-cut between seeds and kept only when the evidence holds
 * (support.c). Appends each part cut (rows at full resolution) to parts. A
 * stand's colours join the segmentation's not-object model. Returns 0, or -1
 * when out of memory. */
int recon_cut_support(recon_segmentation *seg, uint8_t *m, recon_excluded *parts, int max_parts,
                      int *n_parts);

/* ---- the full-resolution mask (refine.c) */

/* The vessel's mask at full resolution (img's size) from the low-resolution
 * one: coarse labels held fixed except on a band of full-resolution pixels
 * around their outline (the two cells of each coarse edge, the cells next to
 * them whose colour is not sure of their label, their mirror cells; grown
 * where the cut reaches the band's edge), where the segmentation's energy is
 * minimised again. Returns 0, or -1 when out of memory. */
int recon_refine_mask(const image_t *img, const recon_segmentation *seg, const uint8_t *coarse,
                      uint8_t *mask);

#endif
