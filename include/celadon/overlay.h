/* A diagnostic picture of one reconstruction (the paper's Figure 2b-d in one
 * image): the photo, lightened, with the traced contour, the PCA axes, the
 * axis of revolution, the fitted profile curve mapped back onto the chosen
 * side, the four corners, and a legend. */
#ifndef CELADON_OVERLAY_H
#define CELADON_OVERLAY_H

#include <stdint.h>

#include "celadon/bspline.h"
#include "celadon/image.h"
#include "celadon/recon.h"

/* Layers, in drawing order (a later one covers an earlier one). */
typedef enum {
    OVERLAY_CONTOUR, /* the traced outer contour, closed */
    OVERLAY_AXIS,    /* the axis of revolution, base to rim, 5% longer at both ends */
    OVERLAY_PCA,     /* arrows from the mean along each eigenvector, sqrt(eigenvalue) long */
    OVERLAY_CURVE,   /* the B-spline profile in the image, on res->side_used */
    OVERLAY_CORNERS, /* discs at the four corners */
    OVERLAY_LAYER_COUNT
} overlay_layer;

extern const uint8_t overlay_colours[OVERLAY_LAYER_COUNT][3];

/* The photo's pixels under the drawing: lightened toward white so the
 * layers stand out, 0.6 * photo + 0.4 * white (photo as 8-bit RGB; a photo
 * with alpha is first composited over white). */
#define OVERLAY_PHOTO_WEIGHT 0.6

/* Line width in pixels for a photo of this size: 2, or 1/300 of the smaller
 * side on large photos. */
double overlay_line_width(int width, int height);

/* Renders the overlay as 8-bit RGB, the photo's size, origin top-left.
 * The legend sits in the top-left corner. Returns a malloc'd buffer or NULL
 * when out of memory. */
uint8_t *overlay_render(const image_t *photo, const recon_result *res, const bspline_t *curve);

#endif
