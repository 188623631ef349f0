/* The registration table of the shape plugins, one line each: the plugin
 * NAME is `const shape_plugin shape_NAME`, defined in its own file NAME.c
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
    X(shape, sor)                        \
    X(shape, serialized)                 \
    X(shape, linearcurve)                \
    X(shape, bsplinecurve)               \
    X(shape, shapegroup)                 \
    X(shape, instance)                   \
    X(shape, sdfgrid)                    \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(shape, SHAPE_PLUGINS)
