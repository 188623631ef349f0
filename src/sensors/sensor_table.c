/* The registration tables of the sensor plugins: cameras, films and
 * reconstruction filters, one line each. The plugin NAME of class C is
 * defined as `const C_plugin C_NAME` in its own file NAME.c (docs/plugins.md). */
#include "sensors/sensors.h"

#define SENSOR_PLUGINS(X) \
    X(sensor, perspective) \
    X(sensor, thinlens)    \
    X(sensor, orthographic) \
    /* one line per plugin, in any order */
#define FILM_PLUGINS(X) \
    X(film, hdrfilm)    \
    /* one line per plugin, in any order */
#define RFILTER_PLUGINS(X) \
    X(rfilter, box)        \
    X(rfilter, gaussian)   \
    X(rfilter, tent)       \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(sensor, SENSOR_PLUGINS)
SCENE_PLUGIN_TABLE(film, FILM_PLUGINS)
SCENE_PLUGIN_TABLE(rfilter, RFILTER_PLUGINS)
