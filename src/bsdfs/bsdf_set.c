/* The BSDFs of a scene, each built once from its <bsdf> object. */
#include "bsdfs/bsdf_impl.h"

const bsdf_t *bsdf_set_get(bsdf_set *set, scene_obj *o, char *err, size_t errlen)
{
    bsdf_t *b = scene_obj_map_find(&set->built, o);
    if (b)
        return b;
    const bsdf_plugin *plugin = bsdf_plugin_find(o->type);
    if (!plugin) {
        scene_obj_error(o, err, errlen, "unsupported BSDF '%s'", o->type);
        return NULL;
    }
    b = plugin->create(o, set, err, errlen);
    if (!b)
        return NULL;
    if (scene_obj_map_add(&set->built, o, b) != 0) {
        bsdf_destroy(b);
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    return b;
}

const bsdf_t *bsdf_set_default(bsdf_set *set, const scene_obj *at, char *err, size_t errlen)
{
    bsdf_t *b = scene_obj_map_find(&set->built, NULL);
    if (b)
        return b;
    /* A <bsdf type="diffuse"/> with every parameter at its default. */
    scene_obj diffuse = {.cls = SCENE_BSDF, .type = (char *)"diffuse", .file = at->file, .line = at->line};
    b = bsdf_plugin_find("diffuse")->create(&diffuse, set, err, errlen);
    if (!b)
        return NULL;
    if (scene_obj_map_add(&set->built, NULL, b) != 0) {
        bsdf_destroy(b);
        scene_obj_error(at, err, errlen, "out of memory");
        return NULL;
    }
    return b;
}

void bsdf_set_free(bsdf_set *set)
{
    for (int i = set->built.count - 1; i >= 0; i--)
        bsdf_destroy(set->built.values[i]);
    scene_obj_map_free(&set->built);
}
