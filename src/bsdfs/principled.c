/* Mitsuba's `principled` BSDF, the Disney BSDF (Burley 2012, 2015) as
 * Mitsuba 3 defines it: a diffuse lobe (Burley's diffuse with
 * retro-reflection, the fake subsurface by `flatness`, `sheen`), a main
 * GGX specular lobe reflecting with a Fresnel term that blends the
 * dielectric one, a `spec_tint` Schlick term and a `metallic` Schlick term
 * on base_color, a GGX transmission lobe weighted by `spec_trans`, and a
 * GTR1 `clearcoat` lobe. Lobes are sampled in proportion to their weights
 * and the sampling rates; the specular pair splits by the Fresnel
 * term of the sampled microfacet. No subsurface scattering, as in Mitsuba. */
#include "bsdfs/fresnel.h"
#include "bsdfs/principled_common.h"
#include "celadon/sampling.h"

typedef struct {
    bsdf_spectrum base_color;
    bsdf_scalar roughness, clearcoat_gloss;
    principled_param anisotropic, metallic, spec_trans, spec_tint, sheen, sheen_tint, flatness, clearcoat;
    double eta;
    double diffuse_rate, specular_rate, clearcoat_rate;
} principled_data;

/* GTR1, the clearcoat's distribution: D(m) = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) cos^2)). */
static double gtr1_d(double alpha, vec3 m)
{
    double a2 = alpha * alpha, c2 = m.z * m.z;
    double r = (a2 - 1.0) / (M_PI * log(a2) * (1.0 + (a2 - 1.0) * c2));
    return r * m.z > 1e-20 ? r : 0.0;
}

static double gtr1_pdf(double alpha, vec3 m)
{
    return m.z < 0.0 ? 0.0 : m.z * gtr1_d(alpha, m);
}

static vec3 gtr1_sample(double alpha, vec2 u)
{
    double a2 = alpha * alpha, phi = 2.0 * M_PI * u.x;
    double c2 = (1.0 - pow(a2, 1.0 - u.y)) / (1.0 - a2);
    double s = sqrt(fmax(0.0, 1.0 - c2)), c = sqrt(fmax(0.0, c2));
    return v3(cos(phi) * s, sin(phi) * s, c);
}

/* Separable Smith GGX with a fixed alpha (the clearcoat's, 0.25). */
static double smith_ggx1(vec3 v, vec3 wh, double alpha)
{
    if (v3_dot(v, wh) * v.z <= 0.0)
        return 0.0;
    if (v.z == 1.0)
        return 1.0;
    double c2 = v.z * v.z, t2 = (1.0 - c2) / c2;
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * t2));
}

/* The clearcoat's alpha: gloss 0 gives 0.1, 1 gives 0.001. */
static double clearcoat_alpha(const principled_data *d, vec2 uv)
{
    double g = scalar_eval(&d->clearcoat_gloss, uv);
    return 0.1 + (0.001 - 0.1) * g;
}

/* The values at uv that every query needs. */
typedef struct {
    double roughness, anisotropic, metallic, spec_trans, clearcoat;
    double brdf, bsdf; /* the weights of the reflective and transmissive major lobes */
} principled_at;

static principled_at principled_values(const principled_data *d, vec2 uv)
{
    principled_at v;
    v.roughness = scalar_eval(&d->roughness, uv);
    v.anisotropic = principled_eval(&d->anisotropic, uv);
    v.metallic = principled_eval(&d->metallic, uv);
    v.spec_trans = principled_eval(&d->spec_trans, uv);
    v.clearcoat = principled_eval(&d->clearcoat, uv);
    v.brdf = (1.0 - v.metallic) * (1.0 - v.spec_trans);
    v.bsdf = (1.0 - v.metallic) * v.spec_trans;
    return v;
}

/* The lobes' selection probabilities: diffuse, clearcoat, transmission,
 * reflection, for the dielectric Fresnel term f of the specular pair. */
static void lobe_probabilities(const principled_data *d, const principled_at *v, double f, bool front, double p[4])
{
    p[3] = front ? d->specular_rate * (1.0 - v->bsdf * (1.0 - f)) : f;
    p[2] = d->spec_trans.on ? (front ? d->specular_rate * v->bsdf * (1.0 - f) : 1.0 - f) : 0.0;
    p[1] = d->clearcoat.on && front ? 0.25 * v->clearcoat * d->clearcoat_rate : 0.0;
    p[0] = front ? v->brdf * d->diffuse_rate : 0.0;
    double total = p[0] + p[1] + p[2] + p[3];
    for (int i = 0; i < 4; i++)
        p[i] /= total;
}

