/* Phase functions in the sense of Mitsuba 3: how a medium scatters light at
 * a point, as a density over the sphere of new directions. Plugins
 * (phase_table.c): `isotropic` and `hg` (Henyey-Greenstein).
 *
 * Convention: d is the direction the path travels in when it arrives (the
 * ray's), w the direction it leaves in; cos(theta) = dot(d, w), so g > 0
 * scatters forward. A phase function is normalised: its value is also the
 * density of phase_sample per unit solid angle.
 *
 * This is src/phases' interface: what media and integrators use; each plugin
 * is one file plus one line of phase_table.c (docs/plugins.md). */
#ifndef CELADON_PHASES_H
#define CELADON_PHASES_H

#include <stddef.h>

#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct phase phase_t;

/* The phase function's value (= density) for leaving along w after
 * arriving along d (both unit). */
double phase_eval(const phase_t *p, vec3 d, vec3 w);
/* A unit direction drawn from the phase function for a path arriving along d,
 * from u in [0, 1)^2; its density in *pdf. */
vec3 phase_sample(const phase_t *p, vec3 d, vec2 u, double *pdf);
void phase_destroy(phase_t *p);

/* A phase plugin: its declaration for the scene reader and its constructor
 * from a <phase> object, which returns NULL with "file:line: problem" in
 * err. */
typedef struct {
    scene_plugin_decl decl;
    phase_t *(*create)(scene_obj *o, char *err, size_t errlen);
} phase_plugin;

/* The registration table: every phase plugin, NULL-terminated. */
extern const scene_plugin_decl *const phase_plugins[];
/* The plugin named name, or NULL. */
const phase_plugin *phase_plugin_find(const char *name);
/* The phase function of a <phase> object, or Mitsuba's default (isotropic)
 * when o is NULL; NULL with "file:line: problem" in err (at names where). */
phase_t *phase_create(scene_obj *o, const scene_obj *at, char *err, size_t errlen);

#endif
