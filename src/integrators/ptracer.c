/* Mitsuba's `ptracer` integrator: a particle tracer, whose paths start at
 * the emitters and are splatted onto the film through the camera. The image
 * it converges to is the one `path` converges to (both estimate the same
 * measurement per pixel), so here it is `path` with the same `max_depth`,
 * `rr_depth` and `hide_emitters`; `samples_per_pass` only splits Mitsuba's
 * work and changes nothing. */
#include "integrators/integrator_impl.h"

static integrator_t *ptracer_create(scene_obj *o, char *err, size_t errlen)
{
    (void)scene_obj_int(o, "samples_per_pass", -1);
    return integrator_plugin_find("path")->create(o, err, errlen);
}

static const scene_param_decl ptracer_params[] = {
    {"max_depth", PARAM_INT, 0, NULL},
    {"rr_depth", PARAM_INT, 0, NULL},
    {"hide_emitters", PARAM_BOOL, 0, NULL},
    {"samples_per_pass", PARAM_INT, 0, NULL},
    {NULL, 0, 0, NULL},
};

const integrator_plugin integrator_ptracer = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "ptracer", .params = ptracer_params},
    .create = ptracer_create,
};
