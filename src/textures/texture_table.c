/* The registration table of the texture plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const texture_plugin texture_NAME`
 * (docs/plugins.md). */
#include "textures/textures.h"

#define TEXTURE_PLUGINS(X)               \
    X(texture, bitmap)                   \
    X(texture, checkerboard)

SCENE_PLUGIN_TABLE(texture, TEXTURE_PLUGINS)
