/* Microfacet distributions; formulas from Walter et al. 2007 ("Microfacet
 * models for refraction through rough surfaces"), Heitz 2014 ("Understanding the
 * masking-shadowing function"), Heitz & d'Eon 2014 (visible normals) and Heitz
 * 2018 (GGX visible normals by hemisphere projection). */
#include "bsdfs/microfacet.h"

#include <gsl/gsl_cdf.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

microfacet microfacet_make(microfacet_type type, double alpha_u, double alpha_v, int sample_visible)
{
    microfacet d = {type, fmax(alpha_u, 1e-4), fmax(alpha_v, 1e-4), sample_visible};
    return d;
}

int microfacet_type_parse(const char *name, microfacet_type *out)
{
    if (strcmp(name, "beckmann") == 0)
        *out = MICROFACET_BECKMANN;
    else if (strcmp(name, "ggx") == 0)
        *out = MICROFACET_GGX;
    else
        return -1;
    return 0;
}

double microfacet_D(const microfacet *d, vec3 m)
{
    if (m.z <= 0.0)
        return 0.0;
    double ax = d->alpha_u, ay = d->alpha_v;
    double z2 = m.z * m.z;
    double e = (m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay)) / z2; /* tan^2 in stretched space */
    double r;
    if (d->type == MICROFACET_BECKMANN)
        r = exp(-e) / (M_PI * ax * ay * z2 * z2);
    else
        r = 1.0 / (M_PI * ax * ay * z2 * z2 * (1.0 + e) * (1.0 + e));
    return r > 1e-300 ? r : 0.0;
}

double microfacet_lambda(const microfacet *d, vec3 v)
{
    double xy2 = d->alpha_u * d->alpha_u * v.x * v.x + d->alpha_v * d->alpha_v * v.y * v.y;
    if (xy2 <= 0.0)
        return 0.0;
    double a = fabs(v.z) / sqrt(xy2); /* 1 / (alpha tan(theta)) along v's azimuth */
    if (d->type == MICROFACET_BECKMANN)
        return 0.5 * (exp(-a * a) / (a * sqrt(M_PI)) - erfc(a));
    return 0.5 * (-1.0 + sqrt(1.0 + 1.0 / (a * a)));
}

double microfacet_G1(const microfacet *d, vec3 v, vec3 m)
{
    if (v3_dot(v, m) * v.z <= 0.0)
        return 0.0;
    return 1.0 / (1.0 + microfacet_lambda(d, v));
}

double microfacet_G(const microfacet *d, vec3 wi, vec3 wo, vec3 m)
{
    return microfacet_G1(d, wi, m) * microfacet_G1(d, wo, m);
}

/* Slope of a visible normal for the isotropic unit-roughness Beckmann surface
 * seen from an incident direction in the xz-plane with cosine cos_i > 0.
 * The y-slope is Gaussian; the x-slope has density proportional to
 * (cot(theta) - x) exp(-x^2) for x < cot(theta), whose CDF
 *   F(x) = [c sqrt(pi) (1 + erf x) + exp(-x^2)] / [c sqrt(pi) (1 + erf c) + exp(-c^2)],  c = cot(theta),
 * is inverted with a safeguarded Newton iteration. */
static vec2 beckmann_visible_slope_11(double cos_i, vec2 u)
{
    /* erf(y) = 2 u - 1  <=>  Phi(y sqrt 2) = u. */
    double uy = fmin(fmax(u.y, 1e-16), 1.0 - 1e-16);
    double y = gsl_cdf_ugaussian_Pinv(uy) / sqrt(2.0);
    double sin_i = sqrt(fmax(0.0, 1.0 - cos_i * cos_i));
    if (sin_i < 1e-9) {
        /* Normal incidence: visible slopes are the plain Gaussian slopes. */
        double r = sqrt(-log(1.0 - u.x)), phi = 2.0 * M_PI * u.y;
        return v2(r * cos(phi), r * sin(phi));
    }
    double c = cos_i / sin_i;
    double sp = sqrt(M_PI);
    double norm = c * sp * erfc(-c) + exp(-c * c);
    double target = u.x * norm;
    double lo = -7.0, hi = c, x = fmin(c, 0.0) - 0.5;
    if (x <= lo)
        x = 0.5 * (lo + hi);
    for (int it = 0; it < 200; it++) {
        double f = c * sp * erfc(-x) + exp(-x * x) - target;
        if (fabs(f) < 1e-13 * norm)
            break;
        if (f > 0.0)
            hi = x;
        else
            lo = x;
        double df = 2.0 * exp(-x * x) * (c - x);
        double step = df > 0.0 ? x - f / df : lo - 1.0;
        x = (step > lo && step < hi) ? step : 0.5 * (lo + hi);
        if (hi - lo < 1e-13)
            break;
    }
    return v2(x, y);
}

