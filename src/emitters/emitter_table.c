/* The registration table of the emitter plugins: one line each. The plugin
 * NAME is defined in its own file NAME.c as `const emitter_plugin
 * emitter_NAME` (docs/plugins.md). */
#include "emitters/emitters.h"

#define EMITTER_PLUGINS(X) \
    X(area)                \
    X(constant)            \
    X(envmap)              \
    X(point)               \
    X(directional)

#define DECLARE(name) extern const emitter_plugin emitter_##name;
EMITTER_PLUGINS(DECLARE)

#define ENTRY(name) &emitter_##name.decl,
const scene_plugin_decl *const emitter_plugins[] = {EMITTER_PLUGINS(ENTRY) NULL};

const emitter_plugin *emitter_plugin_find(const char *name)
{
    return (const emitter_plugin *)scene_plugin_table_find(emitter_plugins, name);
}
