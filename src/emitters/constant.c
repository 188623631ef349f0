/* Mitsuba's `constant` emitter: the same radiance from every direction at
 * infinity. Next-event estimation never picks it (its light_bounds' phi is
 * 0, as pbrt-v4 leaves uniform infinite lights out with MIS compensation:
 * Karlik et al. 2019): BSDF sampling finds it as well as any emitter
 * sample could (the radiance is the same in every direction) and, weighed
 * by MIS at its full share, with no shadow ray spent and no sample taken
 * from the other lights; measured on scenes/studio, its uniform samples
 * had doubled the image's variance. Its sampler (uniform over the sphere)
 * stays for what asks it directly. */
#include "emitters/emitter_impl.h"

typedef struct {
    rgb value; /* radiance */
} constant_data;

static int constant_sample(const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    (void)ref;
    const constant_data *d = e->data;
    out->wi = warp_square_to_uniform_sphere(v2(u.x, u.y));
    out->pdf = warp_uniform_sphere_pdf();
    out->value = d->value;
    return 1;
}

static rgb constant_eval_env(const emitter_t *e, vec3 dir)
{
    (void)dir;
    const constant_data *d = e->data;
    return d->value;
}

static double constant_pdf_env(const emitter_t *e, vec3 dir)
{
    (void)e, (void)dir;
    return warp_uniform_sphere_pdf();
}

/* Never worth picking (above). */
static void constant_bounds(const emitter_t *e, light_bounds *out)
{
    (void)e;
    emitter_bounds_infinite(0.0, out);
}

static const emitter_ops constant_ops = {constant_sample,   NULL, NULL, constant_eval_env, constant_pdf_env,
                                         NULL,              constant_bounds,   false};

static emitter_t *constant_create(scene_obj *o, shape_t *shape, texture_set *textures, char *err, size_t errlen)
{
    (void)shape, (void)textures;
    if (scene_obj_texture(o, "radiance")) {
        scene_obj_error(o, err, errlen, "a textured constant emitter is not supported (use envmap)");
        return NULL;
    }
    constant_data d = {emitter_rgb_param(o, "radiance", 1.0)};
    return emitter_alloc(o, &constant_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl constant_params[] = {{"radiance", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
                                                   {NULL, 0, 0, NULL}};

const emitter_plugin emitter_constant = {
    .decl = {.cls = SCENE_EMITTER, .type = "constant", .params = constant_params},
    .flags = EMITTER_ENVIRONMENT,
    .create = constant_create,
};
