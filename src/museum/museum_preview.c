/* The path-traced preview of museum.xml. See museum_preview.h. */
#include "museum/museum_preview.h"

#include <stdio.h>

#include "celadon/film.h"
#include "celadon/render.h"
#include "celadon/scene.h"

int museum_preview_render(const char *scene_path, const char *png_path, int progress, char *err, size_t errlen)
{
    scene_options bo = scene_options_default();
    scene_t *scene = scene_create_from_file(scene_path, NULL, 0, &bo, err, errlen);
    if (!scene)
        return -1;
    render_options ro = {.threads = 0, .aovs = 0, .progress = progress};
    film_t film;
    render_stats stats;
    int rc = render_scene(scene, &ro, &film, &stats, err, errlen);
    if (rc == 0) {
        rc = film_write(&film, png_path, err, errlen);
        film_free(&film);
    }
    scene_destroy(scene);
    return rc;
}
