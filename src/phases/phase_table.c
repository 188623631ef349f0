/* The registration table of the phase plugins, one line each: the plugin
 * NAME is `const phase_plugin phase_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "phases/phases.h"

#define PHASE_PLUGINS(X)                 \
    X(phase, isotropic)                  \
    X(phase, hg)                         \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(phase, PHASE_PLUGINS)
