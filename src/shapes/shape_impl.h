/* What the shape plugins share: analytic shapes traced in object space,
 * triangle meshes and their builders, the parameters every shape takes.
 * Private to src/shapes/. */
#ifndef CELADON_SHAPE_IMPL_H
#define CELADON_SHAPE_IMPL_H

#include "shapes/shapes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------- analytic shapes */

/* An analytic shape in its object space (sphere.c, ...), traced by accel as
 * an Embree user geometry. */
struct shape_analytic_ops {
    /* Adds the shape to acc placed by to_world: the geometry id, or ACCEL_INVALID_ID with err. */
    unsigned (*add)(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen);
    /* The object-space hit of an accel hit on the shape. */
    void (*local_hit)(const void *data, const accel_hit *ah, shape_local_hit *h);
    /* A point drawn from u with its density per unit object-space area. */
    void (*sample)(const void *data, vec3 u, shape_local_hit *h, double *pdf);
    double (*pdf)(const void *data, const shape_local_hit *h);
    void (*destroy)(void *data);
    /* The object-space derivatives of the point by the texture
     * coordinates, dp/du and dp/dv, at a hit (Mitsuba's dp_du, dp_dv). */
    void (*tangents)(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv);
    /* The object-space axis-aligned bounds. */
    void (*bounds)(const void *data, vec3 *lo, vec3 *hi);
    /* A flat shape's object-space normal (false: normals in every direction). */
    bool (*flat_normal)(const void *data, vec3 *n);
    /* The object-space shading normal at a hit, on the side of h->n (unit),
     * or NULL: the shading normal is the geometric one (an SDF grid's
     * smooth normals differ from it). */
    vec3 (*shading_normal)(const void *data, const shape_local_hit *h);
};

/* World-space hit from an analytic object-space hit. */
void shape_analytic_finish(const shape_t *sh, const shape_local_hit *lh, surface_hit *hit);
/* Density per unit world area of an analytic object-space hit. */
double shape_analytic_pdf_area(const shape_t *sh, const shape_local_hit *lh);
/* The object-space hit of accel as it reports it (the quadrics' local_hit). */
void shape_analytic_local_hit(const void *data, const accel_hit *ah, shape_local_hit *h);

/* --------------------------------------------- sampling by solid angle */

/* A shape's sampler uniform in the solid angle it subtends from a point. */
struct shape_solid_angle_ops {
    /* Its density per solid angle from ref (the same wherever the ray meets
     * the shape), or 0 where it does not apply (area sampling then). */
    double (*pdf)(const shape_t *sh, vec3 ref);
    /* A point drawn from u; returns the density, or 0 where it does not
     * apply (as pdf would). */
    double (*sample)(const shape_t *sh, vec3 ref, vec2 u, surface_hit *hit);
};

/* Below this solid angle (sr) a shape is sampled by area: the density of
 * area sampling is then nearly uniform in solid angle too, and the
 * spherical formulas lose precision (pbrt-v4 takes the same limit). */
#define SHAPE_MIN_SOLID_ANGLE 3e-4

/* ------------------------------------------------------- triangle meshes */

/* Adds a mesh, already in world space, to acc. */
unsigned shape_mesh_add(const shape_t *sh, accel_t *acc, char *err, size_t errlen);
/* World hit on triangle tri at barycentrics (b1, b2). */
void shape_mesh_finish(const shape_t *sh, int tri, double b1, double b2, double t, surface_hit *hit);
/* The same as a sampled point (shape_sample_area): without the shading
 * frame and the derivatives, which nothing shades it with. */
void shape_mesh_point(const shape_t *sh, int tri, double b1, double b2, surface_hit *hit);
int shape_mesh_prepare_sampling(shape_mesh_data *m);
/* The mesh's world bounds and normal cone into sh (shape_prepare_sampling). */
void shape_mesh_extent(shape_t *sh);
void shape_mesh_sample(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area);
void shape_mesh_transform(shape_mesh_data *m, const transform4 *to_world);
void shape_mesh_data_free(shape_mesh_data *m);

/* A mesh just read from file (rc: the reader's result, why its reason) made
 * ready: vertex normals dropped for `face_normals`, or area-weighted smooth
 * ones made when the file has none (Mitsuba does the same). Returns 0, or -1
 * with "file:line: <shape type="T">: why" in err. */
int shape_mesh_from_file(scene_obj *o, int rc, const char *why, shape_t *sh, char *err, size_t errlen);

/* n_verts vertices with positions, normals and uvs and n_tris triangles,
 * zeroed; 0 or -1 when out of memory. */
int shape_mesh_alloc(shape_mesh_data *m, int nv, int nt);
/* Writes face f of a canonical shape: the square [-1,1]^2 spanned by axes a,
 * b at +-1 along axis c (sign s), counter-clockwise seen from outside, with
 * uv = ((x+1)/2, (y+1)/2) over the square. */
void shape_mesh_square_face(shape_mesh_data *m, int f, int a, int b, int c, double s);

/* -------------------------------------------------------------- plugins */

/* The parameters every shape takes, and what every shape may hold. */
#define SHAPE_PARAMS_COMMON                                                                                 \
    {"to_world", PARAM_TRANSFORM, 0, NULL}, {"flip_normals", PARAM_BOOL, 0, NULL},                           \
        {"interior", PARAM_OBJECT, 0, NULL}, {"exterior", PARAM_OBJECT, 0, NULL}
#define SHAPE_PARAMS_END {NULL, 0, 0, NULL}

/* A curve shape (curve.c) of kind ACCEL_KIND_CURVE_LINEAR or _BSPLINE from
 * the file its `filename` names, placed by to_world: 0, or -1 with err. */
int curve_shape_create(scene_obj *o, accel_kind kind, const transform4 *to_world, shape_t *sh, char *err,
                       size_t errlen);
extern const scene_child_decl shape_children[];

#endif
