/* Mitsuba's `principledthin` BSDF: the Disney BSDF of a thin sheet (Burley
 * 2015), the same seen from either side: the diffuse lobes of principled
 * (weighted by 1 - spec_trans and 1 - diff_trans / 2), a Lambertian
 * transmission (diff_trans / 2, diff_trans in [0, 2]), and, by
 * `spec_trans`, a GGX reflection with a Fresnel term tinted by spec_tint
 * and a GGX "transmission" that reflects about the microfacet and goes on
 * through the sheet, undeviated on average, with the roughness scaled by
 * 0.65 eta - 0.35 (Burley 2015, figure 15). No eta crossing: the sheet
 * has the same medium on both sides. */
#include "bsdfs/fresnel.h"
#include "bsdfs/principled_common.h"
#include "celadon/sampling.h"

typedef struct {
    bsdf_spectrum base_color;
    bsdf_scalar roughness, eta;
    principled_param anisotropic, spec_trans, spec_tint, sheen, sheen_tint, flatness, diff_trans;
    double rate[4]; /* sampling rates: specular reflection, specular transmission, diffuse reflection, transmission */
} thin_data;

/* The values at uv, with wi and wo turned to the front (the sheet is the
 * same from both sides). */
typedef struct {
    double roughness, anisotropic, spec_trans, diff_trans, eta;
    vec3 wi;
} thin_at;

static thin_at thin_values(const thin_data *d, const bsdf_query *q)
{
    thin_at v;
    v.roughness = scalar_eval(&d->roughness, q->uv);
    v.anisotropic = principled_eval(&d->anisotropic, q->uv);
    v.spec_trans = principled_eval(&d->spec_trans, q->uv);
    v.diff_trans = 0.5 * principled_eval(&d->diff_trans, q->uv); /* [0, 2] made [0, 1] */
    v.eta = scalar_eval(&d->eta, q->uv);
    v.wi = q->wi.z < 0.0 ? v3_neg(q->wi) : q->wi;
    return v;
}

/* The lobes' selection probabilities: specular reflection and
 * transmission, diffuse reflection and transmission. */
static void lobe_probabilities(const thin_data *d, const thin_at *v, double p[4])
{
    p[0] = d->spec_trans.on ? v->spec_trans * d->rate[0] / 2.0 : 0.0;
    p[1] = d->spec_trans.on ? v->spec_trans * d->rate[1] / 2.0 : 0.0;
    p[2] = d->rate[2] * (1.0 - v->spec_trans) * (1.0 - v->diff_trans);
    p[3] = d->diff_trans.on ? d->rate[3] * (1.0 - v->spec_trans) * v->diff_trans : 0.0;
    double total = p[0] + p[1] + p[2] + p[3];
    for (int i = 0; i < 4; i++)
        p[i] /= total;
}

static microfacet thin_transmission_ggx(const thin_data *d, const thin_at *v)
{
    return principled_ggx((0.65 * v->eta - 0.35) * v->roughness, v->anisotropic, d->anisotropic.on);
}

