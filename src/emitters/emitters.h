/* Emitters in the sense of Mitsuba 3: `area` (a shape's surface radiates),
 * the environment `constant` and `envmap`, and the delta lights `point` and
 * `directional`. Next-event estimation samples them from a reference point;
 * rays find surface emitters through their shape's hit and the environment
 * by escaping the scene.
 *
 * This is src/emitters' interface: what integrators and the scene build use.
 * The plugins' own helpers are in emitter_impl.h; each plugin is one file
 * plus one line of emitter_table.c (docs/plugins.md). */
#ifndef CELADON_EMITTERS_H
#define CELADON_EMITTERS_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"
#include "shapes/shapes.h"
#include "textures/textures.h"

typedef struct emitter emitter_t;

/* One emitter sample seen from a reference point. */
typedef struct {
    vec3 wi;           /* unit, from the reference point toward the emitter */
    double dist;       /* INFINITY for directions at infinity */
    vec3 p, n;         /* the sampled point and its normal (area) */
    double eps;        /* offset of the sampled point (area) */
    rgb value;         /* emitted radiance (or intensity / dist^2, irradiance) arriving */
    double pdf;        /* solid angle density (1 for delta emitters) */
    bool delta;
} emitter_sample_rec;

/* u: three uniform numbers. Returns 0 when the sample carries nothing. */
int emitter_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out);
/* A surface emitter: the radiance leaving its shape's hit toward -dir, and
 * the solid-angle density with which emitter_sample would have picked it
 * from ref. */
rgb emitter_eval_hit(const emitter_t *e, const surface_hit *hit, vec3 dir);
double emitter_pdf_hit(const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir);
/* An environment emitter: the radiance arriving from direction dir (unit,
 * pointing away from the scene), and its sampling density. */
rgb emitter_eval_env(const emitter_t *e, vec3 dir);
double emitter_pdf_env(const emitter_t *e, vec3 dir);
void emitter_destroy(emitter_t *e);

/* What an emitter plugin is. */
enum {
    EMITTER_SURFACE = 1,     /* nested in a shape, whose surface radiates */
    EMITTER_ENVIRONMENT = 2, /* at infinity: rays that leave the scene see it */
};

/* An emitter plugin: its declaration for the scene reader, its kind and its
 * constructor from an <emitter> object (shape: the shape it is nested in, or
 * NULL; textures its parameters name are built in textures), which returns
 * NULL with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    unsigned flags; /* EMITTER_SURFACE, EMITTER_ENVIRONMENT */
    emitter_t *(*create)(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen);
} emitter_plugin;

/* The registration table: every emitter plugin, NULL-terminated. */
extern const scene_plugin_decl *const emitter_plugins[];
/* The plugin named name, or NULL. */
const emitter_plugin *emitter_plugin_find(const char *name);

/* A scene's emitters, in the order built (next-event estimation picks
 * them uniformly by index). */
typedef struct {
    emitter_t **items;
    int count;
    const emitter_t *env; /* the environment emitter among them, or NULL */
} emitter_list;

/* Appends e (the list then owns it): 0, or -1 when out of memory. */
int emitter_list_add(emitter_list *l, emitter_t *e);
void emitter_list_free(emitter_list *l);

#endif
