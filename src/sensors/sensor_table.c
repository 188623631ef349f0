/* The registration tables of the sensor plugins: cameras, films and
 * reconstruction filters, one line each. The plugin NAME of class C is
 * defined as `const C_plugin C_NAME` in its own file NAME.c (the filters
 * that change nothing share rfilters.c; docs/plugins.md). */
#include "sensors/sensors.h"

#define SENSOR_PLUGINS(X) X(perspective)
#define FILM_PLUGINS(X) X(hdrfilm)
#define RFILTER_PLUGINS(X) \
    X(box)                 \
    X(gaussian)            \
    X(tent)

#define DECLARE_SENSOR(name) extern const sensor_plugin sensor_##name;
#define DECLARE_FILM(name) extern const film_plugin film_##name;
#define DECLARE_RFILTER(name) extern const rfilter_plugin rfilter_##name;
SENSOR_PLUGINS(DECLARE_SENSOR)
FILM_PLUGINS(DECLARE_FILM)
RFILTER_PLUGINS(DECLARE_RFILTER)

#define ENTRY_SENSOR(name) &sensor_##name.decl,
#define ENTRY_FILM(name) &film_##name.decl,
#define ENTRY_RFILTER(name) &rfilter_##name.decl,
const scene_plugin_decl *const sensor_plugins[] = {SENSOR_PLUGINS(ENTRY_SENSOR) NULL};
const scene_plugin_decl *const film_plugins[] = {FILM_PLUGINS(ENTRY_FILM) NULL};
const scene_plugin_decl *const rfilter_plugins[] = {RFILTER_PLUGINS(ENTRY_RFILTER) NULL};

const sensor_plugin *sensor_plugin_find(const char *name)
{
    return (const sensor_plugin *)scene_plugin_table_find(sensor_plugins, name);
}

const film_plugin *film_plugin_find(const char *name)
{
    return (const film_plugin *)scene_plugin_table_find(film_plugins, name);
}

const rfilter_plugin *rfilter_plugin_find(const char *name)
{
    return (const rfilter_plugin *)scene_plugin_table_find(rfilter_plugins, name);
}
