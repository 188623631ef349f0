/* Thin dielectric sheet (Mitsuba `thindielectric`): light passes straight
 * through without bending; the reflectance sums the geometric series of
 * internal bounces, R' = R + T^2 R / (1 - R^2). */
#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

typedef struct {
    double eta;
    bsdf_spectrum specular_reflectance, specular_transmittance;
} thindielectric_data;

static double sheet_reflectance(double cos_i, double eta)
{
    double r = fresnel_dielectric(fabs(cos_i), eta, NULL, NULL, NULL);
    if (r < 1.0) {
        double t = 1.0 - r;
        r += t * t * r / (1.0 - r * r);
    }
    return r;
}

static int thindielectric_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)u2;
    const thindielectric_data *d = b->data;
    if (q->wi.z == 0.0)
        return 0;
    double r = sheet_reflectance(q->wi.z, d->eta);
    out->eta = 1.0;
    if (u1 <= r) {
        out->wo = reflect_local(q->wi);
        out->pdf = r;
        out->sampled_type = BSDF_DELTA_REFLECTION;
        out->weight = spectrum_eval(&d->specular_reflectance, bsdf_at(q));
    } else {
        out->wo = v3_neg(q->wi);
        out->pdf = 1.0 - r;
        out->sampled_type = BSDF_DELTA_TRANSMISSION | BSDF_STRAIGHT_TRANSMISSION;
        out->weight = spectrum_eval(&d->specular_transmittance, bsdf_at(q));
    }
    return out->pdf > 0.0;
}

/* The transmission lobe's weight times its selection probability. */
static rgb thindielectric_straight(const bsdf_t *b, const bsdf_query *q)
{
    const thindielectric_data *d = b->data;
    if (q->wi.z == 0.0)
        return rgb_gray(0.0);
    return rgb_scale(spectrum_eval(&d->specular_transmittance, bsdf_at(q)), 1.0 - sheet_reflectance(q->wi.z, d->eta));
}

static rgb thindielectric_albedo(const bsdf_t *b, texture_point uv)
{
    const thindielectric_data *d = b->data;
    return spectrum_eval(&d->specular_transmittance, uv);
}

static const bsdf_ops thindielectric_ops = {"thindielectric",
                                            thindielectric_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only,
                                            thindielectric_albedo, thindielectric_straight, NULL};

static bsdf_t *thindielectric_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    thindielectric_data d;
    if (bsdf_smooth_dielectric_param(set, o, &d.eta, &d.specular_reflectance, &d.specular_transmittance, err,
                                     errlen) != 0)
        return NULL;
    unsigned flags = BSDF_DELTA_REFLECTION | BSDF_DELTA_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE |
                     BSDF_STRAIGHT_TRANSMISSION;
    return bsdf_alloc(o, &thindielectric_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl thindielectric_params[] = {BSDF_PARAMS_DIELECTRIC, BSDF_PARAMS_END};

const bsdf_plugin bsdf_thindielectric = {
    .decl = {.cls = SCENE_BSDF, .type = "thindielectric", .params = thindielectric_params},
    .create = thindielectric_create,
};
