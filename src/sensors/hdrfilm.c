/* Mitsuba's `hdrfilm`: the image size (768 x 576 by default). The output
 * format follows the output file's extension; pixel_format,
 * component_format, file_format and sample_border are accepted and change
 * nothing (docs/scene-format.md). */
#include "sensors/sensors.h"

static int hdrfilm_create(scene_obj *o, film_settings *out, char *err, size_t errlen)
{
    out->width = (int)scene_obj_int(o, "width", 768);
    out->height = (int)scene_obj_int(o, "height", 576);
    static const char *const inert[] = {"pixel_format", "component_format", "file_format", "sample_border"};
    for (size_t i = 0; i < sizeof inert / sizeof inert[0]; i++)
        scene_obj_prop(o, inert[i]);
    scene_obj *rf = scene_obj_child(o, SCENE_RFILTER);
    if (!rf)
        return 0;
    const rfilter_plugin *filter = rfilter_plugin_find(rf->type);
    if (!filter)
        return scene_obj_error(rf, err, errlen, "unsupported rfilter '%s'", rf->type);
    return filter->create(rf, out, err, errlen);
}

static const scene_param_decl hdrfilm_params[] = {
    {"width", PARAM_INT, 0, NULL},
    {"height", PARAM_INT, 0, NULL},
    {"file_format", PARAM_STRING, 0, "openexr|exr"},
    {"pixel_format", PARAM_STRING, 0, "luminance|luminance_alpha|rgb|rgba|xyz|xyza"},
    {"component_format", PARAM_STRING, 0, "float16|float32|uint32"},
    {"sample_border", PARAM_BOOL, 0, NULL}, /* no effect with a one-pixel box filter */
    {NULL, 0, 0, NULL},
};

static const scene_child_decl hdrfilm_children[] = {{SCENE_RFILTER, 0, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const film_plugin film_hdrfilm = {
    .decl = {.cls = SCENE_FILM, .type = "hdrfilm", .params = hdrfilm_params, .children = hdrfilm_children},
    .create = hdrfilm_create,
};
