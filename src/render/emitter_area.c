/* `area` emitters: a shape's surface radiates radiance (a color or a texture
 * over the shape's uv) from its front side only, as in Mitsuba. Sampling
 * picks a point by area on the shape and converts to solid angle. */
#include "render/scene_impl.h"

static rgb area_radiance(const emitter_t *e, vec2 uv)
{
    return e->texture ? texture_eval(e->texture, uv) : e->value;
}

int emitter_area_sample(const struct scene *s, const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    surface_hit h;
    double pdf_area;
    shape_sample_area(&s->shapes[e->shape], u, &h, &pdf_area);
    vec3 d = v3_sub(h.p, ref);
    double dist2 = v3_dot(d, d);
    if (!(dist2 > 0.0) || !(pdf_area > 0.0))
        return 0;
    double dist = sqrt(dist2);
    vec3 wi = v3_scale(d, 1.0 / dist);
    double cos_l = -v3_dot(h.ng, wi);
    if (cos_l <= 0.0)
        return 0;
    out->wi = wi;
    out->dist = dist;
    out->p = h.p;
    out->n = h.ng;
    out->eps = h.eps;
    out->pdf = pdf_area * dist2 / cos_l;
    out->value = area_radiance(e, h.uv);
    out->delta = false;
    return 1;
}

rgb emitter_area_eval(const struct scene *s, const emitter_t *e, const surface_hit *hit, vec3 dir)
{
    (void)s;
    return v3_dot(hit->ng, dir) < 0.0 ? area_radiance(e, hit->uv) : rgb_gray(0.0);
}

double emitter_area_pdf(const struct scene *s, const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir)
{
    double cos_l = -v3_dot(hit->ng, dir);
    if (cos_l <= 0.0)
        return 0.0;
    vec3 d = v3_sub(hit->p, ref);
    return shape_pdf_area(&s->shapes[e->shape], hit) * v3_dot(d, d) / cos_l;
}
