/* Mitsuba's `mesh_attribute` texture: the mesh attribute `name` (e.g.
 * "vertex_color", "face_weight") at the surface point, times `scale` (1):
 * a face attribute is the triangle's value, a vertex attribute is
 * interpolated by the barycentrics; one channel is gray. A shape without
 * that attribute (another shape, a mesh that lacks it) is refused by the
 * scene build, as Mitsuba refuses it; looked up without a mesh (a test, an
 * emitter's mean) the value is black. */
#include <stdio.h>
#include <string.h>

#include "textures/texture_impl.h"

typedef struct {
    char name[128];
    double scale;
} mesh_attribute_data;

static rgb attribute_value(const texture_attribute *a, unsigned i)
{
    const float *v = a->values + (size_t)i * (size_t)a->channels;
    return a->channels == 1 ? rgb_gray(v[0]) : (rgb){v[0], v[1], v[2]};
}

static rgb mesh_attribute_lookup_at(const texture_t *t, const texture_point *at)
{
    const mesh_attribute_data *d = t->data;
    const texture_mesh *m = at->mesh;
    for (int i = 0; m && i < m->count; i++) {
        const texture_attribute *a = &m->items[i];
        if (strcmp(a->name, d->name) != 0)
            continue;
        if (a->per_face)
            return rgb_scale(attribute_value(a, (unsigned)at->prim), d->scale);
        const unsigned *v = m->tri + 3 * (size_t)at->prim;
        rgb c = rgb_add(rgb_add(rgb_scale(attribute_value(a, v[0]), 1.0 - at->b1 - at->b2),
                                rgb_scale(attribute_value(a, v[1]), at->b1)),
                        rgb_scale(attribute_value(a, v[2]), at->b2));
        return rgb_scale(c, d->scale);
    }
    return rgb_gray(0.0);
}

/* Without a surface point there is no mesh: black. */
static rgb mesh_attribute_lookup(const texture_t *t, vec2 uv)
{
    (void)t, (void)uv;
    return rgb_gray(0.0);
}

static const texture_ops mesh_attribute_ops = {.lookup = mesh_attribute_lookup, .lookup_at = mesh_attribute_lookup_at};

static texture_t *mesh_attribute_create(scene_obj *o, char *err, size_t errlen)
{
    const char *name = scene_obj_string(o, "name", "");
    double scale = scene_obj_float(o, "scale", 1.0);
    if (strlen(name) >= sizeof ((mesh_attribute_data *)0)->name ||
        (strncmp(name, "vertex_", 7) != 0 && strncmp(name, "face_", 5) != 0)) {
        scene_obj_error(o, err, errlen, "name must be a mesh attribute's: vertex_... or face_...");
        return NULL;
    }
    texture_t *t = texture_alloc(&mesh_attribute_ops, sizeof(mesh_attribute_data));
    if (!t) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    mesh_attribute_data *d = t->data;
    snprintf(d->name, sizeof d->name, "%s", name);
    d->scale = scale;
    t->mean = rgb_gray(0.5 * scale); /* unknown until a surface is met */
    return t;
}

static const scene_param_decl mesh_attribute_params[] = {
    {"name", PARAM_STRING, PARAM_REQUIRED, NULL},
    {"scale", PARAM_FLOAT, 0, NULL},
    {NULL, 0, 0, NULL},
};

const texture_plugin texture_mesh_attribute = {
    .decl = {.cls = SCENE_TEXTURE, .type = "mesh_attribute", .params = mesh_attribute_params},
    .create = mesh_attribute_create,
};