static rgb thin_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo_in)
{
    const thin_data *d = b->data;
    if (q->wi.z == 0.0)
        return rgb_gray(0.0);
    thin_at v = thin_values(d, q);
    rgb base = spectrum_eval(&d->base_color, q->uv);
    vec3 wi = v.wi, wo = q->wi.z < 0.0 ? v3_neg(wo_in) : wo_in;
    double cos_i = wi.z, cos_o = wo.z;
    bool reflect = cos_o > 0.0, refract = cos_o < 0.0;
    vec3 wo_r = v3(wo.x, wo.y, fabs(wo.z));
    vec3 wh = v3_norm(v3_add(wi, wo_r));
    rgb value = rgb_gray(0.0);
    if (d->spec_trans.on && v.spec_trans > 0.0) {
        double f_diel = fresnel_dielectric(v3_dot(wi, wh), v.eta, NULL, NULL, NULL);
        if (reflect && principled_compatible(wh, wi, wo, wi.z, true)) {
            microfacet distr = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
            double spec_tint = principled_eval(&d->spec_tint, q->uv);
            rgb f = rgb_gray(f_diel);
            if (d->spec_tint.on) {
                rgb r0 = rgb_scale(principled_tint(base), schlick_r0_eta(v.eta));
                f = rgb_lerp(rgb_gray(f_diel), principled_schlick_rgb(r0, v3_dot(wi, wh), v.eta), spec_tint);
            }
            double dg = microfacet_D(&distr, wh) * microfacet_G(&distr, wi, wo, wh);
            value = rgb_add(value, rgb_scale(f, v.spec_trans * dg / (4.0 * cos_i)));
        }
        if (refract && principled_compatible(wh, wi, wo, wi.z, false)) {
            microfacet distr = thin_transmission_ggx(d, &v);
            double dg = microfacet_D(&distr, wh) * microfacet_G(&distr, wi, wo, wh);
            value = rgb_add(value, rgb_scale(base, v.spec_trans * (1.0 - f_diel) * dg / (4.0 * cos_i)));
        }
    }
    if (reflect && v.spec_trans < 1.0 && v.diff_trans < 1.0) {
        double cos_d = v3_dot(wh, wo), w = (1.0 - v.spec_trans) * (1.0 - v.diff_trans);
        rgb diffuse = principled_diffuse(base, v.roughness, principled_eval(&d->flatness, q->uv), d->flatness.on,
                                         cos_i, cos_o, cos_d);
        value = rgb_add(value, rgb_scale(diffuse, w));
        double sheen = principled_eval(&d->sheen, q->uv);
        if (d->sheen.on && sheen > 0.0) {
            rgb s = principled_sheen(base, sheen, principled_eval(&d->sheen_tint, q->uv), cos_o, cos_d);
            value = rgb_add(value, rgb_scale(s, w));
        }
    }
    if (d->diff_trans.on && refract && v.spec_trans < 1.0 && v.diff_trans > 0.0)
        value = rgb_add(value, rgb_scale(base, (1.0 - v.spec_trans) * v.diff_trans * fabs(cos_o) / M_PI));
    return value;
}

static double thin_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo_in)
{
    const thin_data *d = b->data;
    if (q->wi.z == 0.0)
        return 0.0;
    thin_at v = thin_values(d, q);
    vec3 wi = v.wi, wo = q->wi.z < 0.0 ? v3_neg(wo_in) : wo_in;
    bool reflect = wo.z > 0.0, refract = wo.z < 0.0;
    double p[4];
    lobe_probabilities(d, &v, p);
    double pdf = 0.0;
    if (d->spec_trans.on) {
        vec3 wo_r = v3(wo.x, wo.y, fabs(wo.z));
        vec3 wh = v3_norm(v3_add(wi, wo_r));
        double jacobian = fabs(1.0 / (4.0 * v3_dot(wo_r, wh)));
        microfacet reflection = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
        microfacet transmission = thin_transmission_ggx(d, &v);
        if (reflect && principled_compatible(wh, wi, wo, wi.z, true))
            pdf += p[0] * microfacet_pdf(&reflection, wi, wh) * jacobian;
        if (refract && principled_compatible(wh, wi, wo, wi.z, false))
            pdf += p[1] * microfacet_pdf(&transmission, wi, wh) * jacobian;
    }
    if (reflect)
        pdf += p[2] * warp_cosine_hemisphere_pdf(wo);
    if (d->diff_trans.on && refract)
        pdf += p[3] * warp_cosine_hemisphere_pdf(v3_neg(wo));
    return pdf;
}

