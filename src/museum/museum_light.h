/* The museum's baked light (docs/museum.md, "Light"): museum.xml's own path
 * tracer lights the page. From the scene with the vessels: a lightmap of
 * each room surface and of each pedestal (museum_bake.h, JPEG, the
 * render's 8-bit code values), which museum.glb draws unlit; from the same
 * room without its vessels: an environment probe at each vessel's middle
 * and one for the room at the entrance camera, Radiance .hdr files the page
 * gives the glazes (and the glass) to reflect. */
#ifndef CELADON_MUSEUM_LIGHT_H
#define CELADON_MUSEUM_LIGHT_H

#include <stddef.h>
#include <stdint.h>

#include "museum/exhibit.h"
#include "museum/layout.h"
#include "museum/room_surfaces.h"

enum { MUSEUM_LIGHTMAP_JPEG_QUALITY = 90 };

typedef struct {
    uint8_t *bytes;
    size_t len;
} museum_file_bytes;

typedef struct {
    lightmap_layout room_layout[ROOM_SURFACES], *pedestal_layout; /* pedestal: one per exhibit */
    museum_file_bytes room[ROOM_SURFACES], *pedestal;             /* JPEG */
    museum_file_bytes room_probe, *probe;                         /* .hdr; probe: one per exhibit */
    int n;
} museum_light;

/* Bakes with spp samples per texel: the lightmaps from the scene file
 * `scene`, the probes from `room_scene` (the same without vessels).
 * Returns 0, or -1 with a one-line reason (out has nothing to free then). */
int museum_light_bake(const char *scene, const char *room_scene, const layout_t *l, const museum_exhibit *ex,
                      int spp, museum_light *out, char *err, size_t errlen);
void museum_light_free(museum_light *m);

/* Where the probe of exhibit i is looked up from: its vessel's middle. */
vec3 museum_probe_point(const layout_exhibit *le, const museum_exhibit *e);

#endif
