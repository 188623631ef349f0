/* Fresnel reflectance for dielectric and conducting interfaces, and the
 * mirror/refraction directions in the local shading frame (z = normal). */
#ifndef CELADON_FRESNEL_H
#define CELADON_FRESNEL_H

#include "celadon/color.h"
#include "celadon/vecmath.h"

/* Unpolarised reflectance of a smooth dielectric interface with relative IOR
 * eta = n_inside / n_outside, for incidence cosine cos_i (> 0: arriving from the
 * outside, < 0: from the inside). Outputs (any may be NULL): *cos_t, the cosine
 * of the refracted direction, signed opposite to cos_i (0 under total internal
 * reflection); *eta_it = n_t / n_i for this crossing and *eta_ti = 1 / *eta_it. */
double fresnel_dielectric(double cos_i, double eta, double *cos_t, double *eta_it, double *eta_ti);

/* Unpolarised reflectance of a conductor with complex relative IOR eta + i k,
 * light arriving from the outside at |cos_i|. k = 0 reduces to the dielectric. */
double fresnel_conductor(double cos_i, double eta, double k);
rgb fresnel_conductor_rgb(double cos_i, rgb eta, rgb k);

/* Hemispherical average 2 * integral_0^1 F(mu) mu dmu of fresnel_dielectric for
 * light arriving from the outside of an interface of relative IOR eta
 * (eta < 1 includes total internal reflection). Numerical quadrature. */
double fresnel_diffuse_reflectance(double eta);

/* Mirror direction of w about +z, and about a unit microfacet normal m. */
static inline vec3 reflect_local(vec3 w) { return v3(-w.x, -w.y, w.z); }
static inline vec3 reflect_about(vec3 w, vec3 m) { return v3_sub(v3_scale(m, 2.0 * v3_dot(w, m)), w); }
/* Refracted direction of w through a facet with normal m, given the signed
 * cos_t and eta_ti from fresnel_dielectric(dot(w, m), ...). */
static inline vec3 refract_about(vec3 w, vec3 m, double cos_t, double eta_ti)
{
    return v3_sub(v3_scale(m, v3_dot(w, m) * eta_ti + cos_t), v3_scale(w, eta_ti));
}

#endif
