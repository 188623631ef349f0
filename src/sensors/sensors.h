/* Sensors in the sense of Mitsuba 3: the camera (`perspective`,
 * `thinlens`, `orthographic`), the film it exposes (`hdrfilm`: the image
 * size, the pixel format, the reconstruction filter) and the film's
 * reconstruction filter (`box`, `tent`, `gaussian`, Mitsuba's default;
 * docs/scene-format.md).
 *
 * The camera looks along local +z, with local +y up and local +x to the
 * image's left (lookat conventions, include/celadon/transform.h). The film's
 * pixel (0,0) is the top-left one and a film position (x, y) runs in pixels
 * from the top-left corner (docs/conventions.md).
 *
 * This is src/sensors' interface: what the scene build and the render loop
 * use; each plugin is one file plus one line of sensor_table.c
 * (docs/plugins.md). */
#ifndef CELADON_SENSORS_H
#define CELADON_SENSORS_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/film.h"
#include "celadon/scene_xml.h"
#include "celadon/transform.h"
#include "celadon/vecmath.h"

/* Mitsuba's defaults. */
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
    ray3 ray;          /* unit direction */
    double tmin, tmax; /* where the ray crosses the near and far clip planes */
} camera_ray_t;

typedef struct camera camera_t;

struct camera {
    const char *type; /* the plugin's name */
    transform4 to_world;
    int width, height;
    double tan_x, tan_y; /* perspective, thinlens: half extents of the image plane at local z = 1 */
    double near_clip, far_clip;
    double aperture_radius, focus_distance; /* thinlens */
    /* The ray through film position (fx, fy) in [0,1]^2 (fractions of the
     * width and height from the top-left corner); aperture: a point of
     * [0,1]^2 for the lens, used only when needs_aperture. */
    camera_ray_t (*sample)(const camera_t *cam, double fx, double fy, vec2 aperture);
    bool needs_aperture; /* the render loop draws an aperture sample */
};

/* A pinhole (`perspective`) camera: fov_deg in (0, 180) spans the image
 * along axis. to_world must be rigid (no scale; a reflection is allowed).
 * Returns 0, or -1 with a reason. */
int camera_init(camera_t *cam, const transform4 *to_world, double fov_deg, camera_fov_axis axis, int width,
                int height, double near_clip, double far_clip, char *err, size_t errlen);

/* The ray through film position (px + sx, py + sy) in pixels: pixel (px,
 * py) with sample offset (sx, sy) in [0,1)^2, through the lens centre. */
camera_ray_t camera_ray(const camera_t *cam, int px, int py, double sx, double sy);
/* The ray through film position (x, y) in pixels and aperture sample
 * aperture in [0,1)^2 (ignored by cameras without a lens). */
camera_ray_t camera_ray_at(const camera_t *cam, double x, double y, vec2 aperture);

/* ---------------------------------------------------------- the film */

/* A reconstruction filter: the weight of a sample at offset (dx, dy)
 * pixels from a pixel's centre is eval(dx) eval(dy), zero beyond radius. */
typedef struct rfilter rfilter_t;
struct rfilter {
    const char *type; /* the plugin's name */
    double radius;
    double p[2];      /* the plugin's: tent 1 / radius; gaussian -1 / (2 stddev^2) and its value at radius */
    double (*eval)(const rfilter_t *f, double x);
};

static inline double rfilter_eval(const rfilter_t *f, double x)
{
    return f->eval(f, x);
}
/* The box of one pixel: a sample counts in the pixel it falls in only. */
static inline bool rfilter_is_box(const rfilter_t *f)
{
    return f->radius <= 0.5;
}

/* What a <film> and its <rfilter> say. */
typedef struct {
    int width, height;
    film_pixel_format format; /* pixel_format */
    bool sample_border; /* samples are also taken within the filter's reach outside the film */
    rfilter_t filter;
    /* The window rendered (Mitsuba's crop_offset_x/y, crop_width/height):
     * the output image is crop_w x crop_h, its pixel (0, 0) the film's
     * (crop_x, crop_y); the whole film by default. */
    int crop_x, crop_y, crop_w, crop_h;
} film_settings;

/* ---------------------------------------------------------- the plugins */

/* A sensor plugin: the camera of a <sensor> for a width x height film;
 * 0, or -1 with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, int width, int height, camera_t *cam, char *err, size_t errlen);
} sensor_plugin;

/* A film plugin: fills out from a <film> (and its <rfilter>, through the
 * rfilter table: Mitsuba's `gaussian` when it names none); 0, or -1 with
 * "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, film_settings *out, char *err, size_t errlen);
} film_plugin;

/* A reconstruction filter plugin: fills the filter of an <rfilter>. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, rfilter_t *out, char *err, size_t errlen);
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
