/* The registration table of the sampler plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const sampler_plugin sampler_NAME`
 * (docs/plugins.md). */
#include "samplers/samplers.h"

#define SAMPLER_PLUGINS(X)               \
    X(sampler, independent)

SCENE_PLUGIN_TABLE(sampler, SAMPLER_PLUGINS)
