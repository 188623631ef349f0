/* Dispatch to an integrator plugin, and its allocation. */
#include <stdlib.h>

#include "core/core.h"
#include "integrators/integrator_impl.h"

rgb integrator_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                  sampler_stream *smp, double *aov)
{
    return in->ops->li(in, sc, ray, tmin, tmax, smp, aov);
}

integrator_t *integrator_alloc(const scene_obj *o, const integrator_ops *ops, const void *data, size_t data_size,
                               char *err, size_t errlen)
{
    void *at;
    integrator_t *in = record_alloc(sizeof *in, data, data_size, &at);
    if (!in) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    in->ops = ops;
    in->data = at;
    return in;
}

void integrator_destroy(integrator_t *in)
{
    free(in);
}