/* Mitsuba's principled Fresnel: on the front, the dielectric term where
 * neither metallic nor spec_tint, a Schlick term of base_color by metallic
 * and of the tinted R0 by spec_tint; on the back the dielectric term only. */
static rgb principled_fresnel(const principled_data *d, const principled_at *v, rgb base, double f_dielectric,
                              double spec_tint, double cos_i, bool front)
{
    if (!front)
        return rgb_gray(v->bsdf * f_dielectric);
    rgb f = rgb_gray((1.0 - v->metallic) * (1.0 - spec_tint) * f_dielectric);
    if (d->metallic.on)
        f = rgb_add(f, rgb_scale(principled_schlick_rgb(base, cos_i, d->eta), v->metallic));
    if (d->spec_tint.on) {
        double eta_it = cos_i >= 0.0 ? d->eta : 1.0 / d->eta;
        rgb r0 = rgb_scale(principled_tint(base), schlick_r0_eta(eta_it));
        f = rgb_add(f, rgb_scale(principled_schlick_rgb(r0, cos_i, d->eta), (1.0 - v->metallic) * spec_tint));
    }
    return f;
}

/* The half vector of (wi, wo), pointing out of the surface. */
static vec3 half_vector(vec3 wi, vec3 wo, bool reflect, double eta_path)
{
    vec3 wh = v3_norm(v3_add(wi, v3_scale(wo, reflect ? 1.0 : eta_path)));
    return wh.z < 0.0 ? v3_neg(wh) : wh;
}

static rgb principled_eval_bsdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const principled_data *d = b->data;
    vec3 wi = q->wi;
    double cos_i = wi.z, cos_o = wo.z;
    if (cos_i == 0.0)
        return rgb_gray(0.0);
    principled_at v = principled_values(d, q->uv);
    rgb base = spectrum_eval(&d->base_color, q->uv);
    bool reflect = cos_i * cos_o > 0.0, refract = cos_i * cos_o < 0.0, front = cos_i > 0.0;
    double eta_path = front ? d->eta : 1.0 / d->eta, inv_eta_path = 1.0 / eta_path;
    microfacet distr = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
    vec3 wh = half_vector(wi, wo, reflect, eta_path);
    double f_diel = fresnel_dielectric(v3_dot(wi, wh), d->eta, NULL, NULL, NULL);
    bool refl_ok = principled_compatible(wh, wi, wo, cos_i, true);
    bool refr_ok = principled_compatible(wh, wi, wo, cos_i, false);
    double dd = microfacet_D(&distr, wh), g = microfacet_G(&distr, wi, wo, wh);
    rgb value = rgb_gray(0.0);
    if (reflect && refl_ok && f_diel > 0.0) {
        double spec_tint = principled_eval(&d->spec_tint, q->uv);
        rgb f = principled_fresnel(d, &v, base, f_diel, spec_tint, v3_dot(wi, wh), front);
        value = rgb_add(value, rgb_scale(f, dd * g / (4.0 * fabs(cos_i))));
    }
    if (d->spec_trans.on && v.bsdf > 0.0 && refract && refr_ok && f_diel < 1.0) {
        double scale = q->mode == TRANSPORT_RADIANCE ? inv_eta_path * inv_eta_path : 1.0;
        double wi_h = v3_dot(wi, wh), wo_h = v3_dot(wo, wh), denom = wi_h + eta_path * wo_h;
        double t = fabs(scale * (1.0 - f_diel) * dd * g * eta_path * eta_path * wi_h * wo_h / (cos_i * denom * denom));
        rgb root = rgb_make(sqrt(base.r), sqrt(base.g), sqrt(base.b));
        value = rgb_add(value, rgb_scale(root, v.bsdf * t));
    }
    if (d->clearcoat.on && v.clearcoat > 0.0 && reflect && refl_ok && front) {
        double fcc = principled_schlick(0.04, v3_dot(wi, wh), d->eta);
        double gcc = smith_ggx1(wi, wh, 0.25) * smith_ggx1(wo, wh, 0.25);
        double dcc = gtr1_d(clearcoat_alpha(d, q->uv), wh);
        value = rgb_add(value, rgb_gray(0.25 * v.clearcoat * fcc * dcc * gcc * fabs(cos_o)));
    }
    if (v.brdf > 0.0 && reflect && front) {
        double cos_d = v3_dot(wh, wo);
        rgb diffuse = principled_diffuse(base, v.roughness, principled_eval(&d->flatness, q->uv), d->flatness.on,
                                         fabs(cos_i), fabs(cos_o), cos_d);
        value = rgb_add(value, rgb_scale(diffuse, v.brdf));
        double sheen = principled_eval(&d->sheen, q->uv);
        if (d->sheen.on && sheen > 0.0 && 1.0 - v.metallic > 0.0) {
            rgb s = principled_sheen(base, sheen, principled_eval(&d->sheen_tint, q->uv), fabs(cos_o), cos_d);
            value = rgb_add(value, rgb_scale(s, 1.0 - v.metallic));
        }
    }
    return value;
}

