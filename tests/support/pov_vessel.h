/* Rendered vessel photographs with exact geometry, by an independent
 * renderer: POV-Ray (Debian `povray`) draws the pinhole_params vessel as a
 * thin-walled open solid of revolution (the outer wall is p's profile r(t),
 * exact at 201 heights and linear between them, swept in 360 azimuth steps
 * as a smooth-shaded mesh, half as fine in a draft; a wall 1.5% of the height thick; a floor 3%
 * above the foot)
 * standing on a photographer's sweep (a matte floor curving up into a wall
 * behind it), lit by a soft area light above and to the left of the camera
 * (soft shadow on the floor and the sweep) and a weaker fill light from the
 * right, glazed celadon green with a small highlight, anti-aliased. The
 * camera is pinhole_vessel.h's (same position, look-at, focal length and
 * frame; roll and look_at_side are ignored), so pinhole_profile_error
 * measures a reconstruction against the truth. */
#ifndef CELADON_TESTS_POV_VESSEL_H
#define CELADON_TESTS_POV_VESSEL_H

#include <stddef.h>

#include "pinhole_vessel.h"

/* 1 when the `povray` program is on PATH. */
int pov_available(void);

/* Writes the scene for p to pov_path and renders it to png_path (8-bit
 * sRGB PNG, p->width x p->height) with `threads` render threads; a draft
 * (a quarter of the mesh, a coarser soft shadow and anti-aliasing) costs
 * about half. Returns 0, or -1 with a reason in err. */
int pov_vessel_render(const pinhole_params *p, int draft, const char *pov_path, const char *png_path, int threads,
                      char *err, size_t errlen);

#endif
