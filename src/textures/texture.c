/* What every texture shares: evaluation through the uv transform,
 * allocation, the to_uv parameter, and the set of a scene's textures. */
#include <stdlib.h>

#include "core/core.h"
#include "textures/texture_impl.h"

static vec2 uv_apply(const uv_transform *t, vec2 uv)
{
    return v2(t->m[0][0] * uv.x + t->m[0][1] * uv.y + t->m[0][2], t->m[1][0] * uv.x + t->m[1][1] * uv.y + t->m[1][2]);
}

rgb texture_eval_at(const texture_t *t, const texture_point *at)
{
    if (t->ops->lookup_at)
        return t->ops->lookup_at(t, at);
    return t->ops->lookup(t, uv_apply(&t->to_uv, at->uv));
}

rgb texture_eval(const texture_t *t, vec2 uv)
{
    return texture_eval_at(t, &(texture_point){.uv = uv});
}

rgb texture_mean(const texture_t *t)
{
    return t->mean;
}

double texture_eval_1(const texture_t *t, const texture_point *at)
{
    if (t->ops->lookup_1)
        return t->ops->lookup_1(t, uv_apply(&t->to_uv, at->uv));
    return rgb_luminance(texture_eval_at(t, at));
}

/* By the chain rule through uv' = A uv + b: the gradient by uv is A^T
 * times the one by uv'. */
vec2 texture_eval_1_gradient(const texture_t *t, vec2 uv)
{
    if (!t->ops->gradient_1)
        return v2(0.0, 0.0);
    vec2 g = t->ops->gradient_1(t, uv_apply(&t->to_uv, uv));
    const double(*m)[3] = t->to_uv.m;
    return v2(m[0][0] * g.x + m[1][0] * g.y, m[0][1] * g.x + m[1][1] * g.y);
}

void texture_resolution(const texture_t *t, int *width, int *height)
{
    *width = t->width;
    *height = t->height;
}

texture_t *texture_alloc(const texture_ops *ops, size_t data_size)
{
    void *at;
    texture_t *t = record_alloc(sizeof *t, NULL, data_size, &at);
    if (!t)
        return NULL;
    t->ops = ops;
    t->to_uv = (uv_transform){{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}}};
    t->width = t->height = 1;
    t->data = at;
    return t;
}

void texture_mesh_free(texture_mesh *m)
{
    for (int i = 0; i < m->count; i++) {
        free(m->items[i].name);
        free(m->items[i].values);
    }
    free(m->items);
    m->items = NULL;
    m->count = 0;
}

void texture_destroy(texture_t *t)
{
    if (!t)
        return;
    if (t->ops->release)
        t->ops->release(t->data);
    free(t);
}

uv_transform texture_to_uv_param(scene_obj *o)
{
    transform4 t = scene_obj_transform(o, "to_uv");
    uv_transform u;
    for (int i = 0; i < 2; i++)
        u.m[i][0] = t.m[i][0], u.m[i][1] = t.m[i][1], u.m[i][2] = t.m[i][3];
    return u;
}

const texture_t *texture_set_get(texture_set *set, scene_obj *o, char *err, size_t errlen)
{
    texture_t *t = scene_obj_map_find(&set->built, o);
    if (t)
        return t;
    const texture_plugin *plugin = texture_plugin_find(o->type);
    if (!plugin) {
        scene_obj_error(o, err, errlen, "unsupported texture '%s'", o->type);
        return NULL;
    }
    t = plugin->create(o, err, errlen);
    if (!t)
        return NULL;
    if (scene_obj_map_add(&set->built, o, t) != 0) {
        texture_destroy(t);
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    return t;
}

void texture_set_free(texture_set *set)
{
    for (int i = 0; i < set->built.count; i++)
        texture_destroy(set->built.values[i]);
    scene_obj_map_free(&set->built);
}
