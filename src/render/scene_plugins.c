/* Every plugin the renderer builds, declared for the scene reader. */
#include "celadon/scene.h"
#include "bsdfs/bsdfs.h"
#include "textures/textures.h"

#include <string.h>

#define END {NULL, 0, 0, NULL}
#define COLOR_TEX (PARAM_COLOR | PARAM_TEXTURE)


static const scene_child_decl no_children[] = {{SCENE_SCENE, 0, 0, NULL}};

/* ------------------------------------------------------------------ scene */
static const scene_param_decl scene_params[] = {END};
static const scene_child_decl scene_children[] = {
    {SCENE_SENSOR, 0, 1, NULL}, {SCENE_INTEGRATOR, 0, 1, NULL}, {SCENE_SHAPE, 0, 1 << 30, NULL},
    {SCENE_EMITTER, 0, 1 << 30, NULL}, {SCENE_BSDF, 0, 1 << 30, NULL}, {SCENE_TEXTURE, 0, 1 << 30, NULL},
    {SCENE_SCENE, 0, 0, NULL}};

/* ----------------------------------------------------- sensor, film, ... */
static const scene_param_decl perspective_params[] = {
    {"fov", PARAM_FLOAT, 0, NULL},
    {"fov_axis", PARAM_STRING, 0, "x|y|diagonal|smaller|larger"},
    {"near_clip", PARAM_FLOAT, 0, NULL},
    {"far_clip", PARAM_FLOAT, 0, NULL},
    {"focus_distance", PARAM_FLOAT, 0, NULL}, /* Mitsuba accepts it; a pinhole has no focus */
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    END};
static const scene_child_decl sensor_children[] = {{SCENE_FILM, 0, 1, NULL}, {SCENE_SAMPLER, 0, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

static const scene_param_decl hdrfilm_params[] = {
    {"width", PARAM_INT, 0, NULL},
    {"height", PARAM_INT, 0, NULL},
    {"file_format", PARAM_STRING, 0, "openexr|exr"},
    {"pixel_format", PARAM_STRING, 0, "luminance|luminance_alpha|rgb|rgba|xyz|xyza"},
    {"component_format", PARAM_STRING, 0, "float16|float32|uint32"},
    {"sample_border", PARAM_BOOL, 0, NULL}, /* no effect with a one-pixel box filter */
    END};
static const scene_child_decl film_children[] = {{SCENE_RFILTER, 0, 1, NULL}, {SCENE_SCENE, 0, 0, NULL}};

static const scene_param_decl no_params[] = {END};
static const scene_param_decl gaussian_params[] = {{"stddev", PARAM_FLOAT, 0, NULL}, END};

static const scene_param_decl independent_params[] = {
    {"sample_count", PARAM_INT, 0, NULL},
    {"seed", PARAM_INT, 0, NULL},
    END};

static const scene_param_decl path_params[] = {
    {"max_depth", PARAM_INT, 0, NULL},
    {"rr_depth", PARAM_INT, 0, NULL},
    {"hide_emitters", PARAM_BOOL, 0, NULL},
    END};

/* ------------------------------------------------------------------ shapes */
#define SHAPE_COMMON {"to_world", PARAM_TRANSFORM, 0, NULL}, {"flip_normals", PARAM_BOOL, 0, NULL}
static const scene_child_decl shape_children[] = {{SCENE_BSDF, 0, 1, NULL}, {SCENE_EMITTER, 0, 1, "area"}, {SCENE_SCENE, 0, 0, NULL}};
static const scene_param_decl obj_params[] = {
    SHAPE_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"face_normals", PARAM_BOOL, 0, NULL},
    {"flip_tex_coords", PARAM_BOOL, 0, NULL},
    END};
static const scene_param_decl ply_params[] = {
    SHAPE_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"face_normals", PARAM_BOOL, 0, NULL},
    END};
static const scene_param_decl plain_shape_params[] = {SHAPE_COMMON, END};
static const scene_param_decl sphere_params[] = {
    SHAPE_COMMON,
    {"center", PARAM_POINT, 0, NULL},
    {"radius", PARAM_FLOAT, 0, NULL},
    END};
static const scene_param_decl cylinder_params[] = {
    SHAPE_COMMON,
    {"p0", PARAM_POINT, 0, NULL},
    {"p1", PARAM_POINT, 0, NULL},
    {"radius", PARAM_FLOAT, 0, NULL},
    END};
static const scene_param_decl sor_params[] = {
    SHAPE_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"height", PARAM_FLOAT, 0, NULL},
    {"caps", PARAM_BOOL, 0, NULL},
    END};

/* ---------------------------------------------------------------- emitters */
static const scene_param_decl radiance_params[] = {{"radiance", COLOR_TEX, 0, NULL}, END};
static const scene_param_decl envmap_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"scale", PARAM_FLOAT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    END};
static const scene_param_decl point_params[] = {
    {"intensity", PARAM_COLOR, 0, NULL},
    {"position", PARAM_POINT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    END};
static const scene_param_decl directional_params[] = {
    {"irradiance", PARAM_COLOR, 0, NULL},
    {"direction", PARAM_VECTOR, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    END};

static const scene_plugin_decl plugins[] = {
    {SCENE_SCENE, "scene", scene_params, scene_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SENSOR, "perspective", perspective_params, sensor_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_FILM, "hdrfilm", hdrfilm_params, film_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_RFILTER, "box", no_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_RFILTER, "gaussian", gaussian_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_RFILTER, "tent", no_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SAMPLER, "independent", independent_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_INTEGRATOR, "path", path_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "obj", obj_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "ply", ply_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "rectangle", plain_shape_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "cube", plain_shape_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "disk", plain_shape_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "sphere", sphere_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "cylinder", cylinder_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_SHAPE, "sor", sor_params, shape_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "area", radiance_params, no_children, {NULL, NULL}, SCENE_SHAPE},
    {SCENE_EMITTER, "constant", radiance_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "envmap", envmap_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "point", point_params, no_children, {"position", "to_world"}, SCENE_SCENE},
    {SCENE_EMITTER, "directional", directional_params, no_children, {"direction", "to_world"}, SCENE_SCENE},
};


const scene_plugin_decl *scene_plugin_find(scene_class cls, const char *type)
{
    if (cls == SCENE_BSDF)
        return scene_plugin_table_find(bsdf_plugins, type);
    if (cls == SCENE_TEXTURE)
        return scene_plugin_table_find(texture_plugins, type);
    for (size_t i = 0; i < sizeof plugins / sizeof plugins[0]; i++)
        if (plugins[i].cls == cls && strcmp(plugins[i].type, type) == 0)
            return &plugins[i];
    return NULL;
}

const scene_plugin_decl *scene_plugin_at(int i)
{
    int n = (int)(sizeof plugins / sizeof plugins[0]);
    if (i < n)
        return i >= 0 ? &plugins[i] : NULL;
    i -= n;
    for (const scene_plugin_decl *const *t = bsdf_plugins; *t; t++, i--)
        if (i == 0)
            return *t;
    for (const scene_plugin_decl *const *t = texture_plugins; *t; t++, i--)
        if (i == 0)
            return *t;
    return NULL;
}
