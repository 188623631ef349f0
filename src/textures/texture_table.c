/* The registration table of the texture plugins, one line each: the plugin
 * NAME is `const texture_plugin texture_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "textures/textures.h"

#define TEXTURE_PLUGINS(X)               \
    X(texture, bitmap)                   \
    X(texture, checkerboard)             \
    X(texture, rawconstant)              \
    X(texture, mesh_attribute)           \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(texture, TEXTURE_PLUGINS)
