/* The registration table of the shape plugins: one line each. The plugin
 * NAME is defined in its own file NAME.c as `const shape_plugin shape_NAME`
 * (docs/plugins.md). */
#include "shapes/shapes.h"

#define SHAPE_PLUGINS(X) \
    X(obj)               \
    X(ply)               \
    X(rectangle)         \
    X(cube)              \
    X(disk)              \
    X(sphere)            \
    X(cylinder)          \
    X(sor)

#define DECLARE(name) extern const shape_plugin shape_##name;
SHAPE_PLUGINS(DECLARE)

#define ENTRY(name) &shape_##name.decl,
const scene_plugin_decl *const shape_plugins[] = {SHAPE_PLUGINS(ENTRY) NULL};

const shape_plugin *shape_plugin_find(const char *name)
{
    return (const shape_plugin *)scene_plugin_table_find(shape_plugins, name);
}
