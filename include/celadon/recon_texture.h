/* The texture T(u, v) of a reconstructed vessel, taken from its photograph:
 * by scanline resampling (one texture row per height step along the axis),
 * or by the camera (along the imaged cross-sections: recon_camera.h). */
#ifndef CELADON_RECON_TEXTURE_H
#define CELADON_RECON_TEXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/image.h"
#include "celadon/recon.h"

typedef struct {
    int width, height;
    uint8_t *rgb;  /* width*height*3, row 0 = the rim (v = 1), last row = the base (v = 0) */
    uint8_t *seen; /* width*height, 1 where the camera saw the texel; NULL: all seen (scanline) */
} recon_texture_t;

/* Builds the texture from the photo and its extraction result. Rows are
 * lines perpendicular to the axis at heights h = v * H (H = the rim height,
 * the last polyline point's h), one per pixel of H; on each the segment
 * between the left and right silhouette is resampled, with bilinear
 * interpolation in the photo, to the widest row's width. Columns follow the
 * texture u of docs/conventions.md for the visible half (u = 1 - phi/pi): column u
 * samples the point c - a cos(pi u) of a row whose silhouette is c -/+ a, so
 * u = 0 is the left silhouette, 0.5 the front meridian, 1 the right one.
 * Returns 0, or -1 with a one-line reason in err. */
int recon_texture_from_photo(const image_t *photo, const recon_result *res, recon_texture_t *out, char *err, size_t errlen);

void recon_texture_free(recon_texture_t *t);

#endif
