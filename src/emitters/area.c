/* Mitsuba's `area` emitter: a shape's surface radiates `radiance` (a color or
 * a texture over the shape's uv) from its front side only. Sampling asks the
 * shape for a point seen from the reference point (by solid angle where the
 * shape can, by area otherwise: shape_sample_from). */
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
    double pdf;
    shape_sample_from(e->shape, ref, u, &h, &pdf);
    vec3 d = v3_sub(h.p, ref);
    double dist2 = v3_dot(d, d);
    if (!(dist2 > 0.0) || !(pdf > 0.0))
        return 0;
    double dist = sqrt(dist2);
    vec3 wi = v3_scale(d, 1.0 / dist);
    if (v3_dot(h.ng, wi) >= 0.0) /* its back */
        return 0;
    out->wi = wi;
    out->dist = dist;
    out->p = h.p;
    out->n = h.ng;
    out->eps = h.eps;
    out->pdf = pdf;
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
    return v3_dot(hit->ng, dir) < 0.0 ? shape_pdf_from(e->shape, ref, hit) : 0.0;
}

/* phi: the radiance (a texture's mean) times the shape's largest projected
 * area: its area when flat, a quarter of it when its normals turn every way
 * (Cauchy: a convex body's mean projected area is a quarter of its
 * surface), in between A cos(theta_o) but at least A / 4. */
static void area_bounds(const emitter_t *e, light_bounds *out)
{
    const area_data *d = e->data;
    const shape_t *sh = e->shape;
    double radiance = rgb_max(d->texture ? texture_mean(d->texture) : d->value);
    double projected = sh->area * fmax(0.25, sh->normal_cos);
    *out = (light_bounds){.lo = sh->bounds_lo, .hi = sh->bounds_hi, .axis = sh->normal_axis,
                          .cos_theta_o = sh->normal_cos, .cos_theta_e = 0.0, .phi = radiance * projected};
}

static const emitter_ops area_ops = {area_sample, area_eval_hit, area_pdf_hit, NULL, NULL, NULL, area_bounds, true};

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
