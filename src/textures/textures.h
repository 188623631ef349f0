/* Textures in the sense of Mitsuba 3: functions of the surface uv returning
 * linear RGB. Plugins (texture_table.c): `bitmap` (image file, sRGB-decoded
 * unless raw, bilinear or nearest lookups, repeat/mirror/clamp wrapping) and
 * `checkerboard`; both accept an affine `to_uv` transform applied to uv
 * first. Pixel lookup follows Mitsuba: texel (i, j) has its centre at
 * uv = ((i + 0.5) / width, (j + 0.5) / height) with row j = 0 the top row of
 * the file, i.e. v grows downwards in the image (docs/conventions.md).
 *
 * This is src/textures' interface: what the other kinds and the scene build
 * use. A plugin's own helpers are in texture_impl.h. */
#ifndef CELADON_TEXTURES_H
#define CELADON_TEXTURES_H

#include <stdbool.h>
#include <stddef.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"

typedef struct texture texture_t;

/* A mesh's named values per vertex or per face, as Mitsuba names them
 * ("vertex_color", "face_weight": vertex_ or face_ and the stem of the PLY
 * properties stem_0, stem_1, ...; r, g, b are vertex_color). */
typedef struct {
    char *name;
    int channels; /* 1 or 3 */
    bool per_face;
    float *values; /* channels per vertex, or per face */
} texture_attribute;

/* The attributes of a triangle mesh and its triangles (3 vertex indices
 * each), for `mesh_attribute`. */
typedef struct {
    texture_attribute *items;
    int count;
    const unsigned *tri;
} texture_mesh;

/* Where a texture is looked up: the surface's uv and, on a mesh with
 * attributes, the mesh, the triangle and the barycentrics of its second and
 * third vertices (mesh NULL elsewhere). */
typedef struct {
    vec2 uv;
    const texture_mesh *mesh;
    int prim;
    double b1, b2;
} texture_point;

/* The value at a surface point. */
rgb texture_eval_at(const texture_t *t, const texture_point *at);
/* The value at uv, on no mesh (emitters, tests). */
rgb texture_eval(const texture_t *t, vec2 uv);
/* Mean value over the uv unit square (Mitsuba's Texture::mean). */
rgb texture_mean(const texture_t *t);
/* Mitsuba's eval_1, a texture read as a scalar (opacity, roughness, a
 * weight, a height): the luminance of its value at uv. */
double texture_eval_1(const texture_t *t, const texture_point *at);
/* The gradient of texture_eval_1 by (u, v) (Mitsuba's eval_1_grad): the
 * bilinear interpolant's for a bilinear bitmap, zero for the piecewise
 * constant ones. */
vec2 texture_eval_1_gradient(const texture_t *t, vec2 uv);
/* Mitsuba's resolution(): a bitmap's size in texels, 1 x 1 otherwise. */
void texture_resolution(const texture_t *t, int *width, int *height);
void texture_destroy(texture_t *t);
/* Frees a mesh's attributes (their names and values, and the array). */
void texture_mesh_free(texture_mesh *m);

/* A texture plugin: its declaration for the scene reader and its constructor
 * from a <texture> object, which returns NULL with "file:line: problem" in
 * err. */
typedef struct {
    scene_plugin_decl decl;
    texture_t *(*create)(scene_obj *o, char *err, size_t errlen);
} texture_plugin;

/* The registration table: every texture plugin, NULL-terminated. */
extern const scene_plugin_decl *const texture_plugins[];
/* The plugin named name, or NULL. */
const texture_plugin *texture_plugin_find(const char *name);

/* The textures of a scene: one per <texture> object, however often it is
 * referenced, destroyed together by texture_set_free. Zero-initialise. */
typedef struct {
    scene_obj_map built;
} texture_set;

/* The texture of object o, built on first use. NULL with "file:line:
 * problem" in err. */
const texture_t *texture_set_get(texture_set *set, scene_obj *o, char *err, size_t errlen);
void texture_set_free(texture_set *set);

#endif
