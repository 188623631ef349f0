/* Mitsuba's `hdrfilm`: the image size (768 x 576 by default), its
 * `pixel_format` (rgb by default; the "a" formats add the alpha channel of
 * coverage), `sample_border`, and the reconstruction filter of its nested
 * <rfilter>, Mitsuba's `gaussian` when it names none, and the crop window
 * (crop_offset_x/y, crop_width/height). The output file's
 * format follows its extension; `component_format` and `file_format` are
 * accepted and change nothing (docs/scene-format.md). */
#include <string.h>

#include "sensors/sensors.h"

static int hdrfilm_create(scene_obj *o, film_settings *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    film_format_parse(scene_obj_string(o, "pixel_format", "rgb"), &out->format); /* checked by the schema */
    out->width = (int)scene_obj_int(o, "width", 768);
    out->height = (int)scene_obj_int(o, "height", 576);
    out->sample_border = scene_obj_bool(o, "sample_border", false);
    out->crop_x = (int)scene_obj_int(o, "crop_offset_x", 0);
    out->crop_y = (int)scene_obj_int(o, "crop_offset_y", 0);
    out->crop_w = (int)scene_obj_int(o, "crop_width", 0); /* 0: to the film's edge (checked by the build) */
    out->crop_h = (int)scene_obj_int(o, "crop_height", 0);
    scene_obj_prop(o, "component_format");
    scene_obj_prop(o, "file_format");
    scene_obj implicit = {.cls = SCENE_RFILTER, .type = (char *)"gaussian", .file = o->file, .line = o->line};
    scene_obj *rf = scene_obj_child(o, SCENE_RFILTER);
    if (!rf)
        rf = &implicit;
    return rfilter_plugin_find(rf->type)->create(rf, &out->filter, err, errlen);
}

static const scene_param_decl hdrfilm_params[] = {
    {"width", PARAM_INT, 0, NULL},
    {"height", PARAM_INT, 0, NULL},
    {"file_format", PARAM_STRING, 0, "openexr|exr"},
    {"pixel_format", PARAM_STRING, 0, "rgb|rgba|luminance|luminance_alpha|xyz|xyza"},
    {"component_format", PARAM_STRING, 0, "float16|float32|uint32"},
    {"sample_border", PARAM_BOOL, 0, NULL},
    {"crop_offset_x", PARAM_INT, 0, NULL},
    {"crop_offset_y", PARAM_INT, 0, NULL},
    {"crop_width", PARAM_INT, 0, NULL},
    {"crop_height", PARAM_INT, 0, NULL},
    {NULL, 0, 0, NULL},
};

static const scene_child_decl hdrfilm_children[] = {{SCENE_RFILTER, 0, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const film_plugin film_hdrfilm = {
    .decl = {.cls = SCENE_FILM, .type = "hdrfilm", .params = hdrfilm_params, .children = hdrfilm_children},
    .create = hdrfilm_create,
};
