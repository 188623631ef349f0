/* Two-sided adapter (Mitsuba `twosided`): the front BSDF on the front side and
 * the back BSDF (default: the front one) on the back, evaluated in the frame
 * mirrored through the surface. Directions on opposite sides never couple. */
#include "bsdfs/bsdf_impl.h"

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

static rgb twosided_albedo(const bsdf_t *b, texture_point uv)
{
    const twosided_data *d = b->data;
    return bsdf_albedo_at(d->front, uv);
}

static const bsdf_ops twosided_ops = {"twosided", twosided_sample, twosided_eval, twosided_pdf, twosided_albedo, NULL, NULL};

/* The nested BSDFs (one or two: the reader checked) are built in set first. */
static bsdf_t *twosided_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    scene_obj *nested[2];
    int n = scene_obj_children(o, SCENE_BSDF, nested, 2);
    twosided_data d;
    d.front = bsdf_set_get(set, nested[0], err, errlen);
    d.back = n >= 2 ? bsdf_set_get(set, nested[1], err, errlen) : d.front;
    if (!d.front || !d.back)
        return NULL;
    if ((d.front->flags | d.back->flags) & BSDF_TRANSMISSION) {
        bsdf_refuse(o, err, errlen, "twosided: nested bsdfs must not transmit light (got %s)",
                    (d.front->flags & BSDF_TRANSMISSION ? d.front : d.back)->ops->name);
        return NULL;
    }
    unsigned lobes = (d.front->flags | d.back->flags) & ~(unsigned)(BSDF_FRONT_SIDE | BSDF_BACK_SIDE);
    return bsdf_alloc(o, &twosided_ops, lobes | BSDF_FRONT_SIDE | BSDF_BACK_SIDE, &d, sizeof d, err, errlen);
}

static const scene_child_decl twosided_children[] = {{SCENE_BSDF, 1, 2, NULL}, {SCENE_SCENE, 0, 0, NULL}};

const bsdf_plugin bsdf_twosided = {
    .decl = {.cls = SCENE_BSDF, .type = "twosided", .children = twosided_children},
    .create = twosided_create,
};
