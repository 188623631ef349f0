/* The registration table of the BSDF plugins, one line each: the plugin
 * NAME is `const bsdf_plugin bsdf_NAME`, defined in its own file NAME.c
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
    X(bsdf, twosided)                    \
    X(bsdf, null)                        \
    X(bsdf, mask)                        \
    X(bsdf, blendbsdf)                   \
    X(bsdf, normalmap)                   \
    X(bsdf, bumpmap)                     \
    X(bsdf, principled)                  \
    X(bsdf, principledthin)              \
    X(bsdf, hair)                        \
    /* one line per plugin, in any order */

SCENE_PLUGIN_TABLE(bsdf, BSDF_PLUGINS)
