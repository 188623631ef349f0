/* Mitsuba's `area` emitter: a shape's surface radiates `radiance` (a color or
 * a texture over the shape's uv) from its front side only. Sampling picks a
 * point by area on the shape and converts to solid angle. */
#include <stdio.h>

#include "emitters/emitter_impl.h"

typedef struct {
    rgb value;                /* radiance */
    const texture_t *texture; /* or NULL */
} area_data;

static rgb area_radiance(const area_data *d, vec2 uv)
{
    return d->texture ? texture_eval(d->texture, uv) : d->value;
}

static int area_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    surface_hit h;
    double pdf_area;
    shape_sample_area(e->shape, u, &h, &pdf_area);
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
    out->value = area_radiance(e->data, h.uv);
    out->delta = false;
    return 1;
}

static rgb area_eval_hit(const emitter_t *e, const surface_hit *hit, vec3 dir)
{
    return v3_dot(hit->ng, dir) < 0.0 ? area_radiance(e->data, hit->uv) : rgb_gray(0.0);
}

static double area_pdf_hit(const emitter_t *e, vec3 ref, const surface_hit *hit, vec3 dir)
{
    double cos_l = -v3_dot(hit->ng, dir);
    if (cos_l <= 0.0)
        return 0.0;
    vec3 d = v3_sub(hit->p, ref);
    return shape_pdf_area(e->shape, hit) * v3_dot(d, d) / cos_l;
}

static const emitter_ops area_ops = {area_sample, area_eval_hit, area_pdf_hit, NULL, NULL, NULL};

static emitter_t *area_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    area_data d = {rgb_gray(1.0), NULL};
    scene_obj *tex = scene_obj_texture(o, "radiance");
    if (tex && !(d.texture = texture_set_get(textures, tex, err, errlen)))
        return NULL;
    d.value = emitter_rgb_param(o, "radiance", 1.0);
    if (shape_prepare_sampling(shape) != 0) {
        snprintf(err, errlen, "%s:%d: an emitting shape must have a nonzero area", shape->file, shape->line);
        return NULL;
    }
    emitter_t *e = emitter_alloc(o, &area_ops, &d, sizeof d, err, errlen);
    if (e)
        e->shape = shape;
    return e;
}

static const scene_param_decl area_params[] = {{"radiance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL}, {NULL, 0, 0, NULL}};

const emitter_plugin emitter_area = {
    .decl = {.cls = SCENE_EMITTER, .type = "area", .params = area_params, .host = SCENE_SHAPE},
    .flags = EMITTER_SURFACE,
    .create = area_create,
};
