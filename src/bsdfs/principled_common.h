/* What Mitsuba's Disney BSDFs `principled` and `principledthin` share
 * (Burley 2012, "Physically Based Shading at Disney"; Burley 2015,
 * "Extending the Disney BRDF to a BSDF with Integrated Subsurface
 * Scattering"): the Schlick Fresnel terms, the GGX alphas of roughness and
 * anisotropy, the check that a microfacet is seen from the right sides, and
 * the diffuse lobes (diffuse, retro-reflection, fake subsurface, sheen). */
#ifndef CELADON_PRINCIPLED_COMMON_H
#define CELADON_PRINCIPLED_COMMON_H

#include <stdbool.h>

#include "bsdfs/bsdf_impl.h"

/* The parameters both Disney BSDFs take (Mitsuba's names), for their
 * plugins' tables. */
#define PRINCIPLED_PARAMS_COMMON                                        \
    {"base_color", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},               \
        {"roughness", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},            \
        {"anisotropic", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},          \
        {"spec_trans", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},           \
        {"spec_tint", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},            \
        {"sheen", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},                \
        {"sheen_tint", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},           \
        {"flatness", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},             \
        {"diffuse_reflectance_sampling_rate", PARAM_FLOAT, 0, NULL}

/* A parameter of a Disney BSDF and whether its lobe is on: given, and not
 * the float 0 (Mitsuba's get_flag). */
typedef struct {
    bsdf_scalar v;
    bool on;
} principled_param;

int principled_param_read(bsdf_set *set, scene_obj *o, const char *name, double def, principled_param *out,
                          char *err, size_t errlen);
static inline double principled_eval(const principled_param *p, vec2 uv)
{
    return p->on ? scalar_eval(&p->v, uv) : 0.0;
}

/* (1 - cos)^5, cos clamped to [0, 1]. */
double schlick_weight(double cos_i);
/* Schlick's F = lerp(schlick_weight, 1, R0) for light arriving at cos_i on
 * an interface of relative IOR eta (the transmitted cosine's weight when
 * light comes from the denser side). Per channel for a color R0. */
double principled_schlick(double r0, double cos_i, double eta);
rgb principled_schlick_rgb(rgb r0, double cos_i, double eta);
/* ((eta - 1) / (eta + 1))^2. */
double schlick_r0_eta(double eta);
/* Whether the microfacet m is seen from the proper sides by wi and wo
 * (reflection: both above it; transmission: wo below), for a wi on the side
 * sign(cos_i) of the surface. */
bool principled_compatible(vec3 m, vec3 wi, vec3 wo, double cos_i, bool reflection);
/* The GGX alphas of roughness and anisotropic (at least 0.001 each). */
microfacet principled_ggx(double roughness, double anisotropic, bool has_anisotropic);
/* The tint of base_color: base_color / its luminance (1 when black). */
rgb principled_tint(rgb base_color);
/* The diffuse lobes with the cosine, for wi, wo on the front (cos_i,
 * cos_o > 0) and the half vector's cos_d = wh.wo: Burley's diffuse and
 * retro-reflection, lerped toward the fake subsurface by flatness (when on),
 * times base_color / pi. */
rgb principled_diffuse(rgb base_color, double roughness, double flatness, bool has_flatness, double cos_i,
                       double cos_o, double cos_d);
/* The sheen lobe with the cosine: sheen (1 - schlick_weight...) tinted by
 * sheen_tint toward base_color. */
rgb principled_sheen(rgb base_color, double sheen, double sheen_tint, double cos_o, double cos_d);

#endif
