/* Surface scattering models with Mitsuba 3's plugin names, parameters, defaults
 * and conventions (docs/materials.md). This is src/bsdfs' interface: what
 * integrators and the scene build use; the plugins' own helpers are in
 * bsdf_impl.h, and each plugin is one file plus one line of bsdf_table.c
 * (docs/plugins.md).
 *
 * Directions live in the local shading frame: z is the shading normal,
 * z > 0 the front (outside) side. `wi` points from the surface towards the
 * previous path vertex (the camera side when tracing radiance) and `wo` is the
 * sampled or queried other direction; both unit vectors.
 *
 *   bsdf_eval  returns f(wi, wo) |cos theta_o| (zero for delta lobes);
 *   bsdf_pdf   the solid-angle density bsdf_sample uses to choose wo
 *              (non-delta part only; zero for pure-delta BSDFs);
 *   bsdf_sample draws wo and returns weight = f |cos theta_o| / pdf (for delta
 *              lobes: the lobe's reflectance / selection probability).
 *
 * Transport mode: in TRANSPORT_RADIANCE (paths from the camera) refraction
 * scales by 1 / eta^2 (eta = n_o / n_i of the crossing), as Mitsuba does;
 * TRANSPORT_IMPORTANCE (paths from lights) does not.
 *
 * Ownership: a BSDF borrows the textures and nested BSDFs it is built with
 * (a bsdf_set and its texture_set own them all). */
#ifndef CELADON_BSDFS_H
#define CELADON_BSDFS_H

#include <stddef.h>

#include "celadon/color.h"
#include "celadon/scene_xml.h"
#include "celadon/vecmath.h"
#include "textures/textures.h"

typedef struct bsdf bsdf_t;

enum {
    BSDF_DIFFUSE_REFLECTION = 1u << 0,
    BSDF_GLOSSY_REFLECTION = 1u << 1,
    BSDF_DELTA_REFLECTION = 1u << 2,
    BSDF_GLOSSY_TRANSMISSION = 1u << 3,
    BSDF_DELTA_TRANSMISSION = 1u << 4,
    BSDF_FRONT_SIDE = 1u << 5, /* scatters light arriving on the front */
    BSDF_BACK_SIDE = 1u << 6,  /* ... and on the back */
    /* Its delta transmission continues the ray undeviated (wo = -wi: a thin
     * sheet), so a shadow ray may cross it, weighted by
     * bsdf_straight_transmittance, instead of being blocked. A sample that
     * went straight through carries this bit in its sampled_type too. */
    BSDF_STRAIGHT_TRANSMISSION = 1u << 7,
    /* Mitsuba's null lobe: the light goes on as if the surface were not
     * there (`null`, the transparent part of `mask`); such a surface does
     * not count as covering the pixel (alpha). */
    BSDF_NULL = 1u << 8,
    BSDF_DIFFUSE_TRANSMISSION = 1u << 9,
    /* Its lobes are oriented around the normal: the BSDF works in Mitsuba's
     * shading frame, whose x axis is dp/du made perpendicular to the
     * normal (bsdf_query's dpdu); the dispatch turns the query into it. */
    BSDF_ANISOTROPIC = 1u << 10,
};
#define BSDF_DELTA (BSDF_DELTA_REFLECTION | BSDF_DELTA_TRANSMISSION | BSDF_NULL)
/* Lobes that bsdf_eval can see: next-event estimation is useful for them. */
#define BSDF_SMOOTH                                                                                                \
    (BSDF_DIFFUSE_REFLECTION | BSDF_GLOSSY_REFLECTION | BSDF_GLOSSY_TRANSMISSION | BSDF_DIFFUSE_TRANSMISSION)
#define BSDF_TRANSMISSION (BSDF_GLOSSY_TRANSMISSION | BSDF_DELTA_TRANSMISSION | BSDF_NULL | BSDF_DIFFUSE_TRANSMISSION)

typedef enum { TRANSPORT_RADIANCE, TRANSPORT_IMPORTANCE } transport_mode;

