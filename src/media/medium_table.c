/* The registration table of the medium plugins, one line each: the plugin
 * NAME is `const medium_plugin medium_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "media/media.h"

#define MEDIUM_PLUGINS(X)                \
    X(medium, homogeneous)               \
    X(medium, heterogeneous)             \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(medium, MEDIUM_PLUGINS)
