/* Private layout of the built scene, shared by scene_build*.c, shape_*.c,
 * emitter_*.c, scene_trace.c and the integrator. */
#ifndef CELADON_SCENE_IMPL_H
#define CELADON_SCENE_IMPL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "celadon/accel.h"
#include "bsdfs/bsdfs.h"
#include "celadon/camera.h"
#include "celadon/color.h"
#include "celadon/sampling.h"
#include "celadon/scene.h"
#include "textures/textures.h"
#include "celadon/transform.h"
#include "celadon/vecmath.h"

/* ------------------------------------------------------------- hits */

/* What an analytic shape reports in its object space. */
typedef struct {
    double t;
    vec3 p, n;        /* point, unit outward normal */
    vec2 uv;
    int part;         /* shape-specific (SOR: wall, base, mouth) */
    double param[2];  /* shape-specific surface parameters (SOR: u, phi) */
} shape_local_hit;

typedef struct {
    double t;
    vec3 p, ng;       /* world point, unit geometric normal (outside, after flip_normals) */
    frame3 sh;        /* shading frame, sh.n the shading normal */
    vec2 uv;
    double eps;       /* offset that lifts spawned rays off the surface */
    int shape;        /* index into scene->shapes */
    int prim;         /* triangle of a mesh */
    shape_local_hit local; /* analytic shapes: the object-space hit */
} surface_hit;

/* The offset that lifts rays spawned at a world point p off its surface:
 * Embree's float triangle hits are good to a few ulps of the coordinates,
 * and analytic shapes use the same offset so that a shape's secondary rays do
 * not depend on its form (the crosscheck compares an SOR analytic and meshed;
 * a form-dependent offset would leave a difference no segment count removes). */
static inline double surface_hit_eps(vec3 p)
{
    return 2e-5 * (1.0 + fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z))));
}

/* ------------------------------------------------------------- shapes */

/* An analytic shape in its object space (shape_sphere.c, ...), traced by
 * accel as an Embree user geometry. */
typedef struct {
    const char *name;
    /* Adds the shape to acc placed by to_world: the geometry id, or ACCEL_INVALID_ID with err. */
    unsigned (*add)(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen);
    /* The object-space hit of an accel hit on the shape. */
    void (*local_hit)(const void *data, const accel_hit *ah, shape_local_hit *h);
    /* A point drawn from u with its density per unit object-space area. */
    void (*sample)(const void *data, vec3 u, shape_local_hit *h, double *pdf);
    double (*pdf)(const void *data, const shape_local_hit *h);
    void (*destroy)(void *data);
} shape_analytic_ops;

typedef struct {
    int n_verts, n_tris;
    float *pos;       /* world, 3 per vertex + 1 float of padding (Embree reads 16 bytes) */
    float *nrm;       /* world, unit, or NULL */
    float *uv;        /* or NULL */
    unsigned *tri;    /* 3 per triangle */
    distribution1d area_cdf; /* over triangles by area; built only for emitters */
    double area;      /* world, total */
} shape_mesh_data;

typedef struct {
    bool is_mesh;
    bool flip_normals;
    const bsdf_t *bsdf;   /* never NULL (a default diffuse when the scene gives none) */
    int emitter;          /* index of its area emitter, or -1 */
    const char *file;     /* where it was declared, for messages */
    int line;
    /* meshes */
    shape_mesh_data mesh;
    /* analytic shapes */
    const shape_analytic_ops *ops;
    void *data;
    transform4 to_world;
    double det;           /* |det| of to_world's 3x3 part */
} shape_t;

/* World-space hit from an analytic object-space hit. */
void shape_analytic_finish(const shape_t *sh, const shape_local_hit *lh, surface_hit *hit);
/* Density per unit world area of an analytic object-space hit. */
double shape_analytic_pdf_area(const shape_t *sh, const shape_local_hit *lh);
/* The object-space hit of accel as it reports it (the quadrics' local_hit). */
void shape_analytic_local_hit(const void *data, const accel_hit *ah, shape_local_hit *h);
/* Adds a mesh, already in world space, to acc. */
unsigned shape_mesh_add(const shape_t *sh, accel_t *acc, char *err, size_t errlen);

/* World hit on triangle tri at barycentrics (b1, b2). */
void shape_mesh_finish(const shape_t *sh, int tri, double b1, double b2, double t, surface_hit *hit);

int shape_mesh_prepare_sampling(shape_mesh_data *m);
void shape_mesh_sample(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area);
/* Area-weighted vertex normals from the faces (when a file has none). */
int shape_mesh_smooth_normals(shape_mesh_data *m);

/* A point on the shape by area (emitters): world hit and density per area. */
void shape_sample_area(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area);
double shape_pdf_area(const shape_t *sh, const surface_hit *hit);
/* Prepares sampling (a mesh's triangle CDF). Returns 0 or -1. */
int shape_prepare_sampling(shape_t *sh);
void shape_free(shape_t *sh);

