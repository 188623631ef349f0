/* Smooth conductor (Mitsuba `conductor`): a mirror weighted by the complex-IOR
 * Fresnel reflectance, front side only. */
#include "celadon/fresnel.h"
#include "render/bsdf_impl.h"

typedef struct {
    rgb eta, k;
    bsdf_spectrum specular_reflectance;
} conductor_data;

static int conductor_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u1;
    (void)u2;
    const conductor_data *d = b->data;
    if (q->wi.z <= 0.0)
        return 0;
    out->wo = reflect_local(q->wi);
    out->pdf = 1.0;
    out->eta = 1.0;
    out->sampled_type = BSDF_DELTA_REFLECTION;
    out->weight = rgb_mul(spectrum_eval(&d->specular_reflectance, q->uv), fresnel_conductor_rgb(q->wi.z, d->eta, d->k));
    return 1;
}

static rgb conductor_albedo(const bsdf_t *b, vec2 uv)
{
    const conductor_data *d = b->data;
    return rgb_mul(spectrum_eval(&d->specular_reflectance, uv), fresnel_conductor_rgb(1.0, d->eta, d->k));
}

static const bsdf_ops conductor_ops = {conductor_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only, conductor_albedo, NULL};

bsdf_conductor_params bsdf_conductor_defaults(void)
{
    bsdf_conductor_params p;
    bsdf_conductor_preset("none", &p.eta, &p.k);
    p.specular_reflectance = bsdf_spectrum_const(rgb_gray(1.0));
    return p;
}

bsdf_t *bsdf_create_conductor(const bsdf_conductor_params *p, char *err, size_t errlen)
{
    bsdf_spectrum eta = bsdf_spectrum_const(p->eta), k = bsdf_spectrum_const(p->k);
    if (bsdf_check_spectrum("eta", &eta, err, errlen) || bsdf_check_spectrum("k", &k, err, errlen) ||
        bsdf_check_spectrum("specular_reflectance", &p->specular_reflectance, err, errlen))
        return NULL;
    bsdf_t *b = bsdf_alloc("conductor", &conductor_ops, BSDF_DELTA_REFLECTION | BSDF_FRONT_SIDE,
                           sizeof(conductor_data), err, errlen);
    if (b)
        *(conductor_data *)b->data = (conductor_data){p->eta, p->k, p->specular_reflectance};
    return b;
}
