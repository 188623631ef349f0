/* The registration table of the sampler plugins: one line each. The plugin
 * NAME is defined in its own file NAME.c as `const sampler_plugin
 * sampler_NAME` (docs/plugins.md). */
#include "samplers/samplers.h"

#define SAMPLER_PLUGINS(X) X(independent)

#define DECLARE(name) extern const sampler_plugin sampler_##name;
SAMPLER_PLUGINS(DECLARE)

#define ENTRY(name) &sampler_##name.decl,
const scene_plugin_decl *const sampler_plugins[] = {SAMPLER_PLUGINS(ENTRY) NULL};

const sampler_plugin *sampler_plugin_find(const char *name)
{
    return (const sampler_plugin *)scene_plugin_table_find(sampler_plugins, name);
}
