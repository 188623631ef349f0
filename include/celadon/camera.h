/* Mitsuba's `perspective` sensor: a pinhole camera at the origin of its
 * to_world frame looking along local +z, with local +y up and local +x to
 * the image's left (lookat conventions, include/celadon/transform.h). The
 * film's pixel (0,0) is the top-left one. */
#ifndef CELADON_CAMERA_H
#define CELADON_CAMERA_H

#include <stddef.h>

#include "celadon/scene_xml.h"
#include "celadon/transform.h"
#include "celadon/vecmath.h"

/* Mitsuba's defaults. */
#define CAMERA_DEFAULT_FOV 39.3977
#define CAMERA_DEFAULT_NEAR_CLIP 1e-2
#define CAMERA_DEFAULT_FAR_CLIP 1e4

typedef enum {
    CAMERA_FOV_X,
    CAMERA_FOV_Y,
    CAMERA_FOV_DIAGONAL,
    CAMERA_FOV_SMALLER, /* the shorter image side */
    CAMERA_FOV_LARGER   /* the longer image side */
} camera_fov_axis;

typedef struct {
    transform4 to_world;
    int width, height;
    double tan_x, tan_y; /* half extents of the image plane at local z = 1 */
    double near_clip, far_clip;
} camera_t;

typedef struct {
    ray3 ray;          /* origin at the pinhole, unit direction */
    double tmin, tmax; /* where the ray crosses the near and far clip planes */
} camera_ray_t;

/* fov_deg in (0, 180) spans the image along axis. to_world must be rigid
 * (no scale; a reflection is allowed). Returns 0, or -1 with a reason. */
int camera_init(camera_t *cam, const transform4 *to_world, double fov_deg, camera_fov_axis axis, int width,
                int height, double near_clip, double far_clip, char *err, size_t errlen);

/* From a <sensor type="perspective"> (consuming fov, fov_axis, near_clip,
 * far_clip, to_world) for a width x height film; errors name the sensor's
 * file and line. */
int camera_from_sensor(camera_t *cam, scene_obj *sensor, int width, int height, char *err, size_t errlen);

/* The ray through film position (px + sx, py + sy) in pixels: pixel (px,
 * py) with sample offset (sx, sy) in [0,1)^2. */
camera_ray_t camera_ray(const camera_t *cam, int px, int py, double sx, double sy);

#endif
