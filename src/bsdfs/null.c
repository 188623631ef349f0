/* Mitsuba's `null` BSDF: the surface does not interact with light, which
 * goes on straight through it (it only bounds a shape, e.g. of a medium);
 * a camera ray that only meets null surfaces leaves the pixel uncovered. */
#include "bsdfs/bsdf_impl.h"

static int null_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    (void)b, (void)u1, (void)u2;
    out->wo = v3_neg(q->wi);
    out->pdf = 1.0;
    out->eta = 1.0;
    out->sampled_type = BSDF_NULL | BSDF_STRAIGHT_TRANSMISSION;
    out->weight = rgb_gray(1.0);
    return 1;
}

/* Everything passes: the straight lobe transmits all. */
static rgb null_straight(const bsdf_t *b, const bsdf_query *q)
{
    (void)b, (void)q;
    return rgb_gray(1.0);
}

static rgb null_albedo(const bsdf_t *b, texture_point uv)
{
    (void)b, (void)uv;
    return rgb_gray(0.0);
}

static const bsdf_ops null_ops = {"null", null_sample, bsdf_eval_delta_only, bsdf_pdf_delta_only, null_albedo,
                                  null_straight, NULL};

static bsdf_t *null_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    (void)set;
    char none = 0; /* no parameters */
    unsigned flags = BSDF_NULL | BSDF_STRAIGHT_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_BACK_SIDE;
    return bsdf_alloc(o, &null_ops, flags, &none, sizeof none, err, errlen);
}

const bsdf_plugin bsdf_null = {
    .decl = {.cls = SCENE_BSDF, .type = "null"},
    .create = null_create,
};
