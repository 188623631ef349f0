/* Two-sided adapter (Mitsuba `twosided`): the front BSDF on the front side and
 * the back BSDF (default: the front one) on the back, evaluated in the frame
 * mirrored through the surface. Directions on opposite sides never couple. */
#include <stdio.h>

#include "render/bsdf_impl.h"

typedef struct {
    const bsdf_t *front, *back;
} twosided_data;

static vec3 flip(vec3 w) { return v3(w.x, w.y, -w.z); }

static int twosided_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const twosided_data *d = b->data;
    if (q->wi.z > 0.0)
        return bsdf_sample(d->front, q, u1, u2, out);
    if (q->wi.z == 0.0)
        return 0;
    bsdf_query back = *q;
    back.wi = flip(q->wi);
    if (!bsdf_sample(d->back, &back, u1, u2, out))
        return 0;
    out->wo = flip(out->wo);
    return 1;
}

static rgb twosided_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const twosided_data *d = b->data;
    if (q->wi.z > 0.0 && wo.z > 0.0)
        return bsdf_eval(d->front, q, wo);
    if (q->wi.z < 0.0 && wo.z < 0.0) {
        bsdf_query back = *q;
        back.wi = flip(q->wi);
        return bsdf_eval(d->back, &back, flip(wo));
    }
    return rgb_gray(0.0);
}

static double twosided_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    const twosided_data *d = b->data;
    if (q->wi.z > 0.0 && wo.z > 0.0)
        return bsdf_pdf(d->front, q, wo);
    if (q->wi.z < 0.0 && wo.z < 0.0) {
        bsdf_query back = *q;
        back.wi = flip(q->wi);
        return bsdf_pdf(d->back, &back, flip(wo));
    }
    return 0.0;
}

static rgb twosided_albedo(const bsdf_t *b, vec2 uv)
{
    const twosided_data *d = b->data;
    return bsdf_albedo(d->front, uv);
}

static const bsdf_ops twosided_ops = {twosided_sample, twosided_eval, twosided_pdf, twosided_albedo, NULL};

bsdf_t *bsdf_create_twosided(const bsdf_t *front, const bsdf_t *back, char *err, size_t errlen)
{
    if (!front) {
        snprintf(err, errlen, "twosided needs a nested bsdf");
        return NULL;
    }
    if (!back)
        back = front;
    if ((bsdf_flags(front) | bsdf_flags(back)) & BSDF_TRANSMISSION) {
        snprintf(err, errlen, "twosided: nested bsdfs must not transmit light (got %s)",
                 bsdf_flags(front) & BSDF_TRANSMISSION ? bsdf_plugin_name(front) : bsdf_plugin_name(back));
        return NULL;
    }
    unsigned lobes = (bsdf_flags(front) | bsdf_flags(back)) & ~(unsigned)(BSDF_FRONT_SIDE | BSDF_BACK_SIDE);
    bsdf_t *b = bsdf_alloc("twosided", &twosided_ops, lobes | BSDF_FRONT_SIDE | BSDF_BACK_SIDE, sizeof(twosided_data),
                           err, errlen);
    if (b)
        *(twosided_data *)b->data = (twosided_data){front, back};
    return b;
}
