/* The registration table of the integrator plugins, one line each: the plugin
 * NAME is `const integrator_plugin integrator_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "integrators/integrators.h"

#define INTEGRATOR_PLUGINS(X)            \
    X(integrator, path)                  \
    X(integrator, direct)                \
    X(integrator, depth)                 \
    X(integrator, aov)                   \
    X(integrator, moment)                \
    X(integrator, volpath)               \
    X(integrator, volpathmis)            \
    X(integrator, ptracer)               \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(integrator, INTEGRATOR_PLUGINS)
