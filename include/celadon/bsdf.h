/* Surface scattering models with Mitsuba 3's plugin names, parameters, defaults
 * and conventions (docs/materials.md).
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
 * Ownership: a BSDF borrows the textures and nested BSDFs it is given; they
 * must outlive it, and bsdf_free frees only the BSDF itself. */
#ifndef CELADON_BSDF_H
#define CELADON_BSDF_H

#include <stddef.h>

#include "celadon/color.h"
#include "celadon/microfacet.h"
#include "celadon/texture.h"
#include "celadon/vecmath.h"

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
     * bsdf_straight_transmittance, instead of being blocked. */
    BSDF_STRAIGHT_TRANSMISSION = 1u << 7,
};
#define BSDF_DELTA (BSDF_DELTA_REFLECTION | BSDF_DELTA_TRANSMISSION)
/* Lobes that bsdf_eval can see: next-event estimation is useful for them. */
#define BSDF_SMOOTH (BSDF_DIFFUSE_REFLECTION | BSDF_GLOSSY_REFLECTION | BSDF_GLOSSY_TRANSMISSION)
#define BSDF_TRANSMISSION (BSDF_GLOSSY_TRANSMISSION | BSDF_DELTA_TRANSMISSION)

typedef enum { TRANSPORT_RADIANCE, TRANSPORT_IMPORTANCE } transport_mode;

typedef struct {
    vec3 wi;             /* local frame, unit */
    vec2 uv;             /* surface texture coordinates */
    transport_mode mode;
} bsdf_query;

typedef struct {
    vec3 wo;               /* local frame, unit */
    rgb weight;            /* f |cos theta_o| / pdf */
    double pdf;            /* solid-angle density; selection probability for delta lobes */
    double eta;            /* n_o / n_i of the crossing: 1 for reflection (Russian roulette uses it) */
    unsigned sampled_type; /* one of the lobe flags above */
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
const char *bsdf_plugin_name(const bsdf_t *b);
void bsdf_free(bsdf_t *b);

/* Parameter names each plugin accepts (NULL-terminated), or NULL for an unknown
 * plugin: the scene parser reports anything else as an unknown parameter. */
const char *const *bsdf_plugin_params(const char *plugin);

/* Mitsuba's named indices of refraction ("bk7", "air", "water", ...; case-
 * insensitive). Returns 0 and sets *ior, or -1 for an unknown name. */
int bsdf_ior_lookup(const char *name, double *ior);
/* A NULL-terminated list of the accepted IOR names (for error messages). */
const char *const *bsdf_ior_names(void);
/* Mitsuba's conductor presets as RGB complex IOR: "Ag", "Al", "Au", "Cu", and
 * "none" (eta 0, k 1: a perfect mirror). Returns 0, or -1 for an unknown name. */
int bsdf_conductor_preset(const char *name, rgb *eta, rgb *k);
const char *const *bsdf_conductor_names(void);

/* A Mitsuba "spectrum or texture" parameter: the texture if non-NULL, else value. */
typedef struct {
    rgb value;
    const texture_t *texture;
} bsdf_spectrum;
static inline bsdf_spectrum bsdf_spectrum_const(rgb v) { return (bsdf_spectrum){v, NULL}; }
static inline bsdf_spectrum bsdf_spectrum_tex(const texture_t *t) { return (bsdf_spectrum){rgb_gray(0.0), t}; }

/* ---- plugin parameters; *_defaults() gives Mitsuba's defaults ---- */

typedef struct {
    bsdf_spectrum reflectance; /* 0.5 */
} bsdf_diffuse_params;

/* dielectric and thindielectric */
typedef struct {
    double int_ior;                      /* 1.5046 (bk7) */
    double ext_ior;                      /* 1.000277 (air) */
    bsdf_spectrum specular_reflectance;  /* 1 */
    bsdf_spectrum specular_transmittance; /* 1 */
} bsdf_dielectric_params;

typedef struct {
    double int_ior, ext_ior;             /* bk7, air */
    microfacet_type distribution;        /* beckmann */
    double alpha_u, alpha_v;             /* 0.1 ("alpha" sets both) */
    int sample_visible;                  /* 1 */
    bsdf_spectrum specular_reflectance, specular_transmittance; /* 1, 1 */
} bsdf_roughdielectric_params;

typedef struct {
    rgb eta, k;                         /* material "none": eta 0, k 1 */
    bsdf_spectrum specular_reflectance; /* 1 */
} bsdf_conductor_params;

typedef struct {
    rgb eta, k;                         /* material "none" */
    microfacet_type distribution;       /* beckmann */
    double alpha_u, alpha_v;            /* 0.1 */
    int sample_visible;                 /* 1 */
    bsdf_spectrum specular_reflectance; /* 1 */
} bsdf_roughconductor_params;

typedef struct {
    bsdf_spectrum diffuse_reflectance;  /* 0.5 */
    bsdf_spectrum specular_reflectance; /* 1 */
    double int_ior, ext_ior;            /* 1.49 (polypropylene), air */
    int nonlinear;                      /* 0 */
} bsdf_plastic_params;

typedef struct {
    bsdf_spectrum diffuse_reflectance, specular_reflectance; /* 0.5, 1 */
    double int_ior, ext_ior;                                 /* polypropylene, air */
    int nonlinear;                                           /* 0 */
    microfacet_type distribution;                            /* beckmann */
    double alpha;                                            /* 0.1 */
    int sample_visible;                                      /* 1 */
} bsdf_roughplastic_params;

bsdf_diffuse_params bsdf_diffuse_defaults(void);
bsdf_dielectric_params bsdf_dielectric_defaults(void);
bsdf_roughdielectric_params bsdf_roughdielectric_defaults(void);
bsdf_conductor_params bsdf_conductor_defaults(void);
bsdf_roughconductor_params bsdf_roughconductor_defaults(void);
bsdf_plastic_params bsdf_plastic_defaults(void);
bsdf_roughplastic_params bsdf_roughplastic_defaults(void);

/* Constructors validate their parameters and return NULL with a one-line reason
 * in err (naming the parameter) when one is out of range. */
bsdf_t *bsdf_create_diffuse(const bsdf_diffuse_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_dielectric(const bsdf_dielectric_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_thindielectric(const bsdf_dielectric_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_roughdielectric(const bsdf_roughdielectric_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_conductor(const bsdf_conductor_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_roughconductor(const bsdf_roughconductor_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_plastic(const bsdf_plastic_params *p, char *err, size_t errlen);
bsdf_t *bsdf_create_roughplastic(const bsdf_roughplastic_params *p, char *err, size_t errlen);
/* Front-and-back adapter: `front` is used on the front side, `back` (or `front`
 * again when NULL) on the back with the frame mirrored. Both must be
 * reflection-only, as in Mitsuba. */
bsdf_t *bsdf_create_twosided(const bsdf_t *front, const bsdf_t *back, char *err, size_t errlen);

#endif
