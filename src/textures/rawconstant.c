/* Mitsuba's `rawconstant` texture: one value everywhere, a float or a
 * 3-vector, taken as it is written (no colour conversion: in RGB that is
 * what any constant is; it matters for spectral renderers, and for data such
 * as a flat normal map's (0.5, 0.5, 1)). */
#include "textures/texture_impl.h"

static rgb rawconstant_lookup(const texture_t *t, vec2 uv)
{
    (void)uv;
    return t->mean;
}

static const texture_ops rawconstant_ops = {.lookup = rawconstant_lookup}; /* constant: no gradient */

static texture_t *rawconstant_create(scene_obj *o, char *err, size_t errlen)
{
    const scene_prop *p = scene_obj_prop(o, "value");
    texture_t *t = texture_alloc(&rawconstant_ops, 0);
    if (!t) {
        scene_obj_error(o, err, errlen, "cannot create the texture");
        return NULL;
    }
    if (p->type == SCENE_VECTOR)
        t->mean = rgb_make(p->value.v.x, p->value.v.y, p->value.v.z);
    else if (p->type == SCENE_FLOAT)
        t->mean = rgb_gray(p->value.f);
    else
        t->mean = rgb_make(p->value.rgb.r, p->value.rgb.g, p->value.rgb.b);
    return t;
}

static const scene_param_decl rawconstant_params[] = {
    {"value", PARAM_FLOAT | PARAM_VECTOR | (1u << SCENE_RGB), PARAM_REQUIRED, NULL},
    {NULL, 0, 0, NULL},
};

const texture_plugin texture_rawconstant = {
    .decl = {.cls = SCENE_TEXTURE, .type = "rawconstant", .params = rawconstant_params},
    .create = rawconstant_create,
};
