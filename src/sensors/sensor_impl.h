/* What the camera plugins share. Private to src/sensors/. */
#ifndef CELADON_SENSOR_IMPL_H
#define CELADON_SENSOR_IMPL_H

#include "sensors/sensors.h"

/* The parameters of a projective camera (perspective, thinlens): fov and
 * fov_axis or focal_length (Mitsuba's default 50mm), near_clip, far_clip
 * and a rigid to_world, into cam for a width x height film. 0, or -1 with
 * "file:line: <sensor type=...>: problem" in err. */
int camera_projective_param(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen);

/* The checks every camera makes: a positive film size, 0 < near_clip <
 * far_clip, and (unless to_world is NULL) a to_world that does not scale.
 * 0, or -1 with a reason. */
int camera_check(int width, int height, double near_clip, double far_clip, const transform4 *to_world, char *err,
                 size_t errlen);

/* The parameters every camera takes, and what it may hold. */
#define SENSOR_PARAMS_CLIP {"near_clip", PARAM_FLOAT, 0, NULL}, {"far_clip", PARAM_FLOAT, 0, NULL}
#define SENSOR_PARAMS_FOV                                                                                          \
    {"fov", PARAM_FLOAT, 0, NULL}, {"fov_axis", PARAM_STRING, 0, "x|y|diagonal|smaller|larger"},                   \
        {"focal_length", PARAM_STRING, 0, NULL}
extern const scene_child_decl sensor_children[];

#endif
