#include "render/scene_xml_schema.h"

#include <stdio.h>
#include <string.h>

#define END {NULL, 0, 0, NULL}
#define COLOR_TEX (PT_COLOR | PT_TEXTURE)

/* Mitsuba's named indices of refraction (its IOR table). */
#define IOR_NAMES "vacuum|helium|hydrogen|air|carbon dioxide|water|acetone|ethanol|" \
                  "carbon tetrachloride|glycerol|benzene|silicone oil|bromine|water ice|" \
                  "fused quartz|pyrex|acrylic glass|polypropylene|bk7|sodium chloride|amber|pet|diamond"
#define DISTRIBUTIONS "beckmann|ggx"

static const schema_child no_children[] = {{SCENE_SCENE, 0, 0}};

/* ------------------------------------------------------------------ scene */
static const schema_param scene_params[] = {END};
static const schema_child scene_children[] = {
    {SCENE_SENSOR, 0, 1}, {SCENE_INTEGRATOR, 0, 1}, {SCENE_SHAPE, 0, 1 << 30},
    {SCENE_EMITTER, 0, 1 << 30}, {SCENE_BSDF, 0, 1 << 30}, {SCENE_TEXTURE, 0, 1 << 30},
    {SCENE_SCENE, 0, 0}};

/* ----------------------------------------------------- sensor, film, ... */
static const schema_param perspective_params[] = {
    {"fov", PT_FLOAT, 0, NULL},
    {"fov_axis", PT_STRING, 0, "x|y|diagonal|smaller|larger"},
    {"near_clip", PT_FLOAT, 0, NULL},
    {"far_clip", PT_FLOAT, 0, NULL},
    {"focus_distance", PT_FLOAT, 0, NULL}, /* Mitsuba accepts it; a pinhole has no focus */
    {"to_world", PT_TRANSFORM, 0, NULL},
    END};
static const schema_child sensor_children[] = {{SCENE_FILM, 0, 1}, {SCENE_SAMPLER, 0, 1}, {SCENE_SCENE, 0, 0}};

static const schema_param hdrfilm_params[] = {
    {"width", PT_INT, 0, NULL},
    {"height", PT_INT, 0, NULL},
    {"file_format", PT_STRING, 0, "openexr|exr"},
    {"pixel_format", PT_STRING, 0, "luminance|luminance_alpha|rgb|rgba|xyz|xyza"},
    {"component_format", PT_STRING, 0, "float16|float32|uint32"},
    {"sample_border", PT_BOOL, 0, NULL}, /* no effect with a one-pixel box filter */
    END};
static const schema_child film_children[] = {{SCENE_RFILTER, 0, 1}, {SCENE_SCENE, 0, 0}};

static const schema_param no_params[] = {END};
static const schema_param gaussian_params[] = {{"stddev", PT_FLOAT, 0, NULL}, END};

static const schema_param independent_params[] = {
    {"sample_count", PT_INT, 0, NULL},
    {"seed", PT_INT, 0, NULL},
    END};

static const schema_param path_params[] = {
    {"max_depth", PT_INT, 0, NULL},
    {"rr_depth", PT_INT, 0, NULL},
    {"hide_emitters", PT_BOOL, 0, NULL},
    END};

/* ------------------------------------------------------------------ shapes */
#define SHAPE_COMMON {"to_world", PT_TRANSFORM, 0, NULL}, {"flip_normals", PT_BOOL, 0, NULL}
static const schema_child shape_children[] = {{SCENE_BSDF, 0, 1}, {SCENE_EMITTER, 0, 1}, {SCENE_SCENE, 0, 0}};
static const schema_param obj_params[] = {
    SHAPE_COMMON,
    {"filename", PT_STRING, PF_REQUIRED | PF_FILE, NULL},
    {"face_normals", PT_BOOL, 0, NULL},
    {"flip_tex_coords", PT_BOOL, 0, NULL},
    END};
static const schema_param ply_params[] = {
    SHAPE_COMMON,
    {"filename", PT_STRING, PF_REQUIRED | PF_FILE, NULL},
    {"face_normals", PT_BOOL, 0, NULL},
    END};
static const schema_param plain_shape_params[] = {SHAPE_COMMON, END};
static const schema_param sphere_params[] = {
    SHAPE_COMMON,
    {"center", PT_POINT, 0, NULL},
    {"radius", PT_FLOAT, 0, NULL},
    END};
static const schema_param cylinder_params[] = {
    SHAPE_COMMON,
    {"p0", PT_POINT, 0, NULL},
    {"p1", PT_POINT, 0, NULL},
    {"radius", PT_FLOAT, 0, NULL},
    END};
