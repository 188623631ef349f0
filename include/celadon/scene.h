/* The built, renderable scene: a Mitsuba 3 scene description (scene_xml.h)
 * turned into a camera, shapes with their BSDFs, emitters and integrator
 * settings, with an acceleration structure for ray queries.
 *
 * Geometry: every shape is traced through one Embree scene (accel.h):
 * triangle meshes (obj, ply, rectangle, cube, and `sor` under --geometry
 * mesh:N) as triangles; analytic shapes (sphere, disk, cylinder, and `sor` by
 * default) as user geometries intersected exactly in double precision in
 * their object space. */
#ifndef CELADON_SCENE_H
#define CELADON_SCENE_H

#include <stdint.h>
#include <stddef.h>

#include "celadon/camera.h"
#include "celadon/scene_xml.h"

typedef struct scene scene_t;

/* Command-line overrides; zero / negative values keep the scene's own. */
typedef struct {
    int width, height;   /* film size */
    int spp;             /* sampler sample_count */
    long long seed;      /* sampler seed; < 0 keeps the scene's */
    int mesh_segments;   /* 0: SORs analytic; N >= 3: revolved into N angular segments */
} scene_build_options;

scene_build_options scene_build_defaults(void);

/* The declaration of every plugin the renderer builds (scene_xml.h), the
 * lookup scene_desc_create_from_file checks scene files with; and the i-th
 * of them, NULL past the end. */
const scene_plugin_decl *scene_plugin_find(scene_class cls, const char *type);
const scene_plugin_decl *scene_plugin_at(int i);

/* Builds a scene from a loaded description. Returns NULL with one line
 * "file:line: problem" in err on any defect (unsupported combination, bad
 * value, unreadable mesh, profile or image). */
scene_t *scene_build(scene_desc *desc, const scene_build_options *opt, char *err, size_t errlen);
/* scene_desc_create_from_file (with scene_plugin_find) + scene_build. */
scene_t *scene_load(const char *path, const scene_define *defs, int ndefs, const scene_build_options *opt,
                    char *err, size_t errlen);
void scene_free(scene_t *s);

/* Settings the render loop needs. */
const camera_t *scene_camera(const scene_t *s);
int scene_spp(const scene_t *s);
uint64_t scene_seed(const scene_t *s);
/* Counts for reports. */
int scene_shape_count(const scene_t *s);
int scene_emitter_count(const scene_t *s);
long long scene_triangle_count(const scene_t *s);

#endif
