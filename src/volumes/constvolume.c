/* The `constvolume` volume: `value` (a color, Mitsuba's default 1)
 * everywhere; its box is the unit cube placed by `to_world`. */
#include "volumes/volume_impl.h"

static volume_t *constvolume_create(scene_obj *o, char *err, size_t errlen)
{
    transform4 to_world = scene_obj_transform(o, "to_world");
    volume_t *v = volume_of_param(o, "value", rgb_gray(1.0), err, errlen);
    if (v) {
        v->bounded = true;
        v->to_local = transform_inverse(&to_world);
    }
    return v;
}

static const scene_param_decl constvolume_params[] = {
    {"value", PARAM_COLOR, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const volume_plugin volume_constvolume = {
    .decl = {.cls = SCENE_VOLUME, .type = "constvolume", .params = constvolume_params},
    .create = constvolume_create,
};
