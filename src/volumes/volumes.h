/* Volumes in the sense of Mitsuba 3: RGB fields over space that media read
 * their extinction and albedo from. Plugins (volume_table.c): `constvolume`
 * (one value everywhere) and `gridvolume` (a voxel grid in Mitsuba's binary
 * .vol format, trilinear or nearest, over the unit cube placed by to_world).
 *
 * This is src/volumes' interface: what media use; each plugin is one file
 * plus one line of volume_table.c (docs/plugins.md). */
#ifndef CELADON_VOLUMES_H
#define CELADON_VOLUMES_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct volume volume_t;

/* The value at world point p. Thread-safe. */
rgb volume_eval(const volume_t *v, vec3 p);
/* An upper bound of every channel of volume_eval anywhere (a grid's largest
 * voxel: interpolation never exceeds it). */
double volume_max(const volume_t *v);
/* Whether p is within the volume's box: the unit cube placed by its
 * to_world (a <volume>'s; a color's box is all of space). A heterogeneous
 * medium is empty outside its sigma_t's box, as in Mitsuba. */
bool volume_contains(const volume_t *v, vec3 p);
/* Whether the value is the same everywhere. */
bool volume_is_constant(const volume_t *v);
void volume_destroy(volume_t *v);

/* The volume a medium's parameter name gives: a nested or referenced
 * <volume>, or a color (Mitsuba's "spectrum") as a constant volume, or def
 * when absent. NULL with "file:line: problem" in err. */
volume_t *volume_of_param(scene_obj *o, const char *name, rgb def, char *err, size_t errlen);

/* A grid of Mitsuba's binary .vol format (vol_file.c), as stored. */
typedef struct {
    float *values; /* nx * ny * nz * channels floats, finite, x fastest, then y, then z */
    int nx, ny, nz, channels; /* channels 1 or 3 */
    vec3 lo, hi;   /* the bounding box the file records */
} vol_grid;

/* Reads the .vol file at path into g: 0, or -1 with the problem in why
 * (not a .vol file, an encoding other than float32, a size that disagrees
 * with the file's length, a value not finite). */
int vol_grid_read(const char *path, vol_grid *g, char *why, size_t whylen);
void vol_grid_free(vol_grid *g);

/* A volume plugin: its declaration for the scene reader and its constructor
 * from a <volume> object, which returns NULL with "file:line: problem" in
 * err. */
typedef struct {
    scene_plugin_decl decl;
    volume_t *(*create)(scene_obj *o, char *err, size_t errlen);
} volume_plugin;

/* The registration table: every volume plugin, NULL-terminated. */
extern const scene_plugin_decl *const volume_plugins[];
/* The plugin named name, or NULL. */
const volume_plugin *volume_plugin_find(const char *name);

#endif
