/* What the BSDF plugins share: the BSDF record they fill, "spectrum or
 * texture" values, Mitsuba's named IORs and conductor presets, and the
 * readers and checks of the parameters several plugins take. Private to
 * src/bsdfs/. */
#ifndef CELADON_BSDF_IMPL_H
#define CELADON_BSDF_IMPL_H

#include "bsdfs/bsdfs.h"
#include "bsdfs/microfacet.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    const char *name; /* the plugin's */
    int (*sample)(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out);
    rgb (*eval)(const bsdf_t *b, const bsdf_query *q, vec3 wo);
    double (*pdf)(const bsdf_t *b, const bsdf_query *q, vec3 wo);
    rgb (*albedo)(const bsdf_t *b, texture_point uv);
    rgb (*straight)(const bsdf_t *b, const bsdf_query *q); /* NULL unless BSDF_STRAIGHT_TRANSMISSION */
    vec3 (*shading_normal)(const bsdf_t *b, const bsdf_query *q); /* NULL: the frame's own, +z */
} bsdf_ops;

struct bsdf {
    const bsdf_ops *ops;
    unsigned flags;
    void *data; /* the plugin's parameters, allocated together with the struct */
};

/* One allocation holding the bsdf and a copy of the data_size bytes of plugin
 * data at data. NULL when out of memory, with err naming o. */
bsdf_t *bsdf_alloc(const scene_obj *o, const bsdf_ops *ops, unsigned flags, const void *data, size_t data_size,
                   char *err, size_t errlen);

/* A Mitsuba "spectrum or texture" parameter: the texture if non-NULL, else value. */
typedef struct {
    rgb value;
    const texture_t *texture;
} bsdf_spectrum;

/* The texture point of a query. */
static inline texture_point bsdf_at(const bsdf_query *q)
{
    return (texture_point){q->uv, q->mesh, q->prim, q->b1, q->b2};
}

static inline rgb spectrum_eval(const bsdf_spectrum *s, texture_point uv)
{
    return s->texture ? texture_eval_at(s->texture, &uv) : s->value;
}
static inline double spectrum_mean(const bsdf_spectrum *s)
{
    return rgb_mean(s->texture ? texture_mean(s->texture) : s->value);
}

/* A Mitsuba "float or texture" parameter, read as a scalar (eval_1: the
 * texture's luminance): the texture if non-NULL, else value. */
typedef struct {
    double value;
    const texture_t *texture;
} bsdf_scalar;

static inline double scalar_eval(const bsdf_scalar *s, texture_point uv)
{
    return s->texture ? texture_eval_1(s->texture, &uv) : s->value;
}

/* A microfacet distribution whose roughness may vary over the surface
 * (textured alpha), and the distribution at a point. */
typedef struct {
    microfacet_type type;
    bsdf_scalar alpha_u, alpha_v;
    int sample_visible;
} bsdf_roughness;

/* Whether the roughness differs along u and v (or may): BSDF_ANISOTROPIC. */
static inline unsigned bsdf_roughness_flags(const bsdf_roughness *r)
{
    bool same = r->alpha_u.texture == r->alpha_v.texture && r->alpha_u.value == r->alpha_v.value;
    return same ? 0u : BSDF_ANISOTROPIC;
}

static inline microfacet bsdf_roughness_at(const bsdf_roughness *r, texture_point uv)
{
    return microfacet_make(r->type, scalar_eval(&r->alpha_u, uv), scalar_eval(&r->alpha_v, uv), r->sample_visible);
}

/* bsdf_albedo at a surface point (a nested BSDF's, for its wrapper). */
rgb bsdf_albedo_at(const bsdf_t *b, texture_point at);

/* eval and pdf of BSDFs made only of delta lobes: always zero. */
rgb bsdf_eval_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo);
double bsdf_pdf_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo);

/* Rough-BSDF sampling epilogue: fills weight = eval / pdf from the BSDF's own
 * eval and pdf, rejecting a zero density. */
