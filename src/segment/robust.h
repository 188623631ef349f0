/* Constants of the segmentation's robust fits (the backdrop surface, the
 * axis of a mask): Tukey-weighted least squares with the scale from the
 * median absolute deviation. */
#ifndef CELADON_SEGMENT_ROBUST_H
#define CELADON_SEGMENT_ROBUST_H

/* Tukey's biweight constant (95% efficiency for normal residuals). */
#define TUKEY_C 4.685
/* MAD to sigma for a normal distribution. */
#define MAD_TO_SIGMA 1.4826

#endif
