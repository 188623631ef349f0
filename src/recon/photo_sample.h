/* Bilinear samples of a decoded photo at continuous image points, and their
 * 8-bit texels. */
#ifndef CELADON_RECON_PHOTO_SAMPLE_H
#define CELADON_RECON_PHOTO_SAMPLE_H

#include <stdint.h>

#include "celadon/image.h"
#include "celadon/vecmath.h"

/* The photo's colour at the continuous point p (pixel (i, j) has its centre
 * at (i + 0.5, j + 0.5); clamped to the image), bilinear; gray photos give
 * gray. */
void recon_sample_rgb(const image_t *img, vec2 p, float out[3]);

/* An 8-bit channel value of v in [0, 1] (clamped, rounded). */
uint8_t recon_to_u8(float v);

#endif
