/* Mitsuba's `shapegroup` and `instance`: a group of shapes declared once
 * (it renders nothing by itself) and placed any number of times by the
 * instances that reference it, each under its own to_world. celadon expands
 * every instance into copies of the group's shapes, each placed by
 * instance.to_world · shape.to_world, so an instance renders exactly as the
 * shapes written out in its place would (shape_leaves). As in Mitsuba, the
 * shapes of a group may not emit light, and groups do not nest. */
#include <stdio.h>
#include <string.h>

#include "shapes/shape_impl.h"

static int is_type(const scene_obj *o, const char *type) { return strcmp(o->type, type) == 0; }

/* Marks everything under o read: a group no instance places is not used,
 * as in Mitsuba. */
static void mark_read(scene_obj *o)
{
    for (int i = 0; i < o->nprops; i++) {
        o->props[i].consumed = true;
        if (o->props[i].type == SCENE_OBJECT)
            mark_read(o->props[i].value.obj);
    }
    for (int i = 0; i < o->nchildren; i++)
        mark_read(o->children[i]);
}

int shape_leaves(scene_obj *o, shape_leaf *out, int max, char *err, size_t errlen)
{
    if (is_type(o, "shapegroup")) {
        mark_read(o);
        return 0;
    }
    if (!is_type(o, "instance")) {
        if (max > 0)
            out[0] = (shape_leaf){o, false, transform_identity()};
        return 1;
    }
    transform4 to_world = scene_obj_transform(o, "to_world");
    scene_obj *group = scene_obj_child(o, SCENE_SHAPE);
    int k = 0;
    for (int i = 0; i < group->nchildren; i++) {
        scene_obj *s = group->children[i];
        if (s->cls != SCENE_SHAPE)
            continue;
        if (is_type(s, "shapegroup") || is_type(s, "instance"))
            return scene_obj_error(s, err, errlen, "a shapegroup cannot hold a %s (no nested instancing)", s->type);
        if (scene_obj_child(s, SCENE_EMITTER))
            return scene_obj_error(s, err, errlen, "a shape in a shapegroup cannot emit light (nor in Mitsuba)");
        if (k < max)
            out[k] = (shape_leaf){s, true, to_world};
        k++;
    }
    return k;
}

static int group_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                        size_t errlen)
{
    (void)opt, (void)to_world, (void)sh;
    return scene_obj_error(o, err, errlen, "a %s is expanded into its shapes (shape_leaves), not built", o->type);
}

static const scene_child_decl group_children[] = {
    {SCENE_SHAPE, 1, 1 << 30, NULL},
    {SCENE_SCENE, 0, 0, NULL},
};

const shape_plugin shape_shapegroup = {
    .decl = {.cls = SCENE_SHAPE, .type = "shapegroup", .children = group_children},
    .create = group_create,
};

static const scene_param_decl instance_params[] = {
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    SHAPE_PARAMS_END,
};

static const scene_child_decl instance_children[] = {
    {SCENE_SHAPE, 1, 1, "shapegroup"},
    {SCENE_SCENE, 0, 0, NULL},
};

const shape_plugin shape_instance = {
    .decl = {.cls = SCENE_SHAPE, .type = "instance", .params = instance_params, .children = instance_children},
    .create = group_create,
};
