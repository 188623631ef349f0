/* Shapes in the sense of Mitsuba 3, and the ray queries over all of a
 * scene's shapes. Every shape is traced through one Embree scene (accel.h):
 * triangle meshes (obj, ply, rectangle, cube, and `sor` under --geometry
 * mesh:N) as triangles; analytic shapes (sphere, disk, cylinder, sdfgrid,
 * and `sor` by default) as user geometries intersected exactly in double
 * precision in their object space.
 *
 * This is src/shapes' interface: what emitters, integrators and the scene
 * build use. The plugins' own helpers are in shape_impl.h; each plugin is one
 * file plus one line of shape_table.c (docs/plugins.md). */
#ifndef CELADON_SHAPES_H
#define CELADON_SHAPES_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "bsdfs/bsdfs.h"
#include "celadon/accel.h"
#include "celadon/sampling.h"
#include "celadon/scene_xml.h"
#include "celadon/transform.h"
#include "celadon/vecmath.h"

typedef struct shape shape_t;
struct emitter;
struct medium;

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
    vec3 dpdu, dpdv;  /* world derivatives of p by the texture coordinates (Mitsuba's dp_du, dp_dv) */
    double eps;       /* offset that lifts spawned rays off the surface */
    const shape_t *shape;
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
    /* the largest |coordinate| by comparisons: fmax is a call into libm here */
    double ax = fabs(p.x), ay = fabs(p.y), az = fabs(p.z), m = ax > ay ? ax : ay;
    return 2e-5 * (1.0 + (m > az ? m : az));
}

/* The BSDF query at a hit for light leaving toward -dir (dir: the world
 * direction of the ray that arrived): wi, uv, and the surface's
 * derivatives and geometric normal in the local shading frame. */
bsdf_query shape_bsdf_query(const surface_hit *hit, vec3 dir, transport_mode mode);

/* ------------------------------------------------------------- shapes */

typedef struct shape_analytic_ops shape_analytic_ops;
typedef struct shape_solid_angle_ops shape_solid_angle_ops;

typedef struct {
    int n_verts, n_tris;
    float *pos;       /* world, 3 per vertex + 1 float of padding (Embree reads 16 bytes) */
    float *nrm;       /* world, unit, or NULL */
    bool nrm_per_face; /* each triangle's three normals equal (shape_mesh_transform) */
    float *uv;        /* or NULL */
    unsigned *tri;    /* 3 per triangle */
    texture_mesh attrs; /* its attributes (ply), attrs.tri = tri; none: count 0 */
    distribution1d area_cdf; /* over triangles by area; built only for emitters */
    double area;      /* world, total */
} shape_mesh_data;

struct shape {
    const char *type;     /* the plugin name */
    bool is_mesh;
    bool flip_normals;
    const bsdf_t *bsdf;   /* never NULL once the scene is built */
    const struct emitter *emitter; /* its area emitter, or NULL */
    /* the media behind its normal and in front of it (Mitsuba's interior
     * and exterior), NULL for none; a shape with neither leaves the medium
     * of a ray that crosses it unchanged */
    const struct medium *interior, *exterior;
    const char *file;     /* where it was declared, for messages */
    int line;
    /* meshes */
    shape_mesh_data mesh;
    /* analytic shapes */
    const shape_analytic_ops *ops;
    void *data;
    transform4 to_world;  /* every shape's (a mesh is already placed by it) */
    double det;           /* |det| of to_world's 3x3 part */
    /* sampling by solid angle from a point (shape_sample_from), or NULL,
     * and what it keeps (a rectangle: its world corner and edges) */
    const shape_solid_angle_ops *solid_angle;
    vec3 solid_angle_frame[3];
    /* what light selection needs of an emitting shape (shape_prepare_sampling) */
    double area;          /* world */
    vec3 bounds_lo, bounds_hi;      /* world, axis-aligned */
    vec3 normal_axis;     /* every normal within acos(normal_cos) of it */
    double normal_cos;    /* -1: normals in every direction */
    /* a flat emitting mesh (every triangle in one plane, facing one way):
     * a vertex, the unit normal (zero for any other shape), how far the
     * vertices lie off that plane and the triangles' unit normals off
     * plane_n at most, and the bounds' diagonal: shape_faces_away */
    vec3 plane_o, plane_n;
    double plane_off, plane_turn, plane_extent;
};

/* How shapes are built: options of the whole render. */
typedef struct {
    int mesh_segments; /* 0: SORs analytic; N >= 3: revolved into N angular segments */
} shape_options;

