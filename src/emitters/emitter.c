/* What every emitter shares: dispatch to its plugin, allocation, and the
 * list of a scene's emitters. */
#include <stdlib.h>

#include "core/core.h"
#include "emitters/emitter_impl.h"

int emitter_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    out->eps = 0.0;
    out->delta = false;
    out->dist = INFINITY;
    return e->ops->sample(e, ref, u, out);
}

bool emitter_faces_away(const emitter_t *e, vec3 ref)
{
    return e->ops->front_only && shape_faces_away(e->shape, ref);
}

rgb emitter_eval_hit(const emitter_t *e, const surface_hit *hit, vec3 dir)
{
    return e->ops->eval_hit(e, hit, dir);
}

double emitter_pdf_hit(const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir)
{
    return e->ops->pdf_hit(e, ref, hit, dir);
}

rgb emitter_eval_env(const emitter_t *e, vec3 dir)
{
    return e->ops->eval_env(e, dir);
}

double emitter_pdf_env(const emitter_t *e, vec3 dir)
{
    return e->ops->pdf_env(e, dir);
}

void emitter_bounds(const emitter_t *e, light_bounds *out)
{
    e->ops->bounds(e, out);
}

void emitter_bounds_infinite(double phi, light_bounds *out)
{
    *out = (light_bounds){.infinite = true, .axis = v3(0, 0, 1), .cos_theta_o = -1.0, .cos_theta_e = -1.0, .phi = phi};
}

void emitter_bounds_point(vec3 p, double phi, light_bounds *out)
{
    *out = (light_bounds){.lo = p, .hi = p, .axis = v3(0, 0, 1), .cos_theta_o = -1.0, .cos_theta_e = 0.0, .phi = phi};
}

emitter_t *emitter_alloc(const scene_obj *o, const emitter_ops *ops, const void *data, size_t data_size, char *err,
                         size_t errlen)
{
    void *at;
    emitter_t *e = record_alloc(sizeof *e, data, data_size, &at);
    if (!e) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    e->ops = ops;
    e->data = at;
    return e;
}

void emitter_destroy(emitter_t *e)
{
    if (!e)
        return;
    if (e->ops->release)
        e->ops->release(e->data);
    free(e);
}

int emitter_delta_sample(vec3 pos, vec3 ref, emitter_sample_rec *out)
{
    vec3 to = v3_sub(pos, ref);
    double dist2 = v3_dot(to, to);
    if (!(dist2 > 0.0))
        return 0;
    out->dist = sqrt(dist2);
    out->wi = v3_scale(to, 1.0 / out->dist);
    out->p = pos;
    out->pdf = 1.0;
    out->delta = true;
    return 1;
}

rgb emitter_rgb_param(scene_obj *o, const char *name, double def)
{
    scene_rgb c = scene_obj_rgb(o, name, (scene_rgb){def, def, def});
    return rgb_make(c.r, c.g, c.b);
}

int emitter_list_add(emitter_list *l, emitter_t *e)
{
    emitter_t **a = realloc(l->items, sizeof *a * (size_t)(l->count + 1));
    if (!a)
        return -1;
    l->items = a;
    e->index = l->count;
    a[l->count++] = e;
    return 0;
}

void emitter_list_free(emitter_list *l)
{
    for (int i = 0; i < l->count; i++)
        emitter_destroy(l->items[i]);
    free(l->items);
    light_tree_destroy(l->tree);
    *l = (emitter_list){0};
}
