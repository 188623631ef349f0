/* What every camera shares: rays through film positions, the checks of the
 * film size and clip range, and the parameters of projective cameras. */
#include <math.h>
#include <stdio.h>

#include "celadon/field_of_view.h"
#include "sensors/sensor_impl.h"

const scene_child_decl sensor_children[] = {
    {SCENE_FILM, 0, 1, NULL},
    {SCENE_SAMPLER, 0, 1, NULL},
    {SCENE_MEDIUM, 0, 1, NULL}, /* the medium the camera is in (volpath) */
    {SCENE_SCENE, 0, 0, NULL},
};

camera_ray_t camera_ray_at(const camera_t *cam, double x, double y, vec2 aperture)
{
    return cam->sample(cam, x / cam->width, y / cam->height, aperture);
}

camera_ray_t camera_ray(const camera_t *cam, int px, int py, double sx, double sy)
{
    return camera_ray_at(cam, px + sx, py + sy, v2(0.5, 0.5));
}

int camera_check(int width, int height, double near_clip, double far_clip, const transform4 *to_world, char *err,
                 size_t errlen)
{
    if (width <= 0 || height <= 0) {
        snprintf(err, errlen, "film size %dx%d is not positive", width, height);
        return -1;
    }
    if (!(near_clip > 0 && far_clip > near_clip)) {
        snprintf(err, errlen, "clip range [%g, %g] needs 0 < near_clip < far_clip", near_clip, far_clip);
        return -1;
    }
    for (int j = 0; j < 3 && to_world; j++) {
        double len = hypot(hypot(to_world->m[0][j], to_world->m[1][j]), to_world->m[2][j]);
        if (fabs(len - 1.0) > 1e-4) {
            snprintf(err, errlen, "the sensor's to_world must not scale (axis %d has length %g)", j, len);
            return -1;
        }
    }
    return 0;
}

int camera_projective_param(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen)
{
    transform4 to_world = scene_obj_transform(o, "to_world");
    double near = scene_obj_float(o, "near_clip", CAMERA_DEFAULT_NEAR_CLIP);
    double far = scene_obj_float(o, "far_clip", CAMERA_DEFAULT_FAR_CLIP);
    double fov = scene_obj_float(o, "fov", NAN);
    const char *axis = scene_obj_string(o, "fov_axis", "x");
    const char *focal = scene_obj_string(o, "focal_length", NULL);
    char why[256];
    double tx = 0.0, ty = 0.0;
    if (camera_check(width, height, near, far, &to_world, why, sizeof why) != 0 ||
        fov_half_extents(fov, axis, focal, (double)width / height, &tx, &ty, why, sizeof why) != 0)
        return scene_obj_error(o, err, errlen, "<sensor type=\"%s\">: %s", o->type, why);
    cam->to_world = to_world;
    cam->width = width;
    cam->height = height;
    cam->tan_x = tx;
    cam->tan_y = ty;
    cam->near_clip = near;
    cam->far_clip = far;
    return 0;
}