/* A shape to build: a <shape> object and, for a shape of an instanced
 * group, the instance's transform that places it beyond its own to_world. */
typedef struct {
    scene_obj *obj;
    bool placed;      /* a shape of a group, placed by an instance */
    transform4 outer; /* the instance's to_world */
} shape_leaf;

/* The shapes a top-level <shape> object stands for (instance.c): itself;
 * nothing for a shapegroup; for an instance, the shapes of its group under
 * the instance's to_world. Writes up to max of them to out and returns how
 * many there are, or -1 with "file:line: problem" in err. */
int shape_leaves(scene_obj *o, shape_leaf *out, int max, char *err, size_t errlen);

/* Builds the geometry of a <shape> object, placed by outer · to_world (or
 * to_world when outer is NULL), into sh (its bsdf and emitter are the scene build's): 0, or -1 with
 * "file:line: problem" in err. */
int shape_create(scene_obj *o, const transform4 *outer, const shape_options *opt, shape_t *sh, char *err,
                 size_t errlen);
/* Frees what shape_create allocated. */
void shape_free(shape_t *sh);

/* Prepares sampling (a mesh's triangle CDF) and fills the shape's area,
 * bounds and normal cone: 0, or -1 when the shape has no area or memory ran
 * out. */
int shape_prepare_sampling(shape_t *sh);
/* The shape's world-space axis-aligned bounds (NaN where a coordinate is). */
void shape_world_bounds(const shape_t *sh, vec3 *lo, vec3 *hi);
/* How far from the origin a shape may reach: Embree takes rays from at most
 * 1.844e18 (FLT_LARGE), and paths start on the shapes. */
#define SHAPE_MAX_COORD 1e15
/* A point on the shape by area: world hit and density per area. A sampled
 * point of a mesh carries p, ng, uv, eps, prim and its barycentrics, not
 * the shading frame or dp/du, dp/dv (nothing shades a light sample). */
void shape_sample_area(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area);
double shape_pdf_area(const shape_t *sh, const surface_hit *hit);

/* A point on the shape as seen from ref (emitters; the hit as
 * shape_sample_area's): drawn uniformly in the
 * solid angle the shape subtends where it has such a sampler (a rectangle,
 * by spherical rectangles; a sphere from outside, by the cone it subtends)
 * and that solid angle is large enough to matter, by area otherwise. Its
 * density per unit solid angle at ref in *pdf (0: no usable sample, e.g.
 * ref on the shape). */
void shape_sample_from(const shape_t *sh, vec3 ref, vec3 u, surface_hit *hit, double *pdf);
/* Whether ref lies behind the shape beyond rounding, so that every point
 * of it shape_sample_from can draw has its geometric normal turned away
 * from ref (dot(ng, p - ref) > 0): a flat mesh (shape_prepare_sampling)
 * with ref behind its plane by more than its vertices' and normals' spread
 * can account for. False whenever that is not certain. */
bool shape_faces_away(const shape_t *sh, vec3 ref);
/* The density per solid angle with which shape_sample_from draws hit, the
 * first point of the shape along the ray from ref. */
double shape_pdf_from(const shape_t *sh, vec3 ref, const surface_hit *hit);

/* A shape plugin: its declaration for the scene reader and the constructor
 * of its geometry. create fills sh->mesh in object space (shape_create then
 * places it by to_world) or, for an analytic shape, sh->ops, sh->data and
 * sh->to_world; it returns 0, or -1 with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    int (*create)(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                  size_t errlen);
} shape_plugin;

/* The registration table: every shape plugin, NULL-terminated. */
extern const scene_plugin_decl *const shape_plugins[];
/* The plugin named name, or NULL. */
const shape_plugin *shape_plugin_find(const char *name);

/* ------------------------------------------------------- the scene's shapes */

/* A scene's shapes in one acceleration structure. */
typedef struct {
    shape_t *items;
    int count;
    accel_t *accel;        /* every shape, geometry id = index */
    bool straight_shadows; /* some shape's BSDF has BSDF_STRAIGHT_TRANSMISSION */
} shape_list;

/* Builds the acceleration structure once all shapes are in: 0, or -1 with err. */
int shape_list_commit(shape_list *l, char *err, size_t errlen);
/* Nearest hit along r with t in (tmin, tmax). Thread-safe after commit. */
bool shape_list_intersect(const shape_list *l, const ray3 *r, double tmin, double tmax, surface_hit *hit);
bool shape_list_occluded(const shape_list *l, const ray3 *r, double tmin, double tmax);
/* Frees the shapes and the acceleration structure. */
void shape_list_free(shape_list *l);

#endif
