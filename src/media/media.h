/* Participating media in the sense of Mitsuba 3: what fills the inside (or
 * outside) of a shape, absorbing and scattering light along rays. Plugins
 * (medium_table.c): `homogeneous` and `heterogeneous`. A medium has an
 * extinction sigma_t = scale * sigma_t(x) and a single-scattering albedo
 * albedo(x) (both RGB volumes: src/volumes), and a phase function
 * (src/phases). Shapes name them as their `interior` and `exterior`; the
 * `volpath` integrator tracks which one a ray is in.
 *
 * Colour: sigma_t may differ per channel. Free flights are drawn by
 * spectral tracking (Kutz et al. 2017) against one majorant, the largest
 * extinction of any channel anywhere: each tentative collision is an
 * absorption, a real scattering or a null collision with probabilities
 * proportional to the largest channel of beta times sigma_a, sigma_s and
 * sigma_n = majorant - sigma_t, and beta takes the ratio that keeps every
 * channel unbiased. A grey homogeneous medium has no null collisions: its
 * flights are the exact exponential ones. Transmittance along a shadow ray
 * is exp(-sigma_t d) in a homogeneous medium, ratio tracking in a
 * heterogeneous one. A heterogeneous medium is empty outside the box of
 * its sigma_t volume (volumes.h), as Mitsuba's.
 *
 * This is src/media's interface: what integrators and the scene build use;
 * each plugin is one file plus one line of medium_table.c (docs/plugins.md). */
#ifndef CELADON_MEDIA_H
#define CELADON_MEDIA_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/color.h"
#include "celadon/rng.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"
#include "phases/phases.h"

typedef struct medium medium_t;

typedef enum {
    MEDIUM_PASSED,    /* no real collision before tmax */
    MEDIUM_SCATTERED, /* scattered at *t */
    MEDIUM_ABSORBED,  /* the path ends */
} medium_event;

/* Tracks ray r (unit direction) through the medium over (0, tmax), tmax
 * possibly infinite, from rng's numbers: the first real collision, beta
 * multiplied by the tracking's weight. Thread-safe. */
medium_event medium_sample(const medium_t *m, const ray3 *r, double tmax, rng_t *rng, rgb *beta, double *t);
/* The transmittance of the medium along r (unit direction) over (0, tmax):
 * exact in a homogeneous medium, an unbiased estimate from rng's numbers in
 * a heterogeneous one. */
rgb medium_transmittance(const medium_t *m, const ray3 *r, double tmax, rng_t *rng);
const phase_t *medium_phase(const medium_t *m);
/* Whether paths scattered in the medium sample emitters (Mitsuba's
 * sample_emitters). */
bool medium_samples_emitters(const medium_t *m);
void medium_destroy(medium_t *m);

/* A medium plugin: its declaration for the scene reader and its constructor
 * from a <medium> object, which returns NULL with "file:line: problem" in
 * err. */
typedef struct {
    scene_plugin_decl decl;
    medium_t *(*create)(scene_obj *o, char *err, size_t errlen);
} medium_plugin;

/* The registration table: every medium plugin, NULL-terminated. */
extern const scene_plugin_decl *const medium_plugins[];
/* The plugin named name, or NULL. */
const medium_plugin *medium_plugin_find(const char *name);

/* The media of a scene: one per <medium> object, however often it is
 * referenced, destroyed together by medium_set_free. Zero-initialise. */
typedef struct {
    scene_obj_map built;
} medium_set;

/* The medium of the <medium> object mo, built on first use. 0, or -1 with
 * "file:line: problem" in err. */
int medium_set_get(medium_set *set, scene_obj *mo, const medium_t **out, char *err, size_t errlen);
/* The medium the object property name of o names (a shape's interior or
 * exterior), built on first use; NULL in *out when o has no such property.
 * 0, or -1 with "file:line: problem" in err. */
int medium_set_param(medium_set *set, scene_obj *o, const char *name, const medium_t **out, char *err,
                     size_t errlen);
void medium_set_free(medium_set *set);

#endif
