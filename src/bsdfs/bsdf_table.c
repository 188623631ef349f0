/* The registration table of the BSDF plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const bsdf_plugin bsdf_NAME`
 * (docs/plugins.md). */
#include "bsdfs/bsdfs.h"

#define BSDF_PLUGINS(X)                  \
    X(bsdf, diffuse)                     \
    X(bsdf, dielectric)                  \
    X(bsdf, thindielectric)              \
    X(bsdf, roughdielectric)             \
    X(bsdf, conductor)                   \
    X(bsdf, roughconductor)              \
    X(bsdf, plastic)                     \
    X(bsdf, roughplastic)                \
    X(bsdf, twosided)

SCENE_PLUGIN_TABLE(bsdf, BSDF_PLUGINS)