int bsdf_finish_sample(const bsdf_t *b, const bsdf_query *q, bsdf_sample_rec *out);

/* ------------------------------ perturbed shading frames (perturbed_frame.c) */
/* normalmap and bumpmap: a nested BSDF evaluated in a shading frame given
 * in the local frame (its n the perturbed normal). With flip_invalid, a
 * normal that wi sees from behind has its tangential part mirrored
 * (Mitsuba's flip_invalid_normals). Directions whose sides differ between
 * the two frames are refused (zero), as in Mitsuba; with shadowing, values
 * are multiplied by the microfacet shadowing term of Estevez et al. 2019
 * that Mitsuba applies (use_shadowing_function). */

/* Mitsuba's tangent at a hit, local +x or along dp/du: the x axis of its
 * shading frame, in the local frame. */
vec3 bsdf_query_tangent(const bsdf_query *q);
/* The data of a perturbing BSDF begins with this: its nested BSDF, its
 * options, and the function that gives its frame at a query. The
 * bsdf_perturbing_* functions are then its ops. */
typedef struct {
    const bsdf_t *nested;
    bool flip_invalid, shadowing;
    /* The perturbed normal at q (any length) and the tangent it is made
     * perpendicular to, in the local frame. */
    void (*normal)(const void *data, const bsdf_query *q, vec3 *n, vec3 *tangent);
} bsdf_perturbing;

int bsdf_perturbing_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out);
rgb bsdf_perturbing_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo);
double bsdf_perturbing_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo);
rgb bsdf_perturbing_albedo(const bsdf_t *b, texture_point uv);
vec3 bsdf_perturbing_shading_normal(const bsdf_t *b, const bsdf_query *q);
#define BSDF_PERTURBING_OPS(name)                                                                                 \
    {name, bsdf_perturbing_sample, bsdf_perturbing_eval, bsdf_perturbing_pdf, bsdf_perturbing_albedo, NULL,         \
     bsdf_perturbing_shading_normal}
/* Reads the nested BSDF and the two options into d. 0, or -1 with err. */
int bsdf_perturbing_param(bsdf_set *set, scene_obj *o, bsdf_perturbing *d, char *err, size_t errlen);

/* Mitsuba's named indices of refraction ("bk7", "air", "water", ...), as
 * the '|'-separated choices of int_ior and ext_ior (ior.c). */
extern const char bsdf_ior_names[];
/* The index of refraction of a name of bsdf_ior_names (case-insensitive).
 * Returns 0 and sets *ior, or -1 for an unknown name. */
int bsdf_ior_lookup(const char *name, double *ior);
/* Mitsuba's conductor presets as RGB complex IOR: "Ag", "Al", "Au", "Cu", and
 * "none" (eta 0, k 1: a perfect mirror). Returns 0, or -1 for an unknown name. */
int bsdf_conductor_preset(const char *name, rgb *eta, rgb *k);

/* ------------------------------------------------ parameters (bsdf_params.c) */
/* Declarations of the parameters several plugins take. */
#define BSDF_PARAMS_IOR                                                                                            \
    {"int_ior", PARAM_FLOAT | PARAM_STRING, 0, bsdf_ior_names},                                                    \
        {"ext_ior", PARAM_FLOAT | PARAM_STRING, 0, bsdf_ior_names}
#define BSDF_PARAMS_ROUGHNESS                                                                                      \
    {"distribution", PARAM_STRING, 0, "beckmann|ggx"}, {"alpha", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},           \
        {"alpha_u", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL}, {"alpha_v", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},     \
        {"sample_visible", PARAM_BOOL, 0, NULL}
/* The families: dielectric, thindielectric and roughdielectric; conductor and
 * roughconductor; plastic and roughplastic. */
#define BSDF_PARAMS_DIELECTRIC                                                                                     \
    BSDF_PARAMS_IOR, {"specular_reflectance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},                              \
        {"specular_transmittance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}
