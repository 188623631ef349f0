/* Mitsuba's `volpathmis` integrator: in Mitsuba, volpath with spectral MIS
 * over its wavelengths and MIS between free-flight and emitter sampling of
 * the same path. Its estimate has the same expectation as `volpath`'s, and
 * here it is volpath (which tracks every RGB channel at once: media.h), with
 * the same parameters. */
#include "integrators/integrator_impl.h"

const integrator_plugin integrator_volpathmis = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "volpathmis", .params = integrator_volpath_params},
    .create = integrator_volpath_create,
};
