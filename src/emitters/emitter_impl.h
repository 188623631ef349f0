/* What the emitter plugins share: the emitter record they fill. Private to
 * src/emitters/. */
#ifndef CELADON_EMITTER_IMPL_H
#define CELADON_EMITTER_IMPL_H

#include "emitters/emitters.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    /* Fills out (eps, delta and dist are preset to 0, false, INFINITY). */
    int (*sample)(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out);
    /* Surface emitters only (NULL otherwise). */
    rgb (*eval_hit)(const emitter_t *e, const surface_hit *hit, vec3 dir);
    double (*pdf_hit)(const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir);
    /* Environment emitters only (NULL otherwise). */
    rgb (*eval_env)(const emitter_t *e, vec3 dir);
    double (*pdf_env)(const emitter_t *e, vec3 dir);
    /* Frees what data points to (not data itself); may be NULL. */
    void (*release)(void *data);
    /* What light selection needs (emitters.h): required. */
    void (*bounds)(const emitter_t *e, light_bounds *out);
    /* Surface emitters: only the front of the shape radiates (sample
     * refuses a point seen from behind): emitter_faces_away. */
    bool front_only;
} emitter_ops;

struct emitter {
    const emitter_ops *ops;
    const shape_t *shape; /* surface emitters: the shape that radiates */
    void *data;           /* the plugin's, allocated with the emitter */
    int index;            /* in its emitter_list */
};

/* Frees what emitter_list_commit built (NULL: nothing). */
void light_tree_destroy(light_tree *t);

/* The bounds of a light at infinity giving irradiance phi. */
void emitter_bounds_infinite(double phi, light_bounds *out);
/* The bounds of a point light of intensity phi at p. */
void emitter_bounds_point(vec3 p, double phi, light_bounds *out);

/* One allocation holding the emitter and a copy of the data_size bytes at
 * data; NULL when out of memory, with err naming o. */
emitter_t *emitter_alloc(const scene_obj *o, const emitter_ops *ops, const void *data, size_t data_size, char *err,
                         size_t errlen);

/* The sample of a light at the point pos seen from ref (a delta light):
 * wi, dist, p, pdf 1, delta; 0 when ref is at pos. */
int emitter_delta_sample(vec3 pos, vec3 ref, emitter_sample_rec *out);

/* A constant color parameter (def when absent) as rgb. */
rgb emitter_rgb_param(scene_obj *o, const char *name, double def);

#endif
