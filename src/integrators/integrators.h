/* Integrators in the sense of Mitsuba 3: the radiance arriving along a camera
 * ray, estimated from one pixel sample's numbers, and the integrator's own
 * output channels (Mitsuba's AOVs). Plugins: `path`, `direct`, `depth`,
 * `aov`, `moment`.
 *
 * This is src/integrators' interface: what the render loop uses; each
 * plugin is one file plus one line of integrator_table.c (docs/plugins.md). */
#ifndef CELADON_INTEGRATORS_H
#define CELADON_INTEGRATORS_H

#include <stddef.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"
#include "emitters/emitters.h"
#include "samplers/samplers.h"
#include "shapes/shapes.h"

typedef struct integrator integrator_t;

/* What an integrator traces against: the scene's shapes (with their BSDFs
 * and area emitters) and its emitters; and the medium camera rays start in
 * (the sensor's; NULL: none), which only volpath sees. */
typedef struct {
    const shape_list *shapes;
    const emitter_list *emitters;
    const struct medium *camera_medium;
} integrator_scene;

/* The first hit's values for the AOV channels, in this order: depth (the
 * distance along the camera ray), the world shading normal, the BSDF's
 * albedo, zero where the ray escapes; the sample's alpha: 1 when it counts
 * as covered (Mitsuba's "valid" sample: the ray met a surface other than a
 * null one, or sees a visible environment), else 0; then the same three
 * features at the first rough vertex, the denoiser's (docs/rendering.md,
 * "AOVs"): the path's first surface with a non-delta lobe, seen through
 * the mirrors, glass and sheets before it (depth: the path's length to it;
 * albedo: times the path's weight there), zero where the path escapes
 * before one. Integrators other than `path` give the first hit's. Then the
 * specular part of the radiance: what the path gathers after leaving its
 * first rough vertex by a glossy or delta lobe (the rest, direct light at
 * that vertex included, is the diffuse part); and the light seen in the
 * mirror direction at that vertex, where its BSDF has a delta reflection
 * (a coat): the emitter met along the mirrored ray (or the environment),
 * whichever lobe the path then samples. 0 for other integrators. */
enum {
    INTEGRATOR_AOV_DEPTH = 0,
    INTEGRATOR_AOV_NORMAL = 1,
    INTEGRATOR_AOV_ALBEDO = 4,
    INTEGRATOR_AOV_ALPHA = 7,
    INTEGRATOR_AOV_ROUGH_DEPTH = 8,
    INTEGRATOR_AOV_ROUGH_NORMAL = 9,
    INTEGRATOR_AOV_ROUGH_ALBEDO = 12,
    INTEGRATOR_AOV_SPECULAR = 15,
    INTEGRATOR_AOV_MIRROR = 18,
    INTEGRATOR_AOV_COUNT = 21
};

/* Radiance along ray (t in (tmin, tmax)) from the numbers of smp; aov (may
 * be NULL) receives the INTEGRATOR_AOV_COUNT values above followed by the
 * integrator's own channels. Thread-safe. */
rgb integrator_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                  sampler_stream *smp, double *aov);
/* The integrator's own output channels (Mitsuba's aov_names: "dd.T",
 * "m2_nested.X", ...): how many, and the EXR name of each. */
int integrator_channel_count(const integrator_t *in);
const char *integrator_channel_name(const integrator_t *in, int i);
/* The plugin's name. */
const char *integrator_type(const integrator_t *in);
void integrator_destroy(integrator_t *in);

/* An integrator plugin: its declaration for the scene reader and its
 * constructor from an <integrator> object, which returns NULL with
 * "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    integrator_t *(*create)(scene_obj *o, char *err, size_t errlen);
} integrator_plugin;

/* The registration table: every integrator plugin, NULL-terminated. */
extern const scene_plugin_decl *const integrator_plugins[];
/* The plugin named name, or NULL. */
const integrator_plugin *integrator_plugin_find(const char *name);

#endif
