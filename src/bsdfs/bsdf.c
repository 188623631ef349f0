/* BSDF dispatch and allocation, and what delta and rough plugins share. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bsdfs/bsdf_impl.h"
#include "core/core.h"

bsdf_t *bsdf_alloc(const scene_obj *o, const bsdf_ops *ops, unsigned flags, const void *data, size_t data_size,
                   char *err, size_t errlen)
{
    void *at;
    bsdf_t *b = record_alloc(sizeof *b, data, data_size, &at);
    if (!b) {
        bsdf_refuse(o, err, errlen, "out of memory");
        return NULL;
    }
    b->ops = ops;
    b->flags = flags;
    b->data = at;
    return b;
}

/* The rotation about z by the angle of t = (cos, sin, 0), and back. */
static vec3 turn(vec3 w, vec3 t) { return v3(w.x * t.x + w.y * t.y, w.y * t.x - w.x * t.y, w.z); }
static vec3 turn_back(vec3 w, vec3 t) { return v3(w.x * t.x - w.y * t.y, w.x * t.y + w.y * t.x, w.z); }

/* An anisotropic BSDF's query in Mitsuba's shading frame (its dpdu then
 * lies along +x, so turning it again changes nothing); t the rotation. An
 * isotropic BSDF takes the query as it is (the dispatchers below call it
 * directly: no copy of the query, no turn by the identity). */
static bsdf_query oriented(const bsdf_query *q, vec3 *t)
{
    *t = bsdf_query_tangent(q);
    bsdf_query r = *q;
    r.wi = turn(q->wi, *t), r.dpdu = turn(q->dpdu, *t), r.dpdv = turn(q->dpdv, *t), r.ng = turn(q->ng, *t);
    return r;
}

int bsdf_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    memset(out, 0, sizeof *out);
    if (!(b->flags & BSDF_ANISOTROPIC))
        return b->ops->sample(b, q, u1, u2, out);
    vec3 t;
    bsdf_query r = oriented(q, &t);
    int ok = b->ops->sample(b, &r, u1, u2, out);
    out->wo = turn_back(out->wo, t);
    return ok;
}

rgb bsdf_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    if (!(b->flags & BSDF_ANISOTROPIC))
        return b->ops->eval(b, q, wo);
    vec3 t;
    bsdf_query r = oriented(q, &t);
    return b->ops->eval(b, &r, turn(wo, t));
}

double bsdf_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    if (!(b->flags & BSDF_ANISOTROPIC))
        return b->ops->pdf(b, q, wo);
    vec3 t;
    bsdf_query r = oriented(q, &t);
    return b->ops->pdf(b, &r, turn(wo, t));
}

unsigned bsdf_flags(const bsdf_t *b)
{
    return b->flags;
}

rgb bsdf_albedo_at(const bsdf_t *b, texture_point at)
{
    return b->ops->albedo(b, at);
}

rgb bsdf_albedo(const bsdf_t *b, vec2 uv)
{
    return bsdf_albedo_at(b, (texture_point){.uv = uv});
}

rgb bsdf_straight_transmittance(const bsdf_t *b, const bsdf_query *q)
{
    return b->flags & BSDF_STRAIGHT_TRANSMISSION ? b->ops->straight(b, q) : rgb_gray(0.0);
}

vec3 bsdf_shading_normal(const bsdf_t *b, const bsdf_query *q)
{
    if (!b->ops->shading_normal)
        return v3(0.0, 0.0, 1.0);
    if (!(b->flags & BSDF_ANISOTROPIC))
        return b->ops->shading_normal(b, q);
    vec3 t;
    bsdf_query r = oriented(q, &t);
    return turn_back(b->ops->shading_normal(b, &r), t);
}

void bsdf_destroy(bsdf_t *b)
{
    free(b);
}

rgb bsdf_eval_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    (void)b;
    (void)q;
    (void)wo;
    return rgb_gray(0.0);
}

double bsdf_pdf_delta_only(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    (void)b;
    (void)q;
    (void)wo;
    return 0.0;
}

int bsdf_finish_sample(const bsdf_t *b, const bsdf_query *q, bsdf_sample_rec *out)
{
    double pdf = b->ops->pdf(b, q, out->wo);
    if (!(pdf > 0.0) || !isfinite(pdf))
        return 0;
    rgb f = b->ops->eval(b, q, out->wo);
    out->pdf = pdf;
    out->weight = rgb_scale(f, 1.0 / pdf);
    return 1;
}
