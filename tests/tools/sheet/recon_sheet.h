/* What the contact-sheet tools share (draw_hard_cases, draw_real_gallery):
 * box-filtered thumbnails on a cairo sheet and a photo reconstructed as
 * `celadon reconstruct --force` does, drawn as its overlay. */
#ifndef CELADON_TOOLS_RECON_SHEET_H
#define CELADON_TOOLS_RECON_SHEET_H

#include <cairo.h>
#include <stddef.h>

#include "celadon/image.h"
#include "celadon/reconstruct.h"

/* A box-filtered thumbnail of img painted at (x, y), scale s (< 1). */
void sheet_paint_thumbnail(cairo_surface_t *sheet, const image_t *img, int x, int y, double s);

/* The photo at path reconstructed as `celadon reconstruct --force
 * --segmenter s` does, into *r (freed with reconstruction_free either way).
 * Returns reconstruct_photo's status, err its reason. */
int sheet_reconstruct_forced(const char *path, reconstruct_segmenter s, reconstruction *r, char *err, size_t len);

/* The photo at path reconstructed with --force into *r (the caller frees it
 * with reconstruction_free), its overlay into *out, and the verdict
 * ("passed", the gate's failures, or "refused: " and the reason) into
 * verdict. With without_photo, the overlay is drawn over the segmentation
 * (the vessel's mask in grey on white) instead of the photo's pixels; a
 * refused photo then gives a blank image. Returns 0, or -1 when out of
 * memory or the photo cannot be read. */
int sheet_reconstruct_overlay(const char *path, int without_photo, reconstruction *r, image_t *out, char *verdict,
                              size_t len);

#endif
