/* JPEG-like compression artefacts for synthetic photographs: each channel is
 * cut into 8x8 blocks, transformed by the DCT, quantised with the JPEG
 * standard's luminance table scaled for a quality (the IJG scaling) and
 * transformed back, which rings along edges and blocks flat gradients as a
 * real JPEG does (no chroma subsampling, no entropy coding: nothing else of
 * JPEG changes pixels). */
#ifndef CELADON_TESTS_SYNTH_JPEG_H
#define CELADON_TESTS_SYNTH_JPEG_H

#include "celadon/image.h"

/* Quantises img in place (values clamped to [0, 1] after); quality in
 * 1..100. Partial blocks at the right and bottom edges are padded by
 * repeating their last pixel. */
void synth_jpeg_quantise(image_t *img, int quality);

#endif
