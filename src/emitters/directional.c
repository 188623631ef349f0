/* Mitsuba's `directional` emitter: `irradiance` arriving from infinitely far
 * away along `direction` (or the +z axis of `to_world`); a delta light,
 * reached by sampling only. */
#include "emitters/emitter_impl.h"

typedef struct {
    rgb irradiance;
    vec3 direction; /* unit, of travel */
} directional_data;

static int directional_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)ref, (void)u;
    const directional_data *d = e->data;
    out->wi = v3_neg(d->direction);
    out->value = d->irradiance;
    out->pdf = 1.0;
    out->delta = true;
    return 1;
}

static void directional_bounds(const emitter_t *e, light_bounds *out)
{
    const directional_data *d = e->data;
    emitter_bounds_infinite(rgb_max(d->irradiance), out);
}

static const emitter_ops directional_ops = {directional_sample, NULL, NULL, NULL, NULL, NULL, directional_bounds, false};

static emitter_t *directional_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape, (void)textures;
    directional_data d;
    d.irradiance = emitter_rgb_param(o, "irradiance", 1.0);
    transform4 t = scene_obj_transform(o, "to_world");
    d.direction = v3_norm(scene_obj_vector(o, "direction", transform_vector(&t, v3(0, 0, 1))));
    if (!(v3_len(d.direction) > 0.0)) {
        scene_obj_error(o, err, errlen, "directional emitter needs a nonzero direction");
        return NULL;
    }
    return emitter_alloc(o, &directional_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl directional_params[] = {
    {"irradiance", PARAM_COLOR, 0, NULL},
    {"direction", PARAM_VECTOR, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const emitter_plugin emitter_directional = {
    .decl = {.cls = SCENE_EMITTER, .type = "directional", .params = directional_params,
             .exclusive = {"direction", "to_world"}},
    .create = directional_create,
};
