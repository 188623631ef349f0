/* The registration table of the texture plugins: one line each. The plugin
 * NAME is defined in its own file as `const texture_plugin texture_NAME`. */
#include "textures/textures.h"

#define TEXTURE_PLUGINS(X) \
    X(bitmap)              \
    X(checkerboard)

#define DECLARE(name) extern const texture_plugin texture_##name;
TEXTURE_PLUGINS(DECLARE)

#define ENTRY(name) &texture_##name.decl,
const scene_plugin_decl *const texture_plugins[] = {TEXTURE_PLUGINS(ENTRY) NULL};

const texture_plugin *texture_plugin_find(const char *name)
{
    return (const texture_plugin *)scene_plugin_table_find(texture_plugins, name);
}
