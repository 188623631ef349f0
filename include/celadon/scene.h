/* The built, renderable scene: a Mitsuba 3 scene description (scene_xml.h)
 * turned into a camera, a sampler, an integrator, shapes with their BSDFs,
 * and emitters, with an acceleration structure for ray queries. Each object
 * is built by the plugin its XML names, through the registration table of its
 * kind (src/bsdfs/, src/shapes/, ...; docs/plugins.md).
 *
 * Geometry: every shape is traced through one Embree scene (accel.h):
 * triangle meshes (obj, ply, rectangle, cube, and `sor` under --geometry
 * mesh:N) as triangles; analytic shapes (sphere, disk, cylinder, and `sor` by
 * default) as user geometries intersected exactly in double precision in
 * their object space.
 *
 * Lifetime: a scene_t is made by scene_create or scene_create_from_file and
 * released by scene_destroy; it does not keep the description. After
 * creation every query below may be called from any number of threads. */
#ifndef CELADON_SCENE_H
#define CELADON_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct scene scene_t;

/* Command-line overrides; zero / negative values keep the scene's own. */
typedef struct {
    int width, height;   /* film size */
    int spp;             /* sampler sample_count */
    long long seed;      /* sampler seed; < 0 keeps the scene's */
    int mesh_segments;   /* 0: SORs analytic; N >= 3: revolved into N angular segments */
    const char *sampler; /* a sampler plugin to use instead of the scene's (its sample count and seed kept); NULL keeps it */
    const char *const *search_dirs; /* folders where scene_create_from_file also looks for files, tried
                                       last (render -a; scene_desc_create_from_file_in) */
    int n_search_dirs;
    int crop_x, crop_y, crop_w, crop_h; /* crop_w > 0: render only this window (render --crop) */
} scene_options;

/* Every field at "keep the scene's own". */
scene_options scene_options_default(void);

/* The declaration of every plugin the renderer builds (scene_xml.h), the
 * lookup scene_create_from_file checks scene files with; and the i-th of
 * them, NULL past the end. */
const scene_plugin_decl *scene_plugin_find(scene_class cls, const char *type);
const scene_plugin_decl *scene_plugin_at(int i);

/* Builds a scene from a loaded description (opt may be NULL). Returns NULL
 * with one line "file:line: problem" in err on any defect (unsupported
 * combination, bad value, unreadable mesh, profile or image). */
scene_t *scene_create(scene_desc *desc, const scene_options *opt, char *err, size_t errlen);
/* scene_desc_create_from_file (checked against scene_plugin_find) and
 * scene_create. */
scene_t *scene_create_from_file(const char *path, const scene_define *defs, int ndefs, const scene_options *opt,
                                char *err, size_t errlen);
void scene_destroy(scene_t *s);

/* Settings of the render. */
void scene_film_size(const scene_t *s, int *width, int *height);
int scene_spp(const scene_t *s);
uint64_t scene_seed(const scene_t *s);
/* A 64-bit hash (XXH3) of what the scene was built from: its description
 * as read (defaults and -D applied), the contents of every file it names,
 * and the film size, spp and SOR geometry it was built with; not the seed.
 * Two builds of the same scene files with the same options agree on it. */
uint64_t scene_digest(const scene_t *s);
/* Triangles traced (meshes, and SORs under mesh:N), for reports. */
long long scene_triangle_count(const scene_t *s);

/* ------------------------------------------------------------- probing */
/* For tools that compare scenes shape by shape (the cross-check). */

/* How many of the scene's shapes are of plugin type ("sor", "sphere", ...). */
int scene_shapes_of_type(const scene_t *s, const char *type);

/* The camera ray through film position (px + sx, py + sy) in pixels (pixel
 * (0,0) at the top left, (sx, sy) in [0,1)^2), with the t range between the
 * near and far clip planes. */
ray3 scene_camera_ray(const scene_t *s, int px, int py, double sx, double sy, double *tmin, double *tmax);

typedef struct {
    double t;               /* distance along the ray (unit direction) */
    vec3 n;                 /* unit shading normal, world space */
    double eps;             /* a ray continuing from the hit starts at t + eps */
    int shape;              /* the shape's index, in document order */
    const char *shape_type; /* its plugin name */
    bool sheet;             /* its BSDF lets light through undeviated (a thin sheet: thindielectric) */
} scene_hit;

/* The nearest hit along r with t in (tmin, tmax): true with *hit filled. */
bool scene_first_hit(const scene_t *s, const ray3 *r, double tmin, double tmax, scene_hit *hit);

/* The radiance arriving along r (t in (tmin, tmax)) as the scene's own
 * integrator estimates it for a camera ray: the mean of the scene's spp
 * samples, drawn from the sampler's streams of "pixel" (px, py), so a
 * caller tracing from arbitrary points (a light bake) gets the render's
 * estimator, deterministic for a seed. variance (may be NULL) receives the
 * variance of that mean's luminance, estimated from its samples (what the
 * denoiser weighs by: denoise.h). Thread-safe. */
rgb scene_radiance(const scene_t *s, const ray3 *r, double tmin, double tmax, uint32_t px, uint32_t py,
                   double *variance);

#endif