static int thin_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const thin_data *d = b->data;
    if (q->wi.z == 0.0)
        return 0;
    thin_at v = thin_values(d, q);
    vec3 wi = v.wi, wo;
    double p[4];
    lobe_probabilities(d, &v, p);
    out->eta = 1.0;
    if (u1 < p[0]) {
        microfacet distr = principled_ggx(v.roughness, v.anisotropic, d->anisotropic.on);
        vec3 m = microfacet_sample(&distr, wi, u2, NULL);
        wo = reflect_about(wi, m);
        out->sampled_type = BSDF_GLOSSY_REFLECTION;
        if (wo.z <= 0.0 || !principled_compatible(m, wi, wo, wi.z, true))
            return 0;
    } else if (u1 < p[0] + p[1]) {
        microfacet distr = thin_transmission_ggx(d, &v);
        vec3 m = microfacet_sample(&distr, wi, u2, NULL);
        wo = reflect_about(wi, m);
        wo.z = -wo.z; /* through the sheet */
        out->sampled_type = BSDF_GLOSSY_TRANSMISSION;
        if (wo.z >= 0.0 || !principled_compatible(m, wi, wo, wi.z, false))
            return 0;
    } else if (u1 < p[0] + p[1] + p[2]) {
        wo = warp_square_to_cosine_hemisphere(u2);
        out->sampled_type = BSDF_DIFFUSE_REFLECTION;
    } else {
        wo = v3_neg(warp_square_to_cosine_hemisphere(u2));
        out->sampled_type = BSDF_DIFFUSE_TRANSMISSION;
    }
    out->wo = q->wi.z < 0.0 ? v3_neg(wo) : wo;
    return bsdf_finish_sample(b, q, out);
}

static rgb thin_albedo(const bsdf_t *b, vec2 uv)
{
    const thin_data *d = b->data;
    return spectrum_eval(&d->base_color, uv);
}

static const bsdf_ops thin_ops = {"principledthin", thin_sample, thin_eval, thin_pdf, thin_albedo, NULL, NULL};

static bsdf_t *thin_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    thin_data d;
    static const char *const lobes[] = {"anisotropic", "spec_trans", "spec_tint", "sheen",
                                        "sheen_tint",  "flatness",   "diff_trans"};
    principled_param *params[] = {&d.anisotropic, &d.spec_trans, &d.spec_tint, &d.sheen,
                                  &d.sheen_tint,  &d.flatness,   &d.diff_trans};
    static const char *const rates[] = {"specular_reflectance_sampling_rate", "specular_transmittance_sampling_rate",
                                        "diffuse_reflectance_sampling_rate", "diffuse_transmittance_sampling_rate"};
    if (bsdf_spectrum_param(set, o, "base_color", 0.5, &d.base_color, err, errlen) != 0 ||
        bsdf_scalar_param(set, o, "roughness", 0.5, &d.roughness, err, errlen) != 0 ||
        bsdf_scalar_param(set, o, "eta", 1.5, &d.eta, err, errlen) != 0 ||
        bsdf_check_spectrum(o, "base_color", &d.base_color, err, errlen) != 0)
        return NULL;
    for (int i = 0; i < 7; i++)
        if (principled_param_read(set, o, lobes[i], 0.0, params[i], err, errlen) != 0)
            return NULL;
    for (int i = 0; i < 4; i++) {
        d.rate[i] = scene_obj_float(o, rates[i], 1.0);
        if (!(d.rate[i] >= 0.0)) {
            bsdf_refuse(o, err, errlen, "%s must be non-negative", rates[i]);
            return NULL;
        }
    }
    if (!d.eta.texture && !(d.eta.value > 0.0)) {
        bsdf_refuse(o, err, errlen, "eta must be positive, got %g", d.eta.value);
        return NULL;
    }
    unsigned flags = BSDF_DIFFUSE_REFLECTION | BSDF_DIFFUSE_TRANSMISSION | BSDF_GLOSSY_REFLECTION |
                     (d.spec_trans.on ? BSDF_GLOSSY_TRANSMISSION : 0u) | BSDF_FRONT_SIDE | BSDF_BACK_SIDE |
                     (d.anisotropic.on ? BSDF_ANISOTROPIC : 0u);
    return bsdf_alloc(o, &thin_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl thin_params[] = {
    PRINCIPLED_PARAMS_COMMON,
    {"eta", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},
    {"diff_trans", PARAM_FLOAT | PARAM_TEXTURE, 0, NULL},
    {"specular_reflectance_sampling_rate", PARAM_FLOAT, 0, NULL},
    {"specular_transmittance_sampling_rate", PARAM_FLOAT, 0, NULL},
    {"diffuse_transmittance_sampling_rate", PARAM_FLOAT, 0, NULL},
    BSDF_PARAMS_END,
};

const bsdf_plugin bsdf_principledthin = {
    .decl = {.cls = SCENE_BSDF, .type = "principledthin", .params = thin_params},
    .create = thin_create,
};