static const schema_param sor_params[] = {
    SHAPE_COMMON,
    {"filename", PT_STRING, PF_REQUIRED | PF_FILE, NULL},
    {"height", PT_FLOAT, 0, NULL},
    {"caps", PT_BOOL, 0, NULL},
    END};

/* ------------------------------------------------------------------- BSDFs */
#define IOR_PAIR {"int_ior", PT_FLOAT | PT_STRING, 0, IOR_NAMES}, {"ext_ior", PT_FLOAT | PT_STRING, 0, IOR_NAMES}
#define ROUGHNESS(alpha_types)                                                          \
    {"distribution", PT_STRING, 0, DISTRIBUTIONS}, {"alpha", alpha_types, 0, NULL},     \
        {"alpha_u", alpha_types, 0, NULL}, {"alpha_v", alpha_types, 0, NULL},           \
        {"sample_visible", PT_BOOL, 0, NULL}
static const schema_param diffuse_params[] = {{"reflectance", COLOR_TEX, 0, NULL}, END};
static const schema_param dielectric_params[] = {
    IOR_PAIR,
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"specular_transmittance", COLOR_TEX, 0, NULL},
    END};
static const schema_param roughdielectric_params[] = {
    IOR_PAIR,
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"specular_transmittance", COLOR_TEX, 0, NULL},
    ROUGHNESS(PT_FLOAT | PT_TEXTURE),
    END};
