/* Mitsuba's `checkerboard`: color0 where both fractional uv parts are on the
 * same side of 1/2, color1 elsewhere; constant colors only. Read as a scalar
 * (a roughness, a weight: Mitsuba's eval_1) the squares swap: Mitsuba's
 * eval_1 gives color0 where the sides differ, and its reference images
 * (anisotropic roughness, principled weights) are made with it. */
#include "textures/texture_impl.h"

typedef struct {
    rgb color0, color1;
} checkerboard;

static rgb checkerboard_lookup(const texture_t *t, vec2 uv)
{
    const checkerboard *c = t->data;
    int mu = uv.x - floor(uv.x) > 0.5, mv = uv.y - floor(uv.y) > 0.5;
    return mu == mv ? c->color0 : c->color1;
}

static double checkerboard_lookup_1(const texture_t *t, vec2 uv)
{
    const checkerboard *c = t->data;
    int mu = uv.x - floor(uv.x) > 0.5, mv = uv.y - floor(uv.y) > 0.5;
    return rgb_luminance(mu != mv ? c->color0 : c->color1);
}

static const texture_ops checkerboard_ops = {checkerboard_lookup, NULL, NULL, NULL, checkerboard_lookup_1};

static texture_t *checkerboard_create(scene_obj *o, char *err, size_t errlen)
{
    if (scene_obj_texture(o, "color0") || scene_obj_texture(o, "color1")) {
        scene_obj_error(o, err, errlen,
                        "checkerboard colors must be constant colors (nested textures are not supported)");
        return NULL;
    }
    scene_rgb c0 = scene_obj_rgb(o, "color0", (scene_rgb){0.4, 0.4, 0.4});
    scene_rgb c1 = scene_obj_rgb(o, "color1", (scene_rgb){0.2, 0.2, 0.2});
    texture_t *t = texture_alloc(&checkerboard_ops, sizeof(checkerboard));
    if (!t) {
        scene_obj_error(o, err, errlen, "cannot create the texture");
        return NULL;
    }
    checkerboard *c = t->data;
    c->color0 = rgb_make(c0.r, c0.g, c0.b);
    c->color1 = rgb_make(c1.r, c1.g, c1.b);
    t->to_uv = texture_to_uv_param(o);
    t->mean = rgb_scale(rgb_add(c->color0, c->color1), 0.5);
    return t;
}

static const scene_param_decl checkerboard_params[] = {
    {"color0", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
    {"color1", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
    {"to_uv", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const texture_plugin texture_checkerboard = {
    .decl = {.cls = SCENE_TEXTURE, .type = "checkerboard", .params = checkerboard_params},
    .create = checkerboard_create,
};
