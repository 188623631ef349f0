/* museum.glb: the laid-out museum as one binary glTF 2.0 file.
 *
 * Nodes (every name says what it is, with the vessel's title):
 *   "Museum: TITLE"            root; extras.celadon_museum: room size, aisle, vessel count
 *                              and probe (probe.hdr: the room's light at the entrance)
 *     "Floor", "Ceiling", "Back wall", "Entrance wall", "Left wall", "Right wall"
 *                              each under its lightmap baked by the path tracer
 *                              (museum_light.h), unlit (KHR_materials_unlit)
 *     "Lamps", "Lamp rods"     the ceiling lights' fixtures: glowing shades
 *                              (emissive) on rods, one mesh each
 *     "Entrance camera"        perspective camera at the entrance
 *     "Ceiling light K"        KHR_lights_punctual point lights
 *     "Exhibit: T"             per vessel, on the floor at the footprint centre;
 *                              extras: title, date, height_cm (as shown), size (the
 *                              label's line: the catalogue's figures only), size_from,
 *                              note (below the quality gate), description, photo,
 *                              profile (its vessels/SLUG/profile.json), probe (its
 *                              vessels/SLUG/probe.hdr: the light around the vessel)
 *       "Pedestal: T"          its five faces under their lightmap, unlit
 *       "Glass case: T"        KHR_materials_transmission + _ior
 *       "Case frame: T"        the case's twelve edges as thin dark bars
 *       "Vessel: T"            the vessel's base; extras.lod: segments and distances
 *         "T, LOD K (N segments)"  one mesh per level, extras.lod_distance (m)
 *       "Label: T"             textured quad on the pedestal's front
 *       "Case light: T"        point light under the lid
 * glTF has no core LOD: the levels are sibling meshes, the viewer shows the
 * finest one whose lod_distance is not beyond the camera's distance to the
 * vessel node. Vessels use a clear-coated glaze (KHR_materials_clearcoat)
 * over their embedded texture. */
#ifndef CELADON_MUSEUM_GLTF_H
#define CELADON_MUSEUM_GLTF_H

#include <stddef.h>

#include "celadon/museum.h"
#include "museum/exhibit.h"
#include "museum/layout.h"
#include "museum/museum_light.h"

/* Light intensities shared by the glTF (candela) and the scene (W/sr): the
 * same numbers, so both show the same balance. */
#define MUSEUM_CASE_LIGHT_PER_M2 1.2   /* case light intensity per m^2 of the case's height squared */
#define MUSEUM_CEILING_LIGHT 2.0
#define MUSEUM_LIGHT_COLOR_R 1.0       /* a warm white (about 3500 K) */
#define MUSEUM_LIGHT_COLOR_G 0.87
#define MUSEUM_LIGHT_COLOR_B 0.72

/* The room's colours (linear RGB), the glTF's base colours and the scene's
 * diffuse reflectances alike, so both are the same room. */
#define MUSEUM_FLOOR_RGB 0.46, 0.33, 0.22 /* oak */
#define MUSEUM_WALL_RGB 0.84, 0.82, 0.78
#define MUSEUM_CEILING_RGB 0.85, 0.85, 0.85

/* The case light's intensity for an exhibit. */
double museum_case_light(const layout_exhibit *e);

/* Writes path, the room and pedestals drawn with light's lightmaps. Fills
 * rep's triangle and draw-call figures and glb_bytes. Returns 0, or -1 with
 * a one-line reason. */
int museum_gltf_write(const char *path, const char *title, const layout_t *layout, const museum_exhibit *ex,
                      int n, const museum_light *light, museum_report *rep, char *err, size_t errlen);

#endif
