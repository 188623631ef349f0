/* The museum's light, baked by celadon's own path tracer (docs/museum.md,
 * "Light"): what museum.xml's integrator sees leaving each texel of the
 * room's and pedestals' lightmaps (room_surfaces.h), and the light arriving
 * at a point from every direction (an environment probe for the glazes).
 *
 * A diffuse surface sends the same radiance every way, so a texel's value
 * is the radiance along the ray that looks straight down at it from
 * BAKE_OFFSET m in front: the integrator's estimate for a camera ray there
 * (scene_radiance), with every bounce and shadow of the render. Stored as
 * the standard view's 8-bit code values (the PNG render's), an unlit
 * texture on the page shows exactly what the render shows there. */
#ifndef CELADON_MUSEUM_BAKE_H
#define CELADON_MUSEUM_BAKE_H

#include <stdint.h>

#include "celadon/scene.h"
#include "museum/room_surfaces.h"

#define BAKE_OFFSET 1e-3
enum { PROBE_WIDTH = 128, PROBE_HEIGHT = 64 };

/* Linear radiance (RGB floats, rows down) of every texel of the lightmap m
 * of quads q, the gutters repeating their tiles' borders; with denoise,
 * through celadon's denoiser (denoise.h: each face's texels alike but for
 * their noise, told apart from other faces by the normal). Sampler
 * streams: "pixel" (x, y + stream_row) of the image. Uses OpenMP's
 * threads. */
void bake_lightmap(const scene_t *s, const quad_spec *q, const lightmap_layout *m, uint32_t stream_row, int denoise,
                   float *rgb);

/* The light arriving at `at` from every direction, an equirectangular
 * PROBE_WIDTH x PROBE_HEIGHT image (RGB floats, rows down) in three.js's
 * convention: column u looks toward (cos phi, 0, sin phi), phi = 2 pi (u - 1/2),
 * the top row straight up. */
void bake_probe(const scene_t *s, vec3 at, uint32_t stream_row, float *rgb);

/* The standard view's 8-bit code values of n linear RGB pixels. */
void bake_encode(const float *rgb, long n, uint8_t *out);

#endif