/* Analytic kinds. Each create returns NULL with a reason in err. */
extern const shape_analytic_ops shape_sphere_ops, shape_disk_ops, shape_cylinder_ops, shape_sor_ops;
void *shape_sor_create(const char *profile_path, double height, bool caps, char *err, size_t errlen);

/* Triangle-mesh builders: mesh in object space (nrm, uv optional), then
 * shape_mesh_transform moves it to world space. Return 0 or -1 with err. */
int shape_obj_read(const char *path, bool flip_tex_coords, shape_mesh_data *m, char *err, size_t errlen);
int shape_ply_read(const char *path, shape_mesh_data *m, char *err, size_t errlen);
int shape_rectangle_mesh(shape_mesh_data *m);
int shape_cube_mesh(shape_mesh_data *m);
int shape_sor_mesh(const char *profile_path, double height, bool caps, int segments, shape_mesh_data *m,
                   char *err, size_t errlen);
void shape_mesh_transform(shape_mesh_data *m, const transform4 *to_world);
void shape_mesh_data_free(shape_mesh_data *m);

/* ------------------------------------------------------------- emitters */

typedef enum { EMITTER_AREA, EMITTER_CONSTANT, EMITTER_ENVMAP, EMITTER_POINT, EMITTER_DIRECTIONAL } emitter_kind;

typedef struct {
    int width, height;
    rgb *pixels;            /* linear, row 0 = the top (+y, theta = 0) */
    distribution2d dist;    /* over (u, v) cells, luminance x sin(theta) */
    transform4 to_world, to_local;
    double scale;
} envmap_data;

typedef struct {
    emitter_kind kind;
    rgb value;                 /* radiance, intensity or irradiance */
    const texture_t *texture;  /* area radiance texture, or NULL */
    int shape;                 /* area: its shape */
    vec3 position;             /* point */
    vec3 direction;            /* directional: unit direction of travel */
    envmap_data *env;
} emitter_t;

/* One emitter sample seen from a reference point. */
typedef struct {
    vec3 wi;           /* unit, from the reference point toward the emitter */
    double dist;       /* INFINITY for directions at infinity */
    vec3 p, n;         /* the sampled point and its normal (area) */
    double eps;        /* offset of the sampled point (area) */
    rgb value;         /* emitted radiance (or intensity / dist^2, irradiance) arriving */
    double pdf;        /* solid angle density (1 for delta emitters) */
    bool delta;
} emitter_sample_rec;

/* u: three uniform numbers. Returns 0 when the sample carries nothing. */
int emitter_sample(const struct scene *s, const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out);
/* Radiance leaving an area emitter's hit toward -dir, and the solid-angle
 * density with which emitter_sample would have picked it from ref. */
rgb emitter_area_eval(const struct scene *s, const emitter_t *e, const surface_hit *hit, vec3 dir);
double emitter_area_pdf(const struct scene *s, const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir);
/* Radiance arriving from direction dir (unit, pointing away from the scene)
 * for constant and envmap emitters, and its sampling density. */
rgb emitter_env_eval(const emitter_t *e, vec3 dir);
double emitter_env_pdf(const emitter_t *e, vec3 dir);

int emitter_envmap_load(envmap_data *env, const char *path, char *err, size_t errlen);
rgb emitter_envmap_eval(const envmap_data *env, vec3 dir);
double emitter_envmap_pdf(const envmap_data *env, vec3 dir);
int emitter_envmap_sample(const envmap_data *env, vec2 u, vec3 *dir, rgb *value, double *pdf);
void emitter_envmap_free(envmap_data *env);
int emitter_area_sample(const struct scene *s, const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out);
void emitter_free(emitter_t *e);

/* ------------------------------------------------------------- scene */

struct scene {
    camera_t camera;
    int spp;
    uint64_t seed;
    int max_depth, rr_depth;
    bool hide_emitters;

    shape_t *shapes;
    int nshapes;
    bsdf_set bsdfs;
    texture_set textures;
    emitter_t *emitters;
    int nemitters;
    int env;              /* index of the constant/envmap emitter, or -1 */

    accel_t *accel;       /* every shape, geometry id = shape index */
    bool straight_shadows; /* some shape's BSDF has BSDF_STRAIGHT_TRANSMISSION */
};

/* Nearest hit along r with t in (tmin, tmax). */
bool scene_intersect(const struct scene *s, const ray3 *r, double tmin, double tmax, surface_hit *hit);
bool scene_occluded(const struct scene *s, const ray3 *r, double tmin, double tmax);
/* Builds the acceleration structure once all shapes are in. Returns 0 or -1. */
int scene_trace_build(struct scene *s, char *err, size_t errlen);
void scene_trace_free(struct scene *s);

#endif
