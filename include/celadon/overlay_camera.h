/* The perspective layers of the diagnostic overlay: what recon_camera_meridian
 * found, drawn over overlay_render's picture. */
#ifndef CELADON_OVERLAY_CAMERA_H
#define CELADON_OVERLAY_CAMERA_H

#include <stdint.h>

#include "celadon/recon_camera.h"

typedef enum {
    OVERLAY_CAMERA_ELLIPSES, /* the fitted base and rim ellipses, whole */
    OVERLAY_CAMERA_SECTIONS, /* cross-sections of the meridian: the near half solid, the far half dashed */
    OVERLAY_CAMERA_LAYER_COUNT
} overlay_camera_layer;

/* Okabe–Ito bluish green and sky blue, apart from overlay_colours. */
extern const uint8_t overlay_camera_colours[OVERLAY_CAMERA_LAYER_COUNT][3];

/* Draws both layers onto rgb (8-bit RGB, width x height, row-major: the
 * buffer overlay_render returns) in overlay_line_width: the two ellipses,
 * then the imaged cross-sections at n_sections heights evenly spaced
 * between the base and the rim (1/(n+1), ..., n/(n+1) of the meridian's
 * height). Returns 0, or -1 when out of memory (rgb unchanged). */
int overlay_draw_camera(uint8_t *rgb, int width, int height, const recon_camera *cam, const recon_meridian *mer,
                        int n_sections);

#endif
