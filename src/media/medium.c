/* What every medium shares: building from its parameters, the free-flight
 * sampling and the transmittance (media.h gives the method), the set of a
 * scene's media. */
#include <math.h>
#include <stdlib.h>

#include "media/medium_impl.h"

/* Guards against a path that never leaves a medium (an open shape's
 * interior seen to infinity): so many tentative collisions end it. */
enum { MAX_COLLISIONS = 1 << 20 };

const scene_child_decl medium_children[] = {
    {SCENE_PHASE, 0, 1, NULL},
    {SCENE_SCENE, 0, 0, NULL},
};

/* sigma_t at p: none outside a heterogeneous medium's sigma_t box. */
static rgb extinction(const medium_t *m, vec3 p)
{
    if (!m->homogeneous && !volume_contains(m->sigma_t, p))
        return rgb_gray(0.0);
    return rgb_scale(volume_eval(m->sigma_t, p), m->scale);
}

/* sigma_t and sigma_s at p. */
static void coefficients(const medium_t *m, vec3 p, rgb *sigma_t, rgb *sigma_s)
{
    *sigma_t = extinction(m, p);
    rgb a = volume_eval(m->albedo, p);
    a = (rgb){fmin(a.r, 1.0), fmin(a.g, 1.0), fmin(a.b, 1.0)};
    *sigma_s = rgb_mul(*sigma_t, a);
}

static rgb nonnegative(rgb c)
{
    return (rgb){fmax(c.r, 0.0), fmax(c.g, 0.0), fmax(c.b, 0.0)};
}

medium_event medium_sample(const medium_t *m, const ray3 *r, double tmax, rng_t *rng, rgb *beta, double *t_out)
{
    double mu = m->majorant, t = 0.0;
    if (!(mu > 0.0))
        return MEDIUM_PASSED;
    for (int n = 0; n < MAX_COLLISIONS; n++) {
        t -= log1p(-rng_next_double(rng)) / mu;
        if (t >= tmax)
            return MEDIUM_PASSED;
        rgb st, ss;
        coefficients(m, v3_add(r->o, v3_scale(r->d, t)), &st, &ss);
        rgb sa = nonnegative(rgb_sub(st, ss)), sn = nonnegative(rgb_sub(rgb_gray(mu), st));
        double pa = rgb_max(rgb_mul(*beta, sa)), ps = rgb_max(rgb_mul(*beta, ss)), pn = rgb_max(rgb_mul(*beta, sn));
        double c = pa + ps + pn, u = rng_next_double(rng) * c;
        if (!(c > 0.0) || u < pa)
            return MEDIUM_ABSORBED;
        if (u < pa + ps) {
            *beta = rgb_scale(rgb_mul(*beta, ss), c / (mu * ps));
            *t_out = t;
            return MEDIUM_SCATTERED;
        }
        *beta = rgb_scale(rgb_mul(*beta, sn), c / (mu * pn));
    }
    return MEDIUM_ABSORBED;
}

rgb medium_transmittance(const medium_t *m, const ray3 *r, double tmax, rng_t *rng)
{
    double mu = m->majorant, t = 0.0;
    if (!(mu > 0.0))
        return rgb_gray(1.0);
    if (m->homogeneous) {
        rgb st = rgb_scale(volume_eval(m->sigma_t, r->o), m->scale);
        return (rgb){st.r > 0.0 ? exp(-st.r * tmax) : 1.0, st.g > 0.0 ? exp(-st.g * tmax) : 1.0,
                     st.b > 0.0 ? exp(-st.b * tmax) : 1.0};
    }
    /* Ratio tracking, with Russian roulette once every channel is below 0.1. */
    rgb tr = rgb_gray(1.0);
    for (int n = 0; n < MAX_COLLISIONS; n++) {
        t -= log1p(-rng_next_double(rng)) / mu;
        if (t >= tmax)
            return tr;
        rgb st = extinction(m, v3_add(r->o, v3_scale(r->d, t)));
        tr = rgb_mul(tr, rgb_scale(nonnegative(rgb_sub(rgb_gray(mu), st)), 1.0 / mu));
        double q = rgb_max(tr) / 0.1;
        if (q < 1.0) {
            if (rng_next_double(rng) >= q)
                return rgb_gray(0.0);
            tr = rgb_scale(tr, 1.0 / q);
        }
    }
    return rgb_gray(0.0);
}

const phase_t *medium_phase(const medium_t *m)
{
    return m->phase;
}

bool medium_samples_emitters(const medium_t *m)
{
    return m->sample_emitters;
}

void medium_destroy(medium_t *m)
{
    if (!m)
        return;
    volume_destroy(m->sigma_t);
    volume_destroy(m->albedo);
    phase_destroy(m->phase);
    free(m);
}

medium_t *medium_create_common(scene_obj *o, bool homogeneous, char *err, size_t errlen)
{
    medium_t *m = calloc(1, sizeof *m);
    if (!m) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    m->scale = scene_obj_float(o, "scale", 1.0);
    m->sample_emitters = scene_obj_bool(o, "sample_emitters", true);
    (void)scene_obj_bool(o, "has_spectral_extinction", true); /* RGB: every channel is tracked anyway */
    m->homogeneous = homogeneous;
    if (!(m->scale >= 0.0 && isfinite(m->scale))) {
        scene_obj_error(o, err, errlen, "scale must be finite and not negative");
        goto fail;
    }
    if (!(m->sigma_t = volume_of_param(o, "sigma_t", rgb_gray(1.0), err, errlen)) ||
        !(m->albedo = volume_of_param(o, "albedo", rgb_gray(0.75), err, errlen)) ||
        !(m->phase = phase_create(scene_obj_child(o, SCENE_PHASE), o, err, errlen)))
        goto fail;
    if (homogeneous && !volume_is_constant(m->sigma_t)) {
        scene_obj_error(o, err, errlen, "sigma_t of a homogeneous medium must be constant (a heterogeneous one takes a grid)");
        goto fail;
    }
    m->majorant = m->scale * volume_max(m->sigma_t);
    if (!isfinite(m->majorant)) {
        scene_obj_error(o, err, errlen, "sigma_t times scale is not finite");
        goto fail;
    }
    return m;
fail:
    medium_destroy(m);
    return NULL;
}

int medium_set_param(medium_set *set, scene_obj *o, const char *name, const medium_t **out, char *err,
                     size_t errlen)
{
    *out = NULL;
    scene_obj *mo = scene_obj_texture(o, name);
    if (!mo)
        return 0;
    if (mo->cls != SCENE_MEDIUM || !medium_plugin_find(mo->type))
        return scene_obj_error(o, err, errlen, "%s must be a <medium>", name);
    return medium_set_get(set, mo, out, err, errlen);
}

int medium_set_get(medium_set *set, scene_obj *mo, const medium_t **out, char *err, size_t errlen)
{
    const medium_plugin *plugin = medium_plugin_find(mo->type);
    medium_t *m = scene_obj_map_find(&set->built, mo);
    if (!m) {
        if (!(m = plugin->create(mo, err, errlen)))
            return -1;
        if (scene_obj_map_add(&set->built, mo, m) != 0) {
            medium_destroy(m);
            return scene_obj_error(mo, err, errlen, "out of memory");
        }
    }
    *out = m;
    return 0;
}

void medium_set_free(medium_set *set)
{
    for (int i = set->built.count - 1; i >= 0; i--)
        medium_destroy(set->built.values[i]);
    scene_obj_map_free(&set->built);
}
