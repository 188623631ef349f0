/* Mitsuba's `depth` integrator: the distance along the camera ray to the
 * first surface, as a gray value (0 where the ray escapes, and alpha 1
 * where it hits). */
#include "integrators/integrator_impl.h"

static rgb depth_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                    sampler_stream *smp, double *aov)
{
    (void)in, (void)smp;
    surface_hit hit;
    bool found = shape_list_intersect(sc->shapes, ray, tmin, tmax, &hit);
    if (aov) {
        integrator_clear_aovs(aov, found);
        if (found)
            integrator_first_hit_aovs(aov, &hit);
    }
    return rgb_gray(found ? hit.t : 0.0);
}

static const integrator_ops depth_ops = {depth_li, NULL};

static integrator_t *depth_create(scene_obj *o, char *err, size_t errlen)
{
    char none = 0;
    return integrator_alloc(o, &depth_ops, &none, sizeof none, err, errlen);
}

const integrator_plugin integrator_depth = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "depth"},
    .create = depth_create,
};
