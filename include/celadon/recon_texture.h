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
 * u = 0 is the left silhouette, 0.5 the front meridian, 1 the right one;
 * over the rows a part covers (recon_texture_covered_rows) the profile's
 * radius stands in for that side's silhouette, and recon_texture_fill_parts
 * fills what the part covers (docs/algorithms-recon.md, 13.6).
 * Returns 0, or -1 with a one-line reason in err. */
int recon_texture_from_photo(const image_t *photo, const recon_result *res, recon_texture_t *out, char *err, size_t errlen);

void recon_texture_free(recon_texture_t *t);

/* The sides (bit 0 left, bit 1 right) on which a part that the profile left
 * out as not of the body (a handle, an asymmetry: a lug, a spout, a figure)
 * spans image row y of the extraction, or lies within
 * RECON_TEXTURE_PART_MARGIN_ROWS rows of it (where a handle's root tapers
 * into the outline); 0 for none. */
#define RECON_TEXTURE_PART_MARGIN_ROWS 3
int recon_texture_parts_at(const recon_result *res, double y);

/* sides[j] for each of a texture's rows (row j on image row row_y[j], the
 * body's outline there at x = body_x[2 j] on the left, body_x[2 j + 1] on
 * the right): recon_texture_parts_at's, and the sides where the
 * extraction's outline stands out of the body's by more than
 * RECON_TEXTURE_PART_DEPARTURE of its half-width, and at least
 * RECON_TEXTURE_PART_DEPARTURE_PX (a handle's root, a handle the extraction
 * kept in the outline), with RECON_TEXTURE_PART_MARGIN_ROWS rows more on
 * each side of such a row. */
#define RECON_TEXTURE_PART_DEPARTURE 0.02
#define RECON_TEXTURE_PART_DEPARTURE_PX 1.0
void recon_texture_covered_rows(const recon_result *res, int rows, const double *row_y, const double *body_x,
                                unsigned char *sides);

/* Fills what parts left out of the profile cover in a texture of the
 * visible half (u from the left outline to the right one), so that a handle
 * is not smeared into the glaze. sides[j] (bits as above) says on which
 * sides a part covers texture row j; there the texels of that side turned
 * more than RECON_TEXTURE_PART_BAND_DEG from the front toward it (where a
 * handle's roots and what the part hides fall) take the mirror texel of the
 * other side (a surface of revolution shows the same body there), or, when
 * the row is covered on both sides, the linear blend in height of the
 * nearest rows above and below not covered on that side (the nearest one
 * alone at the top or bottom; nothing when every row is covered).
 * Returns 0, or -1 out of memory (the texture unchanged). */
#define RECON_TEXTURE_PART_BAND_DEG 45.0
int recon_texture_fill_parts(recon_texture_t *t, const unsigned char *sides);

#endif
