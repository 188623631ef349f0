/* Smooth dielectric interface (Mitsuba `dielectric`): Fresnel-weighted choice
 * between the mirror and the refracted direction; both sides scatter. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

typedef struct {
    double eta; /* int_ior / ext_ior */
    bsdf_spectrum specular_reflectance, specular_transmittance;
} dielectric_data;

static int dielectric_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u2;
    const dielectric_data *d = b->data;
    double cos_t, eta_it, eta_ti;
    double r = fresnel_dielectric(q->wi.z, d->eta, &cos_t, &eta_it, &eta_ti);
    if (q->wi.z == 0.0)
        return 0;
    if (u1 <= r) {
        out->wo = reflect_local(q->wi);
        out->pdf = r;
        out->eta = 1.0;
        out->sampled_type = BSDF_DELTA_REFLECTION;
        out->weight = spectrum_eval(&d->specular_reflectance, bsdf_at(q));
    } else {
        out->wo = refract_about(q->wi, v3(0.0, 0.0, 1.0), cos_t, eta_ti);
        out->pdf = 1.0 - r;
        out->eta = eta_it;
        out->sampled_type = BSDF_DELTA_TRANSMISSION;
        double scale = q->mode == TRANSPORT_RADIANCE ? eta_ti * eta_ti : 1.0;
        out->weight = rgb_scale(spectrum_eval(&d->specular_transmittance, bsdf_at(q)), scale);
    }
    return out->pdf > 0.0;
}

static rgb dielectric_albedo(const bsdf_t *b, texture_point uv)
{
    const dielectric_data *d = b->data;
    return spectrum_eval(&d->specular_transmittance, uv);
}

static const bsdf_ops dielectric_ops = {"dielectric",
                                        dielectric_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only, dielectric_albedo,
                                        NULL, NULL};

static bsdf_t *dielectric_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    dielectric_data d;
    if (bsdf_smooth_dielectric_param(set, o, &d.eta, &d.specular_reflectance, &d.specular_transmittance, err,
                                     errlen) != 0)
        return NULL;
    unsigned flags = BSDF_DELTA_REFLECTION | BSDF_DELTA_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE;
    return bsdf_alloc(o, &dielectric_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl dielectric_params[] = {BSDF_PARAMS_DIELECTRIC, BSDF_PARAMS_END};

const bsdf_plugin bsdf_dielectric = {
    .decl = {.cls = SCENE_BSDF, .type = "dielectric", .params = dielectric_params},
    .create = dielectric_create,
};
