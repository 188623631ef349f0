/* Microfacet normal distributions (Beckmann, GGX/Trowbridge-Reitz), possibly
 * anisotropic, with the separable Smith shadowing-masking term and sampling
 * of either D(m) cos(theta_m) or the distribution of normals visible from wi
 * (Heitz & d'Eon 2014; Heitz 2018 for GGX). Local frame, z = macro normal. */
#ifndef CELADON_MICROFACET_H
#define CELADON_MICROFACET_H

#include "celadon/vecmath.h"

typedef enum { MICROFACET_BECKMANN, MICROFACET_GGX } microfacet_type;

typedef struct {
    microfacet_type type;
    double alpha_u, alpha_v; /* roughness along x and y (>= 1e-4) */
    int sample_visible;
} microfacet;

/* Builds a distribution; alphas are clamped to >= 1e-4 as Mitsuba does. */
microfacet microfacet_make(microfacet_type type, double alpha_u, double alpha_v, int sample_visible);
/* Parses "beckmann" / "ggx"; returns -1 for anything else. */
int microfacet_type_parse(const char *name, microfacet_type *out);

/* Normal distribution D(m), per unit solid angle of m, zero below the horizon. */
double microfacet_D(const microfacet *d, vec3 m);
/* Smith's Lambda and G1(v, m) = chi(v.m / v.z) / (1 + Lambda(v)). */
double microfacet_lambda(const microfacet *d, vec3 v);
double microfacet_G1(const microfacet *d, vec3 v, vec3 m);
/* Separable shadowing-masking G1(wi) G1(wo). */
double microfacet_G(const microfacet *d, vec3 wi, vec3 wo, vec3 m);
/* Samples a normal m for an incident wi in the upper hemisphere; *pdf is its
 * density (microfacet_pdf). With sample_visible: D_wi(m) = G1(wi,m) max(0, wi.m) D(m) / wi.z;
 * otherwise D(m) m.z. */
vec3 microfacet_sample(const microfacet *d, vec3 wi, vec2 u, double *pdf);
double microfacet_pdf(const microfacet *d, vec3 wi, vec3 m);

/* Reflection off the microfacets, both directions above the surface
 * (wi.z, wo.z > 0; callers check): D(m) G(wi, wo, m) at the half vector
 * m = (wi + wo) / |wi + wo| (stored in *m), and the density of wo when m is
 * drawn by microfacet_sample and wi reflected about it,
 * microfacet_pdf(wi, m) / (4 wo.m) (0 when wo.m <= 0). */
double microfacet_reflection_dg(const microfacet *d, vec3 wi, vec3 wo, vec3 *m);
double microfacet_reflection_pdf(const microfacet *d, vec3 wi, vec3 wo);

#endif
