/* Emitter dispatch: sampling from a reference point for next-event
 * estimation, and evaluation of the environment (constant, envmap) and of
 * the delta lights (point, directional), which only sampling can reach. */
#include <stdlib.h>

#include "celadon/sampling.h"
#include "render/scene_impl.h"

int emitter_sample(const struct scene *s, const emitter_t *e, vec3 ref, vec3 u, emitter_sample_rec *out)
{
    out->eps = 0.0;
    out->delta = false;
    out->dist = INFINITY;
    switch (e->kind) {
    case EMITTER_AREA:
        return emitter_area_sample(s, e, ref, u, out);
    case EMITTER_CONSTANT:
        out->wi = warp_square_to_uniform_sphere(v2(u.x, u.y));
        out->pdf = warp_uniform_sphere_pdf();
        out->value = e->value;
        return 1;
    case EMITTER_ENVMAP:
        return emitter_envmap_sample(e->env, v2(u.x, u.y), &out->wi, &out->value, &out->pdf);
    case EMITTER_POINT: {
        vec3 d = v3_sub(e->position, ref);
        double dist2 = v3_dot(d, d);
        if (!(dist2 > 0.0))
            return 0;
        out->dist = sqrt(dist2);
        out->wi = v3_scale(d, 1.0 / out->dist);
        out->p = e->position;
        out->value = rgb_scale(e->value, 1.0 / dist2);
        out->pdf = 1.0;
        out->delta = true;
        return 1;
    }
    case EMITTER_DIRECTIONAL:
        out->wi = v3_neg(e->direction);
        out->value = e->value;
        out->pdf = 1.0;
        out->delta = true;
        return 1;
    }
    return 0;
}

rgb emitter_env_eval(const emitter_t *e, vec3 dir)
{
    return e->kind == EMITTER_ENVMAP ? emitter_envmap_eval(e->env, dir) : e->value;
}

double emitter_env_pdf(const emitter_t *e, vec3 dir)
{
    return e->kind == EMITTER_ENVMAP ? emitter_envmap_pdf(e->env, dir) : warp_uniform_sphere_pdf();
}

void emitter_free(emitter_t *e)
{
    if (e->env) {
        emitter_envmap_free(e->env);
        free(e->env);
    }
}
