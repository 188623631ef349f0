/* Emitters in the sense of Mitsuba 3: `area` (a shape's surface radiates),
 * the environment `constant` and `envmap`, and the delta lights `point` and
 * `directional`. Next-event estimation picks one of a scene's emitters by
 * its estimated contribution at the shading point (a light tree:
 * emitter_list_pick) and samples it from there; rays find surface emitters
 * through their shape's hit and the environment by escaping the scene.
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
/* True only where emitter_sample from ref certainly returns 0 whatever u:
 * ref behind a flat emitter that radiates from its front only
 * (shape_faces_away); next-event estimation then draws no numbers for it. */
bool emitter_faces_away(const emitter_t *e, vec3 ref);
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

/* What light selection knows of an emitter: where it is, which way it
 * shines and how strongly (Estevez & Kulla 2018, "Importance sampling of
 * many lights with adaptive tree splitting"; pbrt-v4's LightBounds). Its
 * importance at a shading point estimates the irradiance it gives there. */
typedef struct {
    bool infinite;      /* at infinity (environment, directional): phi alone */
    vec3 lo, hi;        /* world bounds (a point light: lo = hi) */
    vec3 axis;          /* every surface normal of the light lies within */
    double cos_theta_o; /*   acos(cos_theta_o) of axis (-1: any direction) */
    double cos_theta_e; /* light leaves within acos(cos_theta_e) of a normal */
    /* The irradiance it gives a surface facing it: at unit distance for a
     * finite light (radiance times its largest projected area; intensity for
     * a point), at any point for an infinite one (pi times its mean radiance;
     * the irradiance of a directional light). Components: the largest of
     * RGB. 0: never worth picking. */
    double phi;
} light_bounds;

void emitter_bounds(const emitter_t *e, light_bounds *out);

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

typedef struct light_tree light_tree;

/* A scene's emitters, in the order built, and the tree that picks them. */
typedef struct {
    emitter_t **items;
    int count;
    const emitter_t *env; /* the environment emitter among them, or NULL */
    light_tree *tree;     /* emitter_list_commit's */
} emitter_list;

/* Appends e (the list then owns it): 0, or -1 when out of memory. */
int emitter_list_add(emitter_list *l, emitter_t *e);
/* Builds the light tree once every emitter is in: 0, or -1 when out of
 * memory. */
int emitter_list_commit(emitter_list *l);
void emitter_list_free(emitter_list *l);

/* A shading point as light selection sees it: its position and surface
 * normal (a zero normal: none). */
typedef struct {
    vec3 p, n;
} emitter_ref;

/* An emitter for next-event estimation at ref, picked with u with a
 * probability (*pmf) in proportion to its estimated contribution there:
 * infinite emitters by their phi, the others down a bounding volume
 * hierarchy of their light_bounds, each step in proportion to the two
 * children's importance (pbrt-v4's BVHLightSampler). *u_reuse is u's
 * remainder within the pick, uniform in [0, 1) again and independent of
 * which emitter was picked. NULL when no emitter can contribute. */
const emitter_t *emitter_list_pick(const emitter_list *l, const emitter_ref *ref, double u, double *pmf,
                                   double *u_reuse);
/* The list's one light when emitter_list_pick always picks it (one finite
 * light, no infinite one), else NULL. */
const emitter_t *emitter_list_only(const emitter_list *l);
/* The probability emitter_list_pick picks e at ref (what MIS weighs a
 * BSDF-sampled hit of e with). */
double emitter_list_pmf(const emitter_list *l, const emitter_ref *ref, const emitter_t *e);

#endif
