/* Mitsuba's `projector` light: the reciprocal of a perspective camera at
 * the origin of to_world looking along its local +z. A point whose local
 * position (x, y, z), z > 0, falls in the frustum of `fov` (or
 * `focal_length`, "50mm") and `fov_axis`, for the aspect of the
 * `irradiance` texture's resolution, is lit through the texture's
 * uv = (1/2 - x / (2 z tan_x), 1/2 - y / (2 z tan_y)) (the film position
 * of a camera with the same parameters) by
 *     value = pi scale irradiance(uv) / (z^2 cos theta),
 * theta the angle between the axis and the ray, so that a plane facing the
 * projector at distance 1 receives the irradiance pi scale irradiance(uv):
 * a constant texture projects as a constant. A delta light. */
#include <math.h>

#include "celadon/field_of_view.h"
#include "emitters/emitter_impl.h"

typedef struct {
    rgb irradiance;           /* or */
    const texture_t *texture; /* NULL for the constant */
    double scale;
    double tan_x, tan_y;
    transform4 to_world, to_local;
} projector_data;

static int projector_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)u;
    const projector_data *s = e->data;
    vec3 local = transform_point(&s->to_local, ref);
    if (!(local.z > 0.0))
        return 0;
    vec2 uv = v2(0.5 - 0.5 * local.x / (local.z * s->tan_x), 0.5 - 0.5 * local.y / (local.z * s->tan_y));
    if (!(uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0))
        return 0;
    if (!emitter_delta_sample(transform_point(&s->to_world, v3(0, 0, 0)), ref, out))
        return 0;
    vec3 axis = transform_vector(&s->to_world, v3(0, 0, 1));
    double cos_theta = -v3_dot(axis, out->wi);
    if (!(cos_theta > 0.0))
        return 0;
    rgb e_uv = s->texture ? texture_eval(s->texture, uv) : s->irradiance;
    out->value = rgb_scale(e_uv, M_PI * s->scale / (local.z * local.z * cos_theta));
    return 1;
}

/* For light selection, a point light of the projector's intensity along
 * its axis (pi scale times the texture's mean) shining every way, as the
 * spot's (spot.c). */
static void projector_bounds(const emitter_t *e, light_bounds *out)
{
    const projector_data *s = e->data;
    rgb e_mean = s->texture ? texture_mean(s->texture) : s->irradiance;
    emitter_bounds_point(transform_point(&s->to_world, v3(0, 0, 0)), M_PI * s->scale * rgb_max(e_mean), out);
}

static const emitter_ops projector_ops = {projector_sample, NULL, NULL, NULL, NULL, NULL, projector_bounds, false};

static emitter_t *projector_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape;
    projector_data d = {.texture = NULL};
    scene_obj *tex = scene_obj_texture(o, "irradiance");
    if (tex && !(d.texture = texture_set_get(textures, tex, err, errlen)))
        return NULL;
    d.irradiance = emitter_rgb_param(o, "irradiance", 1.0);
    d.scale = scene_obj_float(o, "scale", 1.0);
    int w = 1, h = 1;
    if (d.texture)
        texture_resolution(d.texture, &w, &h);
    char why[256];
    if (fov_half_extents(scene_obj_float(o, "fov", NAN), scene_obj_string(o, "fov_axis", "x"),
                         scene_obj_string(o, "focal_length", NULL), (double)w / h, &d.tan_x, &d.tan_y, why,
                         sizeof why) != 0) {
        scene_obj_error(o, err, errlen, "<emitter type=\"projector\">: %s", why);
        return NULL;
    }
    d.to_world = scene_obj_transform(o, "to_world");
    d.to_local = transform_inverse(&d.to_world);
    return emitter_alloc(o, &projector_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl projector_params[] = {
    {"irradiance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
    {"scale", PARAM_FLOAT, 0, NULL},
    {"fov", PARAM_FLOAT, 0, NULL},
    {"fov_axis", PARAM_STRING, 0, "x|y|diagonal|smaller|larger"},
    {"focal_length", PARAM_STRING, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const emitter_plugin emitter_projector = {
    .decl = {.cls = SCENE_EMITTER, .type = "projector", .params = projector_params,
             .exclusive = {"fov", "focal_length"}},
    .create = projector_create,
};
