/* preview.png: museum.xml path-traced from the entrance camera, through the
 * public render API (scene.h, render.h, film.h) only. */
#ifndef CELADON_MUSEUM_PREVIEW_H
#define CELADON_MUSEUM_PREVIEW_H

#include <stddef.h>

/* Renders scene_path at its own film size and spp into png_path (written
 * whole or not at all), with a progress bar on a TTY when progress is 1.
 * Returns 0, or -1 with a one-line reason. */
int museum_preview_render(const char *scene_path, const char *png_path, int progress, char *err, size_t errlen);

#endif
