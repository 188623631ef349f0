/* Mitsuba's `orthographic` sensor: parallel rays along local +z from the
 * near plane, through the region [-1, 1] x [-1/aspect, 1/aspect] of local
 * x and y (the film's width spans local x; aspect = width / height), which
 * to_world places and may scale (a scale of 10 in x and y makes the view
 * 20 units wide). Rays start on the near plane and run far_clip -
 * near_clip along their (unit) direction, as Mitsuba's do. */
#include "sensors/sensor_impl.h"

static camera_ray_t orthographic_sample(const camera_t *cam, double fx, double fy, vec2 aperture)
{
    (void)aperture;
    double aspect = (double)cam->width / cam->height;
    vec3 near_p = v3(1.0 - 2.0 * fx, (1.0 - 2.0 * fy) / aspect, cam->near_clip);
    camera_ray_t r;
    r.ray.o = transform_point(&cam->to_world, near_p);
    r.ray.d = v3_norm(transform_vector(&cam->to_world, v3(0, 0, 1)));
    r.tmin = 0.0;
    r.tmax = cam->far_clip - cam->near_clip;
    return r;
}

static int orthographic_create(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen)
{
    *cam = (camera_t){.type = "orthographic", .sample = orthographic_sample, .width = width, .height = height};
    cam->to_world = scene_obj_transform(o, "to_world");
    cam->near_clip = scene_obj_float(o, "near_clip", CAMERA_DEFAULT_NEAR_CLIP);
    cam->far_clip = scene_obj_float(o, "far_clip", CAMERA_DEFAULT_FAR_CLIP);
    char why[256];
    if (camera_check(width, height, cam->near_clip, cam->far_clip, NULL, why, sizeof why) != 0)
        return scene_obj_error(o, err, errlen, "<sensor type=\"orthographic\">: %s", why);
    return 0;
}

static const scene_param_decl orthographic_params[] = {
    SENSOR_PARAMS_CLIP,
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const sensor_plugin sensor_orthographic = {
    .decl = {.cls = SCENE_SENSOR, .type = "orthographic", .params = orthographic_params,
             .children = sensor_children},
    .create = orthographic_create,
};