typedef struct {
    vec3 wi;             /* local frame, unit */
    vec2 uv;             /* surface texture coordinates */
    transport_mode mode;
    /* The surface in the local frame, for the BSDFs that perturb the
     * shading frame (normalmap, bumpmap) or orient it (anisotropy): the
     * derivatives dp/du, dp/dv of the point by the texture coordinates and
     * the geometric normal. Zero when unknown: the tangent is then local
     * +x and the geometric normal +z. */
    vec3 dpdu, dpdv, ng;
    /* On a mesh with attributes (mesh_attribute textures): the mesh, the
     * triangle and its barycentrics (texture_point); mesh NULL elsewhere. */
    const texture_mesh *mesh;
    int prim;
    double b1, b2;
} bsdf_query;

typedef struct {
    vec3 wo;               /* local frame, unit */
    rgb weight;            /* f |cos theta_o| / pdf */
    double pdf;            /* solid-angle density; selection probability for delta lobes */
    double eta;            /* n_o / n_i of the crossing: 1 for reflection (Russian roulette uses it) */
    unsigned sampled_type; /* one of the lobe flags above (and BSDF_STRAIGHT_TRANSMISSION when straight on) */
} bsdf_sample_rec;

/* u1 picks the lobe, u2 the direction; returns 1 with *out filled, or 0 when
 * no direction is produced (e.g. wi on the black side). */
int bsdf_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out);
rgb bsdf_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo);
double bsdf_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo);
unsigned bsdf_flags(const bsdf_t *b);
/* Albedo for AOVs and denoisers: the diffuse reflectance of diffuse and plastic
 * materials, F(normal) * specular_reflectance of conductors, the specular
 * transmittance of dielectrics; the front BSDF of twosided. */
rgb bsdf_albedo(const bsdf_t *b, vec2 uv);
/* The fraction of light arriving along -q->wi that leaves straight through
 * along q->wi's opposite side undeviated: f / pdf * selection probability of
 * the straight delta transmission lobe. Black unless BSDF_STRAIGHT_TRANSMISSION. */
rgb bsdf_straight_transmittance(const bsdf_t *b, const bsdf_query *q);
/* The shading normal the BSDF works with, in the local frame: +z, or the
 * normal a normalmap or bumpmap perturbs it to (Mitsuba's sh_frame). */
vec3 bsdf_shading_normal(const bsdf_t *b, const bsdf_query *q);
void bsdf_destroy(bsdf_t *b);

/* ---------------------------------------------------------- the plugins */
typedef struct bsdf_set bsdf_set;

/* A BSDF plugin: its declaration for the scene reader and its constructor
 * from a <bsdf> object, which builds the textures and nested BSDFs its
 * parameters name in set and returns NULL with "file:line: problem" in err. */
typedef struct {
    scene_plugin_decl decl;
    bsdf_t *(*create)(scene_obj *o, bsdf_set *set, char *err, size_t errlen);
} bsdf_plugin;

/* The registration table: every BSDF plugin, NULL-terminated. */
extern const scene_plugin_decl *const bsdf_plugins[];
/* The plugin named name, or NULL. */
const bsdf_plugin *bsdf_plugin_find(const char *name);

/* The BSDFs of a scene: one per <bsdf> object, however often it is
 * referenced, and the default one. Zero-initialise it with the texture set
 * the BSDFs' textures go to. */
struct bsdf_set {
    texture_set *textures;
    scene_obj_map built; /* in the order built: nested BSDFs before their outer one */
};

/* The BSDF of object o, built on first use. NULL with "file:line: problem"
 * in err. */
const bsdf_t *bsdf_set_get(bsdf_set *set, scene_obj *o, char *err, size_t errlen);
/* Mitsuba's BSDF for a shape that names none (diffuse, reflectance 0.5),
 * built once; a failure names the object at. */
const bsdf_t *bsdf_set_default(bsdf_set *set, const scene_obj *at, char *err, size_t errlen);
/* Destroys the BSDFs, outer ones before those they borrow. */
void bsdf_set_free(bsdf_set *set);

#endif
