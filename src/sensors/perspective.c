/* Mitsuba's `perspective` sensor: the pinhole camera of sensors.h. */
#include "sensors/sensors.h"

#include <stdio.h>
#include <string.h>

int camera_init(camera_t *cam, const transform4 *to_world, double fov_deg, camera_fov_axis axis, int width,
                int height, double near_clip, double far_clip, char *err, size_t errlen)
{
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "film size %dx%d is not positive", width, height);
        return -1;
    }
    if (!(fov_deg > 0 && fov_deg < 180)) {
        snprintf(err, errlen, "fov %g is not between 0 and 180 degrees", fov_deg);
        return -1;
    }
    if (!(near_clip > 0 && far_clip > near_clip)) {
        snprintf(err, errlen, "clip range [%g, %g] needs 0 < near_clip < far_clip", near_clip, far_clip);
        return -1;
    }
    for (int j = 0; j < 3; j++) {
        double len = hypot(hypot(to_world->m[0][j], to_world->m[1][j]), to_world->m[2][j]);
        if (fabs(len - 1.0) > 1e-4) {
            snprintf(err, errlen, "the sensor's to_world must not scale (axis %d has length %g)", j, len);
            return -1;
        }
    }
    double aspect = (double)width / height;
    if (axis == CAMERA_FOV_SMALLER)
        axis = width <= height ? CAMERA_FOV_X : CAMERA_FOV_Y;
    else if (axis == CAMERA_FOV_LARGER)
        axis = width >= height ? CAMERA_FOV_X : CAMERA_FOV_Y;
    double t = tan(0.5 * fov_deg * (M_PI / 180.0));
    switch (axis) {
    case CAMERA_FOV_Y:
        cam->tan_y = t;
        cam->tan_x = t * aspect;
        break;
    case CAMERA_FOV_DIAGONAL: /* t is the half diagonal: tan_x² + tan_y² = t², tan_x = aspect·tan_y */
        cam->tan_x = t * aspect / sqrt(1.0 + aspect * aspect);
        cam->tan_y = cam->tan_x / aspect;
        break;
    default:
        cam->tan_x = t;
        cam->tan_y = t / aspect;
        break;
    }
    cam->to_world = *to_world;
    cam->width = width;
    cam->height = height;
    cam->near_clip = near_clip;
    cam->far_clip = far_clip;
    return 0;
}

camera_ray_t camera_ray(const camera_t *cam, int px, int py, double sx, double sy)
{
    double x = (px + sx) / cam->width, y = (py + sy) / cam->height;
    /* Local +x is the image's left and +y its top. */
    vec3 local = v3((1.0 - 2.0 * x) * cam->tan_x, (1.0 - 2.0 * y) * cam->tan_y, 1.0);
    double len = v3_len(local);
    camera_ray_t r;
    r.ray.o = transform_point(&cam->to_world, v3(0, 0, 0));
    r.ray.d = v3_norm(transform_vector(&cam->to_world, local));
    r.tmin = cam->near_clip * len; /* local z of the unit direction is 1/len */
    r.tmax = cam->far_clip * len;
    return r;
}

static int perspective_create(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen)
{
    static const char *axes[] = {"x", "y", "diagonal", "smaller", "larger"};
    const char *name = scene_obj_string(o, "fov_axis", "x");
    camera_fov_axis axis = CAMERA_FOV_X;
    for (int i = 0; i < 5; i++)
        if (strcmp(name, axes[i]) == 0)
            axis = (camera_fov_axis)i;
    scene_obj_prop(o, "focus_distance"); /* a pinhole has no focus, in Mitsuba too */
    transform4 to_world = scene_obj_transform(o, "to_world");
    char why[256];
    if (camera_init(cam, &to_world, scene_obj_float(o, "fov", CAMERA_DEFAULT_FOV), axis, width, height,
                    scene_obj_float(o, "near_clip", CAMERA_DEFAULT_NEAR_CLIP),
                    scene_obj_float(o, "far_clip", CAMERA_DEFAULT_FAR_CLIP), why, sizeof why) != 0)
        return scene_obj_error(o, err, errlen, "<sensor type=\"%s\">: %s", o->type, why);
    return 0;
}

static const scene_param_decl perspective_params[] = {
    {"fov", PARAM_FLOAT, 0, NULL},
    {"fov_axis", PARAM_STRING, 0, "x|y|diagonal|smaller|larger"},
    {"near_clip", PARAM_FLOAT, 0, NULL},
    {"far_clip", PARAM_FLOAT, 0, NULL},
    {"focus_distance", PARAM_FLOAT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

static const scene_child_decl perspective_children[] = {
    {SCENE_FILM, 0, 1, NULL},
    {SCENE_SAMPLER, 0, 1, NULL},
    {SCENE_SCENE, 0, 0, NULL},
};

const sensor_plugin sensor_perspective = {
    .decl = {.cls = SCENE_SENSOR, .type = "perspective", .params = perspective_params,
             .children = perspective_children},
    .create = perspective_create,
};
