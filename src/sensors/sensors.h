/* Sensors in the sense of Mitsuba 3: the camera (`perspective`), the film
 * it exposes (`hdrfilm`: the image size) and the film's reconstruction
 * filter (`box`, `gaussian`, `tent`: accepted, the film's one-pixel box is
 * used whatever they say; docs/scene-format.md).
 *
 * The camera is a pinhole at the origin of its to_world frame looking along
 * local +z, with local +y up and local +x to the image's left (lookat
 * conventions, include/celadon/transform.h). The film's pixel (0,0) is the
 * top-left one (docs/conventions.md).
 *
 * This is src/sensors' interface: what the scene build and the render loop
 * use; each plugin is one file plus one line of sensor_table.c
 * (docs/plugins.md). */
#ifndef CELADON_SENSORS_H
#define CELADON_SENSORS_H

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

/* The ray through film position (px + sx, py + sy) in pixels: pixel (px,
 * py) with sample offset (sx, sy) in [0,1)^2. */
camera_ray_t camera_ray(const camera_t *cam, int px, int py, double sx, double sy);

/* ---------------------------------------------------------- the plugins */

/* What a <film> and its <rfilter> say. */
typedef struct {
    int width, height;
} film_settings;

/* A sensor plugin: the camera of a <sensor> for a width x height film;
 * 0, or -1 with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen);
} sensor_plugin;

/* A film plugin: fills out from a <film> (and its <rfilter>, through the
 * rfilter table); 0, or -1 with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, film_settings *out, char *err, size_t errlen);
} film_plugin;

/* A reconstruction filter plugin: what an <rfilter> changes in the film's
 * settings (today nothing: the film reconstructs with a one-pixel box). */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, film_settings *out, char *err, size_t errlen);
} rfilter_plugin;

/* The registration tables, NULL-terminated, and lookups by name (NULL for
 * an unknown one). */
extern const scene_plugin_decl *const sensor_plugins[];
extern const scene_plugin_decl *const film_plugins[];
extern const scene_plugin_decl *const rfilter_plugins[];
const sensor_plugin *sensor_plugin_find(const char *name);
const film_plugin *film_plugin_find(const char *name);
const rfilter_plugin *rfilter_plugin_find(const char *name);

#endif
