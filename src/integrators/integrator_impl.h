/* What an integrator plugin provides. Private to src/integrators/. */
#ifndef CELADON_INTEGRATOR_IMPL_H
#define CELADON_INTEGRATOR_IMPL_H

#include "integrators/integrators.h"

typedef struct {
    rgb (*li)(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
              sampler_stream *smp, double *aov);
    /* Frees what data points to (not data itself); may be NULL. */
    void (*release)(void *data);
} integrator_ops;

struct integrator {
    const integrator_ops *ops;
    const char *type; /* the plugin's name */
    void *data;       /* the plugin's, allocated with the integrator */
    char **channels;  /* its own output channels' names, owned */
    int nchannels;
};

/* One allocation holding the integrator and a copy of the data_size bytes at
 * data; NULL when out of memory, with err naming o. */
integrator_t *integrator_alloc(const scene_obj *o, const integrator_ops *ops, const void *data, size_t data_size,
                               char *err, size_t errlen);
/* The AOV values of a camera ray's first hit: its depth, shading normal
 * and the BSDF's albedo, as the rough vertex's too (the alpha is the
 * integrator's to say). */
void integrator_first_hit_aovs(double *aov, const surface_hit *hit);
/* The AOV values of a sample: all zero, the alpha 1 when covered. */
void integrator_clear_aovs(double *aov, bool covered);
/* The rough-vertex features (INTEGRATOR_AOV_ROUGH_*) of a path's vertex
 * hit, path_length from the camera, the path's weight weight there; returns
 * whether hit is rough (its BSDF has a non-delta lobe: the features stay
 * those of this vertex) rather than a mirror, glass or sheet the path goes
 * through. integrator_clear_rough_aovs zeroes them (the path escaped). */
bool integrator_rough_hit_aovs(double *aov, const surface_hit *hit, double path_length, rgb weight);
void integrator_clear_rough_aovs(double *aov);

/* A ray leaving hit toward w, lifted off the surface on w's side. */
ray3 integrator_spawn(const surface_hit *hit, vec3 w);
/* Whether nothing blocks the segment from hit to the emitter sample (any
 * surface does, as for Mitsuba's shadow rays). */
bool integrator_unoccluded(const shape_list *shapes, const surface_hit *hit, const emitter_sample_rec *es);

/* Runs a nested integrator: its radiance, its fixed AOV values into fixed
 * (INTEGRATOR_AOV_COUNT of them; may be NULL) and its own channels into
 * own. */
rgb integrator_nested_li(const integrator_t *nested, const integrator_scene *sc, const ray3 *ray, double tmin,
                         double tmax, sampler_stream *smp, double *fixed, double *own);

/* Appends an output channel named prefix.suffix (or whichever is not
 * empty); 0, or -1 when out of memory. */
int integrator_add_channel(integrator_t *in, const char *prefix, const char *suffix);
/* Appends the channels of a nested integrator named name: name.<each of
 * its own channels>. 0, or -1 when out of memory. */
int integrator_add_nested_channels(integrator_t *in, const char *name, const integrator_t *nested);
/* The integrators nested in o, built in order into out (at most max): their
 * number, or -1 with err. */
int integrator_nested(scene_obj *o, integrator_t **out, int max, char *err, size_t errlen);
/* The name Mitsuba gives a nested object: its name attribute, or "_arg_i"
 * for the i-th unnamed one. */
void integrator_nested_name(const scene_obj *o, int i, char *buf, size_t len);

/* The `volpath` integrator's constructor and parameters, which
 * `volpathmis` shares (volpath.c). */
integrator_t *integrator_volpath_create(scene_obj *o, char *err, size_t errlen);
extern const scene_param_decl integrator_volpath_params[];

#endif