static const schema_param conductor_params[] = {
    {"material", PT_STRING, 0, NULL},
    {"eta", COLOR_TEX, 0, NULL},
    {"k", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    END};
static const schema_param roughconductor_params[] = {
    {"material", PT_STRING, 0, NULL},
    {"eta", COLOR_TEX, 0, NULL},
    {"k", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    ROUGHNESS(PT_FLOAT | PT_TEXTURE),
    END};
static const schema_param plastic_params[] = {
    IOR_PAIR,
    {"diffuse_reflectance", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"nonlinear", PT_BOOL, 0, NULL},
    END};
static const schema_param roughplastic_params[] = {
    IOR_PAIR,
    {"diffuse_reflectance", COLOR_TEX, 0, NULL},
    {"specular_reflectance", COLOR_TEX, 0, NULL},
    {"nonlinear", PT_BOOL, 0, NULL},
    {"distribution", PT_STRING, 0, DISTRIBUTIONS},
    {"alpha", PT_FLOAT, 0, NULL},
    {"sample_visible", PT_BOOL, 0, NULL},
    END};
static const schema_child twosided_children[] = {{SCENE_BSDF, 1, 2}, {SCENE_SCENE, 0, 0}};

/* ---------------------------------------------------------------- textures */
static const schema_param bitmap_params[] = {
    {"filename", PT_STRING, PF_REQUIRED | PF_FILE, NULL},
    {"raw", PT_BOOL, 0, NULL},
    {"filter_type", PT_STRING, 0, "nearest|bilinear"},
    {"wrap_mode", PT_STRING, 0, "repeat|mirror|clamp"},
    {"to_uv", PT_TRANSFORM, 0, NULL},
    END};
static const schema_param checkerboard_params[] = {
    {"color0", COLOR_TEX, 0, NULL},
    {"color1", COLOR_TEX, 0, NULL},
    {"to_uv", PT_TRANSFORM, 0, NULL},
    END};

/* ---------------------------------------------------------------- emitters */
static const schema_param radiance_params[] = {{"radiance", COLOR_TEX, 0, NULL}, END};
static const schema_param envmap_params[] = {
    {"filename", PT_STRING, PF_REQUIRED | PF_FILE, NULL},
    {"scale", PT_FLOAT, 0, NULL},
    {"to_world", PT_TRANSFORM, 0, NULL},
    END};
static const schema_param point_params[] = {
    {"intensity", PT_COLOR, 0, NULL},
    {"position", PT_POINT, 0, NULL},
    {"to_world", PT_TRANSFORM, 0, NULL},
    END};
static const schema_param directional_params[] = {
    {"irradiance", PT_COLOR, 0, NULL},
    {"direction", PT_VECTOR, 0, NULL},
    {"to_world", PT_TRANSFORM, 0, NULL},
    END};

static const schema_plugin plugins[] = {
    {SCENE_SCENE, "scene", scene_params, scene_children, {NULL, NULL}},
    {SCENE_SENSOR, "perspective", perspective_params, sensor_children, {NULL, NULL}},
    {SCENE_FILM, "hdrfilm", hdrfilm_params, film_children, {NULL, NULL}},
    {SCENE_RFILTER, "box", no_params, no_children, {NULL, NULL}},
    {SCENE_RFILTER, "gaussian", gaussian_params, no_children, {NULL, NULL}},
    {SCENE_RFILTER, "tent", no_params, no_children, {NULL, NULL}},
    {SCENE_SAMPLER, "independent", independent_params, no_children, {NULL, NULL}},
    {SCENE_INTEGRATOR, "path", path_params, no_children, {NULL, NULL}},
    {SCENE_SHAPE, "obj", obj_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "ply", ply_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "rectangle", plain_shape_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "cube", plain_shape_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "disk", plain_shape_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "sphere", sphere_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "cylinder", cylinder_params, shape_children, {NULL, NULL}},
    {SCENE_SHAPE, "sor", sor_params, shape_children, {NULL, NULL}},
    {SCENE_BSDF, "diffuse", diffuse_params, no_children, {NULL, NULL}},
    {SCENE_BSDF, "dielectric", dielectric_params, no_children, {NULL, NULL}},
    {SCENE_BSDF, "thindielectric", dielectric_params, no_children, {NULL, NULL}},
    {SCENE_BSDF, "roughdielectric", roughdielectric_params, no_children, {"alpha", "alpha_u"}},
    {SCENE_BSDF, "conductor", conductor_params, no_children, {"material", "eta"}},
    {SCENE_BSDF, "roughconductor", roughconductor_params, no_children, {"alpha", "alpha_u"}},
    {SCENE_BSDF, "plastic", plastic_params, no_children, {NULL, NULL}},
    {SCENE_BSDF, "roughplastic", roughplastic_params, no_children, {NULL, NULL}},
    {SCENE_BSDF, "twosided", no_params, twosided_children, {NULL, NULL}},
    {SCENE_TEXTURE, "bitmap", bitmap_params, no_children, {NULL, NULL}},
    {SCENE_TEXTURE, "checkerboard", checkerboard_params, no_children, {NULL, NULL}},
    {SCENE_EMITTER, "area", radiance_params, no_children, {NULL, NULL}},
    {SCENE_EMITTER, "constant", radiance_params, no_children, {NULL, NULL}},
    {SCENE_EMITTER, "envmap", envmap_params, no_children, {NULL, NULL}},
    {SCENE_EMITTER, "point", point_params, no_children, {"position", "to_world"}},
    {SCENE_EMITTER, "directional", directional_params, no_children, {"direction", "to_world"}},
};

const schema_plugin *schema_find(scene_class cls, const char *type)
{
    for (size_t i = 0; i < sizeof plugins / sizeof plugins[0]; i++)
        if (plugins[i].cls == cls && strcmp(plugins[i].type, type) == 0)
            return &plugins[i];
    return NULL;
}

const schema_plugin *schema_plugin_at(int i)
{
    return i >= 0 && i < (int)(sizeof plugins / sizeof plugins[0]) ? &plugins[i] : NULL;
}

const schema_param *schema_param_find(const schema_plugin *p, const char *name)
{
    for (const schema_param *q = p->params; q->name; q++)
        if (strcmp(q->name, name) == 0)
            return q;
    return NULL;
}

const schema_child *schema_child_find(const schema_plugin *p, scene_class cls)
{
    for (const schema_child *c = p->children; c->max > 0; c++)
        if (c->cls == cls)
            return c;
    return NULL;
}

int schema_choice_ok(const char *choices, const char *word)
{
    size_t n = strlen(word);
    for (const char *s = choices; *s;) {
        const char *bar = strchr(s, '|');
        size_t len = bar ? (size_t)(bar - s) : strlen(s);
        if (len == n && strncmp(s, word, n) == 0)
            return 1;
        if (!bar)
            break;
        s = bar + 1;
    }
    return 0;
}

const char *schema_type_tag(scene_prop_type t)
{
    static const char *tags[] = {"float", "integer", "boolean", "string", "rgb",
                                 "spectrum", "point", "vector", "transform", "texture"};
    return tags[t];
}

void schema_types_text(unsigned types, char *buf, size_t len)
{
    int k = 0, total = 0;
    for (int t = SCENE_FLOAT; t <= SCENE_OBJECT; t++)
        total += (types >> t) & 1u;
    buf[0] = '\0';
    for (int t = SCENE_FLOAT; t <= SCENE_OBJECT; t++) {
        if (!((types >> t) & 1u))
            continue;
        size_t used = strlen(buf);
        const char *sep = k == 0 ? "" : (k == total - 1 ? " or " : ", ");
        snprintf(buf + used, len - used, "%s<%s>", sep, schema_type_tag((scene_prop_type)t));
        k++;
    }
}
