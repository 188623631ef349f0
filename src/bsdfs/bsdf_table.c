/* The registration table of the BSDF plugins: one line each. The plugin NAME
 * is defined in its own file NAME.c as `const bsdf_plugin bsdf_NAME`
 * (docs/plugins.md). */
#include "bsdfs/bsdfs.h"

#define BSDF_PLUGINS(X) \
    X(diffuse)          \
    X(dielectric)       \
    X(thindielectric)   \
    X(roughdielectric)  \
    X(conductor)        \
    X(roughconductor)   \
    X(plastic)          \
    X(roughplastic)     \
    X(twosided)

#define DECLARE(name) extern const bsdf_plugin bsdf_##name;
BSDF_PLUGINS(DECLARE)

#define ENTRY(name) &bsdf_##name.decl,
const scene_plugin_decl *const bsdf_plugins[] = {BSDF_PLUGINS(ENTRY) NULL};

const bsdf_plugin *bsdf_plugin_find(const char *name)
{
    return (const bsdf_plugin *)scene_plugin_table_find(bsdf_plugins, name);
}
