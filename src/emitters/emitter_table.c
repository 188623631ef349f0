/* The registration table of the emitter plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const emitter_plugin emitter_NAME`
 * (docs/plugins.md). */
#include "emitters/emitters.h"

#define EMITTER_PLUGINS(X)               \
    X(emitter, area)                     \
    X(emitter, constant)                 \
    X(emitter, envmap)                   \
    X(emitter, point)                    \
    X(emitter, directional)

SCENE_PLUGIN_TABLE(emitter, EMITTER_PLUGINS)
