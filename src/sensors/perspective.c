/* Mitsuba's `perspective` sensor: a pinhole at the origin of to_world, its
 * field of view given by `fov` along `fov_axis` or by a 35 mm
 * `focal_length` (50mm, Mitsuba's default, when neither is given). */
#include "celadon/field_of_view.h"
#include "sensors/sensor_impl.h"

/* Local direction ((1 - 2 fx) tan_x, (1 - 2 fy) tan_y, 1): local +x is the
 * image's left and +y its top. */
static camera_ray_t perspective_sample(const camera_t *cam, double fx, double fy, vec2 aperture)
{
    (void)aperture;
    vec3 local = v3((1.0 - 2.0 * fx) * cam->tan_x, (1.0 - 2.0 * fy) * cam->tan_y, 1.0);
    double len = v3_len(local);
    camera_ray_t r;
    r.ray.o = transform_point(&cam->to_world, v3(0, 0, 0));
    r.ray.d = v3_norm(transform_vector(&cam->to_world, local));
    r.tmin = cam->near_clip * len; /* local z of the unit direction is 1/len */
    r.tmax = cam->far_clip * len;
    return r;
}

int camera_init(camera_t *cam, const transform4 *to_world, double fov_deg, camera_fov_axis axis, int width,
                int height, double near_clip, double far_clip, char *err, size_t errlen)
{
    static const char *const axes[] = {"x", "y", "diagonal", "smaller", "larger"};
    if (camera_check(width, height, near_clip, far_clip, to_world, err, errlen) != 0 ||
        fov_half_extents(fov_deg, axes[axis], NULL, (double)width / height, &cam->tan_x, &cam->tan_y, err,
                         errlen) != 0)
        return -1;
    cam->type = "perspective";
    cam->to_world = *to_world;
    cam->width = width;
    cam->height = height;
    cam->near_clip = near_clip;
    cam->far_clip = far_clip;
    cam->aperture_radius = 0.0;
    cam->focus_distance = 0.0;
    cam->sample = perspective_sample;
    cam->needs_aperture = false;
    return 0;
}

static int perspective_create(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen)
{
    scene_obj_prop(o, "focus_distance"); /* a pinhole has no focus, in Mitsuba too */
    *cam = (camera_t){.type = "perspective", .sample = perspective_sample};
    return camera_projective_param(o, width, height, cam, err, errlen);
}

static const scene_param_decl perspective_params[] = {
    SENSOR_PARAMS_FOV,
    SENSOR_PARAMS_CLIP,
    {"focus_distance", PARAM_FLOAT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const sensor_plugin sensor_perspective = {
    .decl = {.cls = SCENE_SENSOR, .type = "perspective", .params = perspective_params, .children = sensor_children,
             .exclusive = {"fov", "focal_length"}},
    .create = perspective_create,
};
