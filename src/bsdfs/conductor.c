/* Smooth conductor (Mitsuba `conductor`): a mirror weighted by the complex-IOR
 * Fresnel reflectance, front side only. */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

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
    out->weight = rgb_mul(spectrum_eval(&d->specular_reflectance, bsdf_at(q)), fresnel_conductor_rgb(q->wi.z, d->eta, d->k));
    return 1;
}

static rgb conductor_albedo(const bsdf_t *b, texture_point uv)
{
    const conductor_data *d = b->data;
    return rgb_mul(spectrum_eval(&d->specular_reflectance, uv), fresnel_conductor_rgb(1.0, d->eta, d->k));
}

static const bsdf_ops conductor_ops = {"conductor",
                                       conductor_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only, conductor_albedo,
                                       NULL, NULL};

static bsdf_t *conductor_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    conductor_data d;
    if (bsdf_conductor_param(o, &d.eta, &d.k, err, errlen) != 0 ||
        bsdf_spectrum_param(set, o, "specular_reflectance", 1.0, &d.specular_reflectance, err, errlen) != 0)
        return NULL;
    bsdf_spectrum eta = {d.eta, NULL}, k = {d.k, NULL};
    if (bsdf_check_spectrum(o, "eta", &eta, err, errlen) || bsdf_check_spectrum(o, "k", &k, err, errlen) ||
        bsdf_check_spectrum(o, "specular_reflectance", &d.specular_reflectance, err, errlen))
        return NULL;
    return bsdf_alloc(o, &conductor_ops, BSDF_DELTA_REFLECTION | BSDF_FRONT_SIDE, &d, sizeof d, err, errlen);
}

static const scene_param_decl conductor_params[] = {BSDF_PARAMS_CONDUCTOR, BSDF_PARAMS_END};

const bsdf_plugin bsdf_conductor = {
    .decl = {.cls = SCENE_BSDF, .type = "conductor", .params = conductor_params, .exclusive = {"material", "eta"}},
    .create = conductor_create,
};
