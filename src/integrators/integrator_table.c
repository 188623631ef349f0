/* The registration table of the integrator plugins: one line each. The
 * plugin NAME is defined in its own file NAME.c as `const integrator_plugin
 * integrator_NAME` (docs/plugins.md). */
#include "integrators/integrators.h"

#define INTEGRATOR_PLUGINS(X) X(path)

#define DECLARE(name) extern const integrator_plugin integrator_##name;
INTEGRATOR_PLUGINS(DECLARE)

#define ENTRY(name) &integrator_##name.decl,
const scene_plugin_decl *const integrator_plugins[] = {INTEGRATOR_PLUGINS(ENTRY) NULL};

const integrator_plugin *integrator_plugin_find(const char *name)
{
    return (const integrator_plugin *)scene_plugin_table_find(integrator_plugins, name);
}
