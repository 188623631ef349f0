/* The registration table of the emitter plugins, one line each: the plugin
 * NAME is `const emitter_plugin emitter_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "emitters/emitters.h"

#define EMITTER_PLUGINS(X)               \
    X(emitter, area)                     \
    X(emitter, constant)                 \
    X(emitter, envmap)                   \
    X(emitter, point)                    \
    X(emitter, directional)              \
    X(emitter, spot)                     \
    X(emitter, projector)                \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(emitter, EMITTER_PLUGINS)