#define BSDF_PARAMS_CONDUCTOR                                                                                      \
    {"material", PARAM_STRING, 0, NULL}, {"eta", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},                           \
        {"k", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}, {"specular_reflectance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}
#define BSDF_PARAMS_PLASTIC                                                                                        \
    BSDF_PARAMS_IOR, {"diffuse_reflectance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},                               \
        {"specular_reflectance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}, {"nonlinear", PARAM_BOOL, 0, NULL}
#define BSDF_PARAMS_END {NULL, 0, 0, NULL}

/* Readers: 0, or -1 with "file:line: problem" in err. */
/* A "color or texture" parameter, a gray def when absent; textures are built in set. */
int bsdf_spectrum_param(bsdf_set *set, scene_obj *o, const char *name, double def, bsdf_spectrum *out, char *err,
                        size_t errlen);
/* A float-or-IOR-name parameter, def when absent. */
int bsdf_ior_param(scene_obj *o, const char *name, double def, double *out, char *err, size_t errlen);
/* int_ior and ext_ior, Mitsuba's named IOR inside (e.g. "bk7") and air
 * outside when absent. */
int bsdf_ior_pair_param(scene_obj *o, const char *inside, double *int_ior, double *ext_ior, char *err,
                        size_t errlen);
/* The indices of refraction (bk7 inside, air outside by default) and the
 * specular reflectance and transmittance (1) of the dielectric family. */
int bsdf_dielectric_param(bsdf_set *set, scene_obj *o, double *int_ior, double *ext_ior, bsdf_spectrum *reflectance,
                          bsdf_spectrum *transmittance, char *err, size_t errlen);
/* The same, checked, for the smooth ones: *eta = int_ior / ext_ior. */
int bsdf_smooth_dielectric_param(bsdf_set *set, scene_obj *o, double *eta, bsdf_spectrum *reflectance,
                                 bsdf_spectrum *transmittance, char *err, size_t errlen);
/* The indices of refraction (polypropylene inside, air outside by default),
 * the diffuse (0.5) and specular (1) reflectances and `nonlinear` of the
 * plastic family. */
int bsdf_plastic_param(bsdf_set *set, scene_obj *o, double *int_ior, double *ext_ior, bsdf_spectrum *diffuse,
                       bsdf_spectrum *specular, int *nonlinear, char *err, size_t errlen);
/* The plastics' probability of sampling the specular lobe: its share of the
 * mean reflectances (1/2 when both are black). */
double bsdf_specular_sampling_weight(const bsdf_spectrum *diffuse, const bsdf_spectrum *specular);
/* A conductor's complex IOR: the `material` preset (default "none"),
 * overridden by constant `eta` and `k`. */
int bsdf_conductor_param(scene_obj *o, rgb *eta, rgb *k, char *err, size_t errlen);
/* A "float or texture" parameter, def when absent (a color, where one is
 * allowed, is its luminance); textures are built in set. */
int bsdf_scalar_param(bsdf_set *set, scene_obj *o, const char *name, double def, bsdf_scalar *out, char *err,
                      size_t errlen);
/* The microfacet parameters of BSDF_PARAMS_ROUGHNESS, Mitsuba's defaults
 * (beckmann, alpha 0.1, visible normals): `alpha` sets both alphas,
 * `alpha_u`/`alpha_v` each; each may be a texture. Constants are checked
 * non-negative. */
int bsdf_roughness_param(bsdf_set *set, scene_obj *o, bsdf_roughness *out, char *err, size_t errlen);

/* Checks of values: 0, or -1 with "file:line: <bsdf type='T'>: reason"
 * naming the parameter. */
int bsdf_check_ior(const scene_obj *o, double int_ior, double ext_ior, char *err, size_t errlen);
int bsdf_check_alpha(const scene_obj *o, const char *name, double alpha, char *err, size_t errlen);
int bsdf_check_spectrum(const scene_obj *o, const char *name, const bsdf_spectrum *s, char *err, size_t errlen);

/* "file:line: <bsdf type='T'>: reason" for any other refusal; returns -1. */
int bsdf_refuse(const scene_obj *o, char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#endif
