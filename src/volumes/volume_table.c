/* The registration table of the volume plugins, one line each: the plugin
 * NAME is `const volume_plugin volume_NAME`, defined in its own file NAME.c
 * (docs/plugins.md). */
#include "volumes/volumes.h"

#define VOLUME_PLUGINS(X)                \
    X(volume, constvolume)               \
    X(volume, gridvolume)                \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(volume, VOLUME_PLUGINS)
