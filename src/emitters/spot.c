/* Mitsuba's `spot` light: `intensity` radiated from the origin of
 * to_world around its local +z, full within `beam_width` degrees of the
 * axis (3/4 of cutoff_angle by default), falling linearly in the angle to
 * zero at `cutoff_angle` (20 degrees); an optional `texture` is projected
 * along the beam, uv = 1/2 + 1/2 (x, y) / (z tan(cutoff_angle)) for a
 * local direction (x, y, z). A delta light, reached by sampling only. */
#include "emitters/emitter_impl.h"

typedef struct {
    rgb intensity;
    const texture_t *texture; /* or NULL */
    transform4 to_world, to_local;
    double cutoff, cos_cutoff, cos_beam, inv_transition; /* radians */
    double uv_factor;                                    /* tan(cutoff) */
} spot_data;

/* The falloff in [0, 1] toward the local direction d (any length). */
static double spot_falloff(const spot_data *s, vec3 d)
{
    double cos_theta = v3_norm(d).z;
    if (!(cos_theta > s->cos_cutoff))
        return 0.0;
    if (cos_theta >= s->cos_beam)
        return 1.0;
    return (s->cutoff - acos(cos_theta)) * s->inv_transition;
}

static int spot_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)u;
    const spot_data *s = e->data;
    if (!emitter_delta_sample(transform_point(&s->to_world, v3(0, 0, 0)), ref, out))
        return 0;
    vec3 local = transform_vector(&s->to_local, v3_neg(out->wi));
    double falloff = spot_falloff(s, local);
    if (falloff <= 0.0)
        return 0;
    rgb value = s->intensity;
    if (s->texture) {
        vec2 uv = v2(0.5 + 0.5 * local.x / (local.z * s->uv_factor), 0.5 + 0.5 * local.y / (local.z * s->uv_factor));
        value = rgb_mul(value, texture_eval(s->texture, uv));
    }
    out->value = rgb_scale(value, falloff / (out->dist * out->dist));
    return 1;
}

/* For light selection, a point light of the beam's intensity (the texture's
 * mean across it) shining every way: its cone is not bounded here, since
 * under a to_world that is no similarity the beam's world cone is not the
 * local one. */
static void spot_bounds(const emitter_t *e, light_bounds *out)
{
    const spot_data *s = e->data;
    rgb value = s->texture ? rgb_mul(s->intensity, texture_mean(s->texture)) : s->intensity;
    emitter_bounds_point(transform_point(&s->to_world, v3(0, 0, 0)), rgb_max(value), out);
}

static const emitter_ops spot_ops = {spot_sample, NULL, NULL, NULL, NULL, NULL, spot_bounds, false};

static emitter_t *spot_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape;
    spot_data d = {.texture = NULL};
    d.intensity = emitter_rgb_param(o, "intensity", 1.0);
    scene_obj *tex = scene_obj_texture(o, "texture");
    if (tex && !(d.texture = texture_set_get(textures, tex, err, errlen)))
        return NULL;
    double cutoff = scene_obj_float(o, "cutoff_angle", 20.0);
    double beam = scene_obj_float(o, "beam_width", cutoff * 0.75);
    if (!(cutoff > 0.0 && cutoff < 90.0) || !(beam >= 0.0 && beam < cutoff)) {
        scene_obj_error(o, err, errlen, "<emitter type=\"spot\">: needs 0 <= beam_width < cutoff_angle < 90 "
                        "(got %g and %g)", beam, cutoff);
        return NULL;
    }
    d.to_world = scene_obj_transform(o, "to_world");
    d.to_local = transform_inverse(&d.to_world);
    d.cutoff = cutoff * (M_PI / 180.0);
    d.cos_cutoff = cos(d.cutoff);
    d.cos_beam = cos(beam * (M_PI / 180.0));
    d.inv_transition = 1.0 / (d.cutoff - beam * (M_PI / 180.0));
    d.uv_factor = tan(d.cutoff);
    return emitter_alloc(o, &spot_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl spot_params[] = {
    {"intensity", PARAM_COLOR, 0, NULL},
    {"cutoff_angle", PARAM_FLOAT, 0, NULL},
    {"beam_width", PARAM_FLOAT, 0, NULL},
    {"texture", PARAM_TEXTURE, 0, NULL},
    {"to_world", PARAM_TRANSFORM, 0, NULL},
    {NULL, 0, 0, NULL},
};

const emitter_plugin emitter_spot = {
    .decl = {.cls = SCENE_EMITTER, .type = "spot", .params = spot_params},
    .create = spot_create,
};
