/* What the Disney BSDFs share (principled_common.h). */
#include "bsdfs/principled_common.h"

int principled_param_read(bsdf_set *set, scene_obj *o, const char *name, double def, principled_param *out,
                          char *err, size_t errlen)
{
    scene_prop *p = scene_obj_has(o, name) ? scene_obj_prop(o, name) : NULL;
    out->on = p && !(p->type == SCENE_FLOAT && p->value.f == 0.0);
    return bsdf_scalar_param(set, o, name, def, &out->v, err, errlen);
}

double schlick_weight(double cos_i)
{
    double m = fmin(fmax(1.0 - cos_i, 0.0), 1.0);
    return m * m * m * m * m;
}

/* The cosine whose weight Schlick's approximation takes: the incident one
 * from the rarer side, the transmitted one from the denser side. */
static double schlick_cosine(double cos_i, double eta, bool *denser)
{
    double eta_it = cos_i >= 0.0 ? eta : 1.0 / eta, eta_ti = 1.0 / eta_it;
    *denser = !(eta_it > 1.0);
    double cos_t2 = 1.0 - (1.0 - cos_i * cos_i) * eta_ti * eta_ti;
    return *denser ? sqrt(fmax(cos_t2, 0.0)) : fabs(cos_i);
}

double principled_schlick(double r0, double cos_i, double eta)
{
    bool denser;
    double w = schlick_weight(schlick_cosine(cos_i, eta, &denser));
    return w + (1.0 - w) * r0; /* lerp(w, 1, r0) */
}

rgb principled_schlick_rgb(rgb r0, double cos_i, double eta)
{
    bool denser;
    double w = schlick_weight(schlick_cosine(cos_i, eta, &denser));
    return rgb_make(w + (1.0 - w) * r0.r, w + (1.0 - w) * r0.g, w + (1.0 - w) * r0.b);
}

double schlick_r0_eta(double eta)
{
    double r = (eta - 1.0) / (eta + 1.0);
    return r * r;
}

bool principled_compatible(vec3 m, vec3 wi, vec3 wo, double cos_i, bool reflection)
{
    vec3 mi = cos_i >= 0.0 ? m : v3_neg(m); /* mulsign(m, cos_i) */
    if (!(v3_dot(wi, mi) > 0.0))
        return false;
    return reflection ? v3_dot(wo, mi) > 0.0 : v3_dot(wo, v3_neg(mi)) > 0.0;
}

microfacet principled_ggx(double roughness, double anisotropic, bool has_anisotropic)
{
    double r2 = roughness * roughness;
    if (!has_anisotropic)
        return microfacet_make(MICROFACET_GGX, fmax(0.001, r2), fmax(0.001, r2), 1);
    double aspect = sqrt(1.0 - 0.9 * anisotropic);
    return microfacet_make(MICROFACET_GGX, fmax(0.001, r2 / aspect), fmax(0.001, r2 * aspect), 1);
}

rgb principled_tint(rgb base_color)
{
    double lum = rgb_luminance(base_color);
    return lum > 0.0 ? rgb_scale(base_color, 1.0 / lum) : rgb_gray(1.0);
}

rgb principled_diffuse(rgb base_color, double roughness, double flatness, bool has_flatness, double cos_i,
                       double cos_o, double cos_d)
{
    double fo = schlick_weight(cos_o), fi = schlick_weight(cos_i);
    double f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    double rr = 2.0 * roughness * cos_d * cos_d;
    double f = f_diff + rr * (fo + fi + fo * fi * (rr - 1.0)); /* + retro-reflection */
    if (has_flatness) {
        /* Hanrahan-Krueger's fake subsurface, Fss90 flattening the retro part. */
        double fss90 = 0.5 * rr;
        double fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
        double f_ss = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
        f += (f_ss - f) * flatness;
    }
    return rgb_scale(base_color, f * cos_o / M_PI);
}

rgb principled_sheen(rgb base_color, double sheen, double sheen_tint, double cos_o, double cos_d)
{
    rgb c = rgb_lerp(rgb_gray(1.0), principled_tint(base_color), sheen_tint);
    return rgb_scale(c, sheen * schlick_weight(fabs(cos_d)) * cos_o);
}
