/* The hand-checked truth of the real-dev photographs (tests/data/real-dev-truth/:
 * one mask per photo, NAME.png, 255 = the vessel with its handles and lid,
 * no stand, plinth or shadow; the body's rows are the mask's extent),
 * and the yardstick of issue 25: is a reconstruction's profile on the true
 * outline? docs/gallery-real.md ("Truth") says how the masks were made.
 *
 * The outline's distance: on each row of the body (rim row to base row) the
 * profile's image outline (the polyline, both sides, about the found axis)
 * against the truth mask's nearest edge of that side's kind on the row (the
 * silhouette's, or the body's seen through a handle's window), across the
 * outline (|dx| / sqrt(1 + slope^2)), the nearer side (a handle on one side
 * leaves the other); a body row the profile misses, or a profile row outside the
 * body, is infinitely far. The figure is the mean over all those rows but
 * the worst fifth of the body's height (handles, spouts, the ellipses'
 * arcs). The profile is on the true outline when that is at most 0.5% of
 * the body's height and the profile reaches beyond the body's rows by at
 * most 1% of it in all (a stand revolved into the body reaches below). */
#ifndef CELADON_TEST_REALDEV_TRUTH_H
#define CELADON_TEST_REALDEV_TRUTH_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/recon.h"

#define REALDEV_TRUTH_DIR "tests/data/real-dev-truth"
#define REALDEV_ON_OUTLINE 0.005     /* of the body's height */
#define REALDEV_MAX_OVERREACH 0.01   /* of the body's height */

typedef struct {
    int width, height;
    uint8_t *mask;     /* 0/1 */
    int rim_row, base_row; /* the body's top and bottom rows */
} realdev_truth;

/* The truth of the photo at path (its file name without .jpg names it).
 * Returns 0, or -1 when there is none (truth zeroed). */
int realdev_truth_load(const char *photo_path, realdev_truth *t);
void realdev_truth_free(realdev_truth *t);

/* IoU of the truth mask and a 0/1 mask of the same size. */
double realdev_truth_iou(const realdev_truth *t, const uint8_t *mask);

/* The outline's distance as a fraction of the body's height (INFINITY when
 * the profile covers less than four fifths of it). */
double realdev_truth_outline(const realdev_truth *t, const recon_result *x);

/* How far the profile's rows reach above the body's top row and below its
 * bottom one, in all, as a fraction of the body's height. */
double realdev_truth_overreach(const realdev_truth *t, const recon_result *x);

/* 1 when the profile is on the true outline (the outline's distance and the
 * overreach within their limits). */
int realdev_truth_on_outline(const realdev_truth *t, const recon_result *x);

#endif