static double principled_pdf_bsdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const principled_data *d = b->data;
    vec3 wi = q->wi;
    double cos_i = wi.z, cos_o = wo.z;
    if (cos_i == 0.0)
        return 0.0;
    principled_at v = principled_values(d, q->uv);
    bool front = cos_i > 0.0, reflect = cos_i * cos_o > 0.0, refract = cos_i * cos_o < 0.0;
    if (!front && !(v.bsdf > 0.0))
        return 0.0; /* what sampling never gives (Mitsuba claims a density here) */
    double eta_path = front ? d->eta : 1.0 / d->eta;
    vec3 wh = half_vector(wi, wo, reflect, eta_path);
    microfacet distr = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
    double p[4];
    lobe_probabilities(d, &v, fresnel_dielectric(v3_dot(wi, wh), d->eta, NULL, NULL, NULL), front, p);
    double wi_h = v3_dot(wi, wh), wo_h = v3_dot(wo, wh);
    double jacobian = reflect || !d->spec_trans.on
                          ? fabs(1.0 / (4.0 * wo_h))
                          : fabs(eta_path * eta_path * wo_h / ((wi_h + eta_path * wo_h) * (wi_h + eta_path * wo_h)));
    vec3 wi_up = front ? wi : v3_neg(wi);
    double pdf = 0.0;
    bool refl_ok = principled_compatible(wh, wi, wo, cos_i, true) && reflect;
    if (refl_ok)
        pdf += p[3] * microfacet_pdf(&distr, wi_up, wh) * jacobian;
    if (reflect)
        pdf += p[0] * warp_cosine_hemisphere_pdf(wo);
    if (d->spec_trans.on && principled_compatible(wh, wi, wo, cos_i, false) && refract)
        pdf += p[2] * microfacet_pdf(&distr, wi_up, wh) * jacobian;
    if (d->clearcoat.on && refl_ok)
        pdf += p[1] * gtr1_pdf(clearcoat_alpha(d, q->uv), wh) * jacobian;
    return pdf;
}

static int principled_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const principled_data *d = b->data;
    vec3 wi = q->wi;
    double cos_i = wi.z;
    if (cos_i == 0.0)
        return 0;
    principled_at v = principled_values(d, q->uv);
    bool front = cos_i > 0.0;
    if (!front && !(v.bsdf > 0.0))
        return 0; /* no transmission: nothing from the back */
    microfacet distr = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
    vec3 m = microfacet_sample(&distr, front ? wi : v3_neg(wi), u2, NULL);
    double cos_t, eta_it, eta_ti;
    double f = fresnel_dielectric(v3_dot(wi, m), d->eta, &cos_t, &eta_it, &eta_ti);
    double p[4];
    lobe_probabilities(d, &v, f, front, p);
    out->eta = 1.0;
    if (u1 < p[0]) {
        out->wo = warp_square_to_cosine_hemisphere(u2);
        out->sampled_type = BSDF_DIFFUSE_REFLECTION;
        if (cos_i * out->wo.z <= 0.0)
            return 0;
    } else if (u1 < p[0] + p[1]) {
        vec3 mc = gtr1_sample(clearcoat_alpha(d, q->uv), u2);
        out->wo = reflect_about(wi, mc);
        out->sampled_type = BSDF_GLOSSY_REFLECTION;
        if (!principled_compatible(mc, wi, out->wo, cos_i, true) || cos_i * out->wo.z <= 0.0)
            return 0;
    } else if (u1 < p[0] + p[1] + p[2]) {
        out->wo = v3_norm(refract_about(wi, m, cos_t, eta_ti));
        out->eta = eta_it;
        out->sampled_type = BSDF_GLOSSY_TRANSMISSION;
        if (!principled_compatible(m, wi, out->wo, cos_i, false) || cos_i * out->wo.z >= 0.0)
            return 0;
    } else {
        out->wo = reflect_about(wi, m);
        out->sampled_type = BSDF_GLOSSY_REFLECTION;
        if (!principled_compatible(m, wi, out->wo, cos_i, true) || cos_i * out->wo.z <= 0.0)
            return 0;
    }
    return bsdf_finish_sample(b, q, out);
}

