/* museum.xml: the museum of museum.glb as a Mitsuba 3 scene for `celadon
 * render` (docs/scene-format.md): every vessel an exact `sor` shape (its
 * vessels/SLUG/profile.json at its real height, open mouth, a plastic glaze
 * over vessels/SLUG/texture.png), pedestals as cubes, the glass cases as five
 * thindielectric rectangles, labels as rectangles with labels/SLUG.png, the
 * lights as point emitters of the same intensities, and the entrance camera.
 * The film size and spp are <default>s (resx, resy, spp). */
#ifndef CELADON_MUSEUM_SCENE_H
#define CELADON_MUSEUM_SCENE_H

#include <stddef.h>

#include "museum/exhibit.h"
#include "museum/layout.h"

/* Writes path atomically; with_vessels = 0 leaves the vessels out (the
 * room the environment probes see, museum_light.h). Returns 0, or -1 with a
 * one-line reason. */
int museum_scene_write(const char *path, const char *title, const layout_t *layout, const museum_exhibit *ex,
                       int n, int with_vessels, int width, int height, int spp, char *err, size_t errlen);

#endif
