/* Mitsuba's `thinlens` sensor: a perspective camera whose pinhole is a
 * thin lens of `aperture_radius` (required) focused at `focus_distance`
 * (default: far_clip). The film position picks a point of the focal plane
 * at local depth focus_distance, the aperture sample a point of the lens
 * (a uniform disk in the local z = 0 plane), and the ray joins them, so a
 * point at depth z is imaged as a disc of radius
 * aperture_radius |1/z - 1/focus_distance| on the plane at distance 1. */
#include "celadon/sampling.h"
#include "sensors/sensor_impl.h"

static camera_ray_t thinlens_sample(const camera_t *cam, double fx, double fy, vec2 aperture)
{
    vec3 on_plane = v3((1.0 - 2.0 * fx) * cam->tan_x, (1.0 - 2.0 * fy) * cam->tan_y, 1.0);
    vec3 focus = v3_scale(on_plane, cam->focus_distance);
    vec2 a = v2_scale(warp_square_to_concentric_disk(aperture), cam->aperture_radius);
    vec3 lens = v3(a.x, a.y, 0.0);
    vec3 d = v3_norm(v3_sub(focus, lens));
    camera_ray_t r;
    r.ray.o = transform_point(&cam->to_world, lens);
    r.ray.d = transform_vector(&cam->to_world, d);
    r.tmin = cam->near_clip / d.z; /* the clip planes are planes of local z */
    r.tmax = cam->far_clip / d.z;
    return r;
}

static int thinlens_create(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen)
{
    *cam = (camera_t){.type = "thinlens", .sample = thinlens_sample, .needs_aperture = true};
    if (camera_projective_param(o, width, height, cam, err, errlen) != 0)
        return -1;
    cam->aperture_radius = scene_obj_float(o, "aperture_radius", 0.0);
    cam->focus_distance = scene_obj_float(o, "focus_distance", cam->far_clip);
    if (!(cam->aperture_radius >= 0.0))
        return scene_obj_error(o, err, errlen, "<sensor type=\"thinlens\">: aperture_radius %g is negative",
                               cam->aperture_radius);
    if (!(cam->focus_distance > 0.0))
        return scene_obj_error(o, err, errlen, "<sensor type=\"thinlens\">: focus_distance %g is not positive",
                               cam->focus_distance);
    /* Mitsuba replaces a zero aperture by its float epsilon: a pinhole. */
    if (cam->aperture_radius == 0.0)
        cam->aperture_radius = 0x1p-24;
    return 0;
}

static const scene_param_decl thinlens_params[] = {
    {"aperture_radius", PARAM_FLOAT, PARAM_REQUIRED, NULL},
    {"focus_distance", PARAM_FLOAT, 0, NULL},
    SENSOR_PARAMS_FOV,
    SENSOR_PARAMS_CLIP,
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const sensor_plugin sensor_thinlens = {
    .decl = {.cls = SCENE_SENSOR, .type = "thinlens", .params = thinlens_params, .children = sensor_children,
             .exclusive = {"fov", "focal_length"}},
    .create = thinlens_create,
};