static vec3 sample_visible(const microfacet *d, vec3 wi, vec2 u)
{
    double ax = d->alpha_u, ay = d->alpha_v;
    vec3 v = v3_norm(v3(ax * wi.x, ay * wi.y, wi.z)); /* stretch to unit roughness */
    if (d->type == MICROFACET_GGX) {
        /* Heitz 2018: sample the projected hemisphere seen from v. */
        double len2 = v.x * v.x + v.y * v.y;
        vec3 t1 = len2 > 0.0 ? v3_scale(v3(-v.y, v.x, 0.0), 1.0 / sqrt(len2)) : v3(1.0, 0.0, 0.0);
        vec3 t2 = v3_cross(v, t1);
        double r = sqrt(u.x), phi = 2.0 * M_PI * u.y;
        double p1 = r * cos(phi), p2 = r * sin(phi);
        double s = 0.5 * (1.0 + v.z);
        p2 = (1.0 - s) * sqrt(fmax(0.0, 1.0 - p1 * p1)) + s * p2;
        double pz = sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2));
        vec3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(v, pz));
        return v3_norm(v3(ax * nh.x, ay * nh.y, fmax(1e-12, nh.z)));
    }
    /* Beckmann: sample slopes in the stretched frame, rotate to v's azimuth, unstretch. */
    vec2 s = beckmann_visible_slope_11(v.z, u);
    double sin_v = sqrt(fmax(0.0, 1.0 - v.z * v.z));
    double cph = sin_v > 0.0 ? v.x / sin_v : 1.0, sph = sin_v > 0.0 ? v.y / sin_v : 0.0;
    double sx = cph * s.x - sph * s.y, sy = sph * s.x + cph * s.y;
    return v3_norm(v3(-sx * ax, -sy * ay, 1.0));
}

vec3 microfacet_sample(const microfacet *d, vec3 wi, vec2 u, double *pdf)
{
    vec3 m;
    if (d->sample_visible) {
        m = sample_visible(d, wi, u);
    } else {
        /* D(m) cos(theta_m) is the slope density P22 mapped to normals: Gaussian
         * slopes (Beckmann) or r^2 = u / (1 - u) radially (GGX), stretched by alpha. */
        double phi = 2.0 * M_PI * u.y;
        double r = d->type == MICROFACET_BECKMANN ? sqrt(-log(1.0 - u.x)) : sqrt(u.x / (1.0 - u.x));
        double sx = r * cos(phi) * d->alpha_u, sy = r * sin(phi) * d->alpha_v;
        m = v3_norm(v3(-sx, -sy, 1.0));
    }
    if (pdf)
        *pdf = microfacet_pdf(d, wi, m);
    return m;
}

double microfacet_pdf(const microfacet *d, vec3 wi, vec3 m)
{
    if (!d->sample_visible)
        return microfacet_D(d, m) * m.z;
    if (wi.z <= 0.0)
        return 0.0;
    return microfacet_G1(d, wi, m) * fmax(0.0, v3_dot(wi, m)) * microfacet_D(d, m) / wi.z;
}

double microfacet_reflection_dg(const microfacet *d, vec3 wi, vec3 wo, vec3 *m)
{
    *m = v3_norm(v3_add(wi, wo));
    return microfacet_D(d, *m) * microfacet_G(d, wi, wo, *m);
}

double microfacet_reflection_pdf(const microfacet *d, vec3 wi, vec3 wo)
{
    vec3 m = v3_norm(v3_add(wi, wo));
    double wo_m = v3_dot(wo, m);
    return wo_m > 0.0 ? microfacet_pdf(d, wi, m) / (4.0 * wo_m) : 0.0;
}
