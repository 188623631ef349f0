/* Mitsuba's `point` emitter: `intensity` radiated equally in every direction
 * from `position` (or the origin of `to_world`); a delta light, reached by
 * sampling only. */
#include "emitters/emitter_impl.h"

typedef struct {
    rgb intensity;
    vec3 position;
} point_data;

static int point_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)u;
    const point_data *d = e->data;
    vec3 to = v3_sub(d->position, ref);
    double dist2 = v3_dot(to, to);
    if (!(dist2 > 0.0))
        return 0;
    out->dist = sqrt(dist2);
    out->wi = v3_scale(to, 1.0 / out->dist);
    out->p = d->position;
    out->value = rgb_scale(d->intensity, 1.0 / dist2);
    out->pdf = 1.0;
    out->delta = true;
    return 1;
}

static void point_bounds(const emitter_t *e, light_bounds *out)
{
    const point_data *d = e->data;
    emitter_bounds_point(d->position, rgb_max(d->intensity), out);
}

static const emitter_ops point_ops = {point_sample, NULL, NULL, NULL, NULL, NULL, point_bounds, false};

static emitter_t *point_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape, (void)textures;
    point_data d;
    d.intensity = emitter_rgb_param(o, "intensity", 1.0);
    transform4 t = scene_obj_transform(o, "to_world");
    d.position = scene_obj_point(o, "position", transform_point(&t, v3(0, 0, 0)));
    return emitter_alloc(o, &point_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl point_params[] = {
    {"intensity", PARAM_COLOR, 0, NULL},
    {"position", PARAM_POINT, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const emitter_plugin emitter_point = {
    .decl = {.cls = SCENE_EMITTER, .type = "point", .params = point_params, .exclusive = {"position", "to_world"}},
    .create = point_create,
};
