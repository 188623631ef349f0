/* The registration table of the shape plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const shape_plugin shape_NAME`
 * (docs/plugins.md). */
#include "shapes/shapes.h"

#define SHAPE_PLUGINS(X)                 \
    X(shape, obj)                        \
    X(shape, ply)                        \
    X(shape, rectangle)                  \
    X(shape, cube)                       \
    X(shape, disk)                       \
    X(shape, sphere)                     \
    X(shape, cylinder)                   \
    X(shape, sor)

SCENE_PLUGIN_TABLE(shape, SHAPE_PLUGINS)
