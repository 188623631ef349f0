/* The registration table of the integrator plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const integrator_plugin integrator_NAME`
 * (docs/plugins.md). */
#include "integrators/integrators.h"

#define INTEGRATOR_PLUGINS(X)            \
    X(integrator, path)

SCENE_PLUGIN_TABLE(integrator, INTEGRATOR_PLUGINS)
