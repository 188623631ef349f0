/* Every plugin the renderer builds, gathered from the registration tables of
 * the kinds for the scene reader; and the scene root's own declaration. */
#include "phases/phases.h"
#include "render/scene_impl.h"
#include "volumes/volumes.h"

static const scene_child_decl scene_children[] = {
    {SCENE_SENSOR, 0, 1, NULL},           {SCENE_INTEGRATOR, 0, 1, NULL}, {SCENE_SHAPE, 0, 1 << 30, NULL},
    {SCENE_EMITTER, 0, 1 << 30, NULL},    {SCENE_BSDF, 0, 1 << 30, NULL}, {SCENE_TEXTURE, 0, 1 << 30, NULL},
    {SCENE_SCENE, 0, 0, NULL},
};

static const scene_plugin_decl scene_root = {.cls = SCENE_SCENE, .type = "scene", .children = scene_children};
static const scene_plugin_decl *const root_table[] = {&scene_root, NULL};

/* The table of each class, indexed by scene_class. */
static const scene_plugin_decl *const *const tables[SCENE_CLASS_COUNT] = {
    [SCENE_SCENE] = root_table,          [SCENE_SENSOR] = sensor_plugins,   [SCENE_FILM] = film_plugins,
    [SCENE_SAMPLER] = sampler_plugins,   [SCENE_RFILTER] = rfilter_plugins, [SCENE_INTEGRATOR] = integrator_plugins,
    [SCENE_SHAPE] = shape_plugins,       [SCENE_BSDF] = bsdf_plugins,       [SCENE_TEXTURE] = texture_plugins,
    [SCENE_EMITTER] = emitter_plugins,   [SCENE_MEDIUM] = medium_plugins,   [SCENE_PHASE] = phase_plugins,
    [SCENE_VOLUME] = volume_plugins,
};

const scene_plugin_decl *scene_plugin_find(scene_class cls, const char *type)
{
    return cls >= 0 && cls < SCENE_CLASS_COUNT ? scene_plugin_table_find(tables[cls], type) : NULL;
}

const scene_plugin_decl *scene_plugin_at(int i)
{
    for (int c = 0; c < SCENE_CLASS_COUNT && i >= 0; c++)
        for (const scene_plugin_decl *const *t = tables[c]; *t; t++, i--)
            if (i == 0)
                return *t;
    return NULL;
}
