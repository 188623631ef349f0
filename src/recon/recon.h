/* What src/recon/ offers the other reconstruction folders (src/perspective/)
 * besides its public API (celadon/recon.h, recon_texture.h, overlay.h): the
 * sub-pixel edge on a row of the photo, and bilinear samples of the photo. */
#ifndef CELADON_RECON_RECON_H
#define CELADON_RECON_RECON_H

#include <math.h>
#include <stdint.h>

#include "celadon/image.h"
#include "celadon/vecmath.h"

/* ---- sub-pixel silhouette (subpixel_edge.c) */

typedef struct {
    double x;        /* edge position on the row's centre line, px */
    double contrast; /* |fg - bg| at the edge, signal units */
    int ok;
} recon_edge;

/* One pixel row of the signal the outline is measured on: its colours
 * (channels 3) or one value per pixel (channels 1: gray, or alpha). */
typedef struct {
    const float *row;
    int width, channels;
} recon_signal;

/* Colour distance between the signal's pixels a and b. Inline: the edge
 * searches run it per pixel. */
static inline double recon_signal_distance(const recon_signal *s, int a, int b)
{
    double d2 = 0;
    for (int c = 0; c < s->channels; c++) {
        double t = (double)s->row[(size_t)a * s->channels + c] - s->row[(size_t)b * s->channels + c];
        d2 += t * t;
    }
    return sqrt(d2);
}

/* Sub-pixel position of the outermost edge of the object on a row, on side
 * (-1 left, +1 right), from the anti-aliased ramp: the fraction of each pixel
 * covered by the object, the projection of (c - bg) onto fg - bg over
 * |fg - bg|^2, summed over the pixels the edge crosses, is the object's
 * length in that window (exact for a straight edge under box anti-aliasing).
 * The search starts at i0, the mask's outermost object pixel on that side of
 * the row; slope is the outline's dx per row (from the neighbouring rows);
 * delta the smallest colour distance from the background that counts as
 * object. */
recon_edge recon_subpixel_edge(const recon_signal *s, int i0, int side, double slope, double delta);
/* The same without following a glaze's drift toward the backdrop: fg is the
 * pixel just inside. For the outline's top and bottom arcs, where a thin
 * band of another colour (the lip, the mouth seen from above) lies just
 * inside the edge and the drift rule would read it as a glaze. */
recon_edge recon_subpixel_edge_flat(const recon_signal *s, int i0, int side, double slope, double delta);

/* ---- samples of a photo (photo_sample.c) */

/* Row j of the signal the outline is measured on: the photo's colours in
 * [0, 1] (a gray photo's one channel), or gray (the alpha-based gray when the
 * mask came from alpha). buf: width * 3 floats, or NULL when the photo has
 * three channels already in [0, 1] (its rows serve as they are). */
recon_signal recon_signal_row(const image_t *img, const float *gray, int alpha, int j, float *buf);


/* The photo's colour at the continuous point p (pixel (i, j) has its centre
 * at (i + 0.5, j + 0.5); clamped to the image), bilinear; gray photos give
 * gray. */
void recon_sample_rgb(const image_t *img, vec2 p, float out[3]);

/* An 8-bit channel value of v in [0, 1] (clamped, NaN to 0, rounded to
 * nearest as lrintf). Inline, as it runs per pixel: adding 2^23 to a float
 * in [0, 255] leaves no bits for a fraction, so the sum is rounded to an
 * integer in the current rounding mode, as lrintf rounds. */
static inline uint8_t recon_to_u8(float v)
{
    v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    float r = v * 255.0f + 0x1p23f;
    return (uint8_t)(r - 0x1p23f);
}

#endif