static rgb principled_albedo(const bsdf_t *b, vec2 uv)
{
    const principled_data *d = b->data;
    return spectrum_eval(&d->base_color, uv);
}

static const bsdf_ops principled_ops = {"principled",      principled_sample, principled_eval_bsdf, principled_pdf_bsdf,
                                        principled_albedo, NULL,              NULL};

static bsdf_t *principled_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    principled_data d;
    static const char *const lobes[] = {"anisotropic", "metallic", "spec_trans", "spec_tint",
                                        "sheen",       "sheen_tint", "flatness", "clearcoat"};
    principled_param *params[] = {&d.anisotropic, &d.metallic, &d.spec_trans, &d.spec_tint,
                                  &d.sheen,       &d.sheen_tint, &d.flatness, &d.clearcoat};
    if (bsdf_spectrum_param(set, o, "base_color", 0.5, &d.base_color, err, errlen) != 0 ||
        bsdf_scalar_param(set, o, "roughness", 0.5, &d.roughness, err, errlen) != 0 ||
        bsdf_scalar_param(set, o, "clearcoat_gloss", 0.0, &d.clearcoat_gloss, err, errlen) != 0 ||
        bsdf_check_spectrum(o, "base_color", &d.base_color, err, errlen) != 0)
        return NULL;
    for (int i = 0; i < 8; i++)
        if (principled_param_read(set, o, lobes[i], 0.0, params[i], err, errlen) != 0)
            return NULL;
    d.diffuse_rate = scene_obj_float(o, "diffuse_reflectance_sampling_rate", 1.0);
    d.specular_rate = scene_obj_float(o, "main_specular_sampling_rate", 1.0);
    d.clearcoat_rate = scene_obj_float(o, "clearcoat_sampling_rate", 1.0);
    if (scene_obj_has(o, "eta")) {
        d.eta = scene_obj_float(o, "eta", 1.5);
        if (d.spec_trans.on && d.eta == 1.0)
            d.eta = 1.001; /* Mitsuba's: eta 1 is not plausible for transmission */
    } else {
        double specular = scene_obj_float(o, "specular", 0.5);
        if (d.spec_trans.on && specular == 0.0)
            specular = 1e-3;
        d.eta = 2.0 / (1.0 - sqrt(0.08 * specular)) - 1.0;
    }
    if (!(d.eta > 0.0) || !isfinite(d.eta) || !(d.diffuse_rate >= 0.0) || !(d.specular_rate >= 0.0) ||
        !(d.clearcoat_rate >= 0.0) || d.diffuse_rate + d.specular_rate <= 0.0) {
        bsdf_refuse(o, err, errlen, "eta must be positive (specular in [0, 1]) and the sampling rates non-negative");
        return NULL;
    }
    unsigned flags = BSDF_DIFFUSE_REFLECTION | BSDF_GLOSSY_REFLECTION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE |
                     (d.spec_trans.on ? BSDF_GLOSSY_TRANSMISSION : 0u) | (d.anisotropic.on ? BSDF_ANISOTROPIC : 0u);
    return bsdf_alloc(o, &principled_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl principled_params[] = {
    PRINCIPLED_PARAMS_COMMON,
    {"metallic", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},
    {"eta", PARAM_FLOAT, 0, NULL},
    {"specular", PARAM_FLOAT, 0, NULL},
    {"clearcoat", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},
    {"clearcoat_gloss", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},
    {"main_specular_sampling_rate", PARAM_FLOAT, 0, NULL},
    {"clearcoat_sampling_rate", PARAM_FLOAT, 0, NULL},
    BSDF_PARAMS_END,
};

const bsdf_plugin bsdf_principled = {
    .decl = {.cls = SCENE_BSDF, .type = "principled", .params = principled_params, .exclusive = {"eta", "specular"}},
    .create = principled_create,
};
