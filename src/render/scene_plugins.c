/* Every plugin the renderer builds, declared for the scene reader. */
#include "celadon/scene.h"

#include <string.h>

#define END {NULL, 0, 0, NULL}
#define COLOR_TEX (PARAM_COLOR | PARAM_TEXTURE)

/* Mitsuba's named indices of refraction (its IOR table). */
#define IOR_NAMES "vacuum|helium|hydrogen|air|carbon dioxide|water|acetone|ethanol|" \
                  "carbon tetrachloride|glycerol|benzene|silicone oil|bromine|water ice|" \
                  "fused quartz|pyrex|acrylic glass|polypropylene|bk7|sodium chloride|amber|pet|diamond"
#define DISTRIBUTIONS "beckmann|ggx"

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

/* ------------------------------------------------------------------- BSDFs */
#define IOR_PAIR {"int_ior", PARAM_FLOAT | PARAM_STRING, 0, IOR_NAMES}, {"ext_ior", PARAM_FLOAT | PARAM_STRING, 0, IOR_NAMES}
#define ROUGHNESS(alpha_types)                                                          \
    {"distribution", PARAM_STRING, 0, DISTRIBUTIONS}, {"alpha", alpha_types, 0, NULL},     \
        {"alpha_u", alpha_types, 0, NULL}, {"alpha_v", alpha_types, 0, NULL},           \
        {"sample_visible", PARAM_BOOL, 0, NULL}
static const scene_param_decl diffuse_params[] = {{"reflectance", COLOR_TEX, 0, NULL}, END};
static const scene_param_decl dielectric_params[] = {
    IOR_PAIR,
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"specular_transmittance", COLOR_TEX, 0, NULL},
    END};
static const scene_param_decl roughdielectric_params[] = {
    IOR_PAIR,
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"specular_transmittance", COLOR_TEX, 0, NULL},
    ROUGHNESS(PARAM_FLOAT | PARAM_TEXTURE),
    END};
static const scene_param_decl conductor_params[] = {
    {"material", PARAM_STRING, 0, NULL},
    {"eta", COLOR_TEX, 0, NULL},
    {"k", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    END};
static const scene_param_decl roughconductor_params[] = {
    {"material", PARAM_STRING, 0, NULL},
    {"eta", COLOR_TEX, 0, NULL},
    {"k", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    ROUGHNESS(PARAM_FLOAT | PARAM_TEXTURE),
    END};
static const scene_param_decl plastic_params[] = {
    IOR_PAIR,
    {"diffuse_reflectance", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"nonlinear", PARAM_BOOL, 0, NULL},
    END};
static const scene_param_decl roughplastic_params[] = {
    IOR_PAIR,
    {"diffuse_reflectance", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"nonlinear", PARAM_BOOL, 0, NULL},
    {"distribution", PARAM_STRING, 0, DISTRIBUTIONS},
    {"alpha", PARAM_FLOAT, 0, NULL},
    {"sample_visible", PARAM_BOOL, 0, NULL},
    END};
static const scene_child_decl twosided_children[] = {{SCENE_BSDF, 1, 2, NULL}, {SCENE_SCENE, 0, 0, NULL}};

/* ---------------------------------------------------------------- textures */
static const scene_param_decl bitmap_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"raw", PARAM_BOOL, 0, NULL},
    {"filter_type", PARAM_STRING, 0, "nearest|bilinear"},
    {"wrap_mode", PARAM_STRING, 0, "repeat|mirror|clamp"},
    {"to_uv", PARAM_TRANSFORM, 0, NULL},
    END};
static const scene_param_decl checkerboard_params[] = {
    {"color0", COLOR_TEX, 0, NULL},
    {"color1", COLOR_TEX, 0, NULL},
    {"to_uv", PARAM_TRANSFORM, 0, NULL},
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
    {SCENE_BSDF, "diffuse", diffuse_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_BSDF, "dielectric", dielectric_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_BSDF, "thindielectric", dielectric_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_BSDF, "roughdielectric", roughdielectric_params, no_children, {"alpha", "alpha_u"}, SCENE_SCENE},
    {SCENE_BSDF, "conductor", conductor_params, no_children, {"material", "eta"}, SCENE_SCENE},
    {SCENE_BSDF, "roughconductor", roughconductor_params, no_children, {"alpha", "alpha_u"}, SCENE_SCENE},
    {SCENE_BSDF, "plastic", plastic_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_BSDF, "roughplastic", roughplastic_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_BSDF, "twosided", no_params, twosided_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_TEXTURE, "bitmap", bitmap_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_TEXTURE, "checkerboard", checkerboard_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "area", radiance_params, no_children, {NULL, NULL}, SCENE_SHAPE},
    {SCENE_EMITTER, "constant", radiance_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "envmap", envmap_params, no_children, {NULL, NULL}, SCENE_SCENE},
    {SCENE_EMITTER, "point", point_params, no_children, {"position", "to_world"}, SCENE_SCENE},
    {SCENE_EMITTER, "directional", directional_params, no_children, {"direction", "to_world"}, SCENE_SCENE},
};


const scene_plugin_decl *scene_plugin_find(scene_class cls, const char *type)
{
    for (size_t i = 0; i < sizeof plugins / sizeof plugins[0]; i++)
        if (plugins[i].cls == cls && strcmp(plugins[i].type, type) == 0)
            return &plugins[i];
    return NULL;
}

const scene_plugin_decl *scene_plugin_at(int i)
{
    return i >= 0 && i < (int)(sizeof plugins / sizeof plugins[0]) ? &plugins[i] : NULL;
}
