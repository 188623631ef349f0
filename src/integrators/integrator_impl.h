/* What an integrator plugin provides. Private to src/integrators/. */
#ifndef CELADON_INTEGRATOR_IMPL_H
#define CELADON_INTEGRATOR_IMPL_H

#include "integrators/integrators.h"

typedef struct {
    rgb (*li)(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
              sampler_stream *smp, double *aov);
} integrator_ops;

struct integrator {
    const integrator_ops *ops;
    void *data; /* the plugin's, allocated with the integrator */
};

/* One allocation holding the integrator and a copy of the data_size bytes at
 * data; NULL when out of memory, with err naming o. */
integrator_t *integrator_alloc(const scene_obj *o, const integrator_ops *ops, const void *data, size_t data_size,
                               char *err, size_t errlen);

#endif
