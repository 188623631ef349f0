/* Smooth dielectric interface (Mitsuba `dielectric`): Fresnel-weighted choice
 * between the mirror and the refracted direction; both sides scatter. */
#include "celadon/fresnel.h"
#include "render/bsdf_impl.h"

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
        out->weight = spectrum_eval(&d->specular_reflectance, q->uv);
    } else {
        out->wo = refract_about(q->wi, v3(0.0, 0.0, 1.0), cos_t, eta_ti);
        out->pdf = 1.0 - r;
        out->eta = eta_it;
        out->sampled_type = BSDF_DELTA_TRANSMISSION;
        double scale = q->mode == TRANSPORT_RADIANCE ? eta_ti * eta_ti : 1.0;
        out->weight = rgb_scale(spectrum_eval(&d->specular_transmittance, q->uv), scale);
    }
    return out->pdf > 0.0;
}

static rgb dielectric_albedo(const bsdf_t *b, vec2 uv)
{
    const dielectric_data *d = b->data;
    return spectrum_eval(&d->specular_transmittance, uv);
}

static const bsdf_ops dielectric_ops = {dielectric_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only, dielectric_albedo, NULL};

bsdf_dielectric_params bsdf_dielectric_defaults(void)
{
    bsdf_dielectric_params p;
    bsdf_ior_lookup("bk7", &p.int_ior);
    bsdf_ior_lookup("air", &p.ext_ior);
    p.specular_reflectance = bsdf_spectrum_const(rgb_gray(1.0));
    p.specular_transmittance = bsdf_spectrum_const(rgb_gray(1.0));
    return p;
}

bsdf_t *bsdf_create_dielectric(const bsdf_dielectric_params *p, char *err, size_t errlen)
{
    if (bsdf_check_ior(p->int_ior, p->ext_ior, err, errlen) ||
        bsdf_check_spectrum("specular_reflectance", &p->specular_reflectance, err, errlen) ||
        bsdf_check_spectrum("specular_transmittance", &p->specular_transmittance, err, errlen))
        return NULL;
    unsigned flags = BSDF_DELTA_REFLECTION | BSDF_DELTA_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE;
    bsdf_t *b = bsdf_alloc("dielectric", &dielectric_ops, flags, sizeof(dielectric_data), err, errlen);
    if (b)
        *(dielectric_data *)b->data =
            (dielectric_data){p->int_ior / p->ext_ior, p->specular_reflectance, p->specular_transmittance};
    return b;
}
