/* The registration table of the sampler plugins, one line each: the plugin
 * NAME is `const sampler_plugin sampler_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "samplers/samplers.h"

#define SAMPLER_PLUGINS(X)               \
    X(sampler, independent)              \
    X(sampler, stratified)               \
    X(sampler, multijitter)              \
    X(sampler, orthogonal)               \
    X(sampler, ldsampler)                \
    X(sampler, zsobol)                   \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(sampler, SAMPLER_PLUGINS)
