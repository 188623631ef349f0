/* Mitsuba's `direct` integrator: the light reaching the first surface
 * straight from the emitters, by emitter_samples samples of the emitters
 * (one chosen uniformly each time) and bsdf_samples samples of the BSDF,
 * combined by the power heuristic over the two strategies' sample counts:
 * a sample of strategy s with density p_s gets the weight
 *   (f_s p_s)^2 / ((f_e p_e)^2 + (f_b p_b)^2) / n_s,
 * f_s = n_s / (n_e + n_b) its share of the samples (delta lights and
 * delta lobes, which only one strategy can produce: weight 1 / n_s).
 * Emitters seen directly are added, unless hide_emitters, which looks
 * through area emitters as Mitsuba does. Shadow rays stop at any surface. */
#include <math.h>

#include "integrators/integrator_impl.h"

typedef struct {
    int emitter_samples, bsdf_samples;
    double frac_emitter, frac_bsdf; /* each strategy's share of the samples */
    bool hide_emitters;
} direct_data;

/* Mitsuba's power heuristic: a^2 / (a^2 + b^2), 0 where undefined. */
static double power_weight(double a, double b)
{
    double w = a * a / (a * a + b * b);
    return isfinite(w) ? w : 0.0;
}

static rgb emitter_strategy(const direct_data *d, const integrator_scene *sc, const surface_hit *hit,
                            const bsdf_query *q, sampler_stream *smp)
{
    const bsdf_t *b = hit->shape->bsdf;
    int n = sc->emitters->count;
    rgb sum = rgb_gray(0.0);
    for (int i = 0; i < d->emitter_samples; i++) {
        int k = (int)(sampler_next_1d(smp) * n);
        k = k < n ? k : n - 1;
        double uz = sampler_next_1d(smp);
        vec2 uxy = sampler_next_2d(smp);
        emitter_sample_rec es;
        if (!emitter_sample(sc->emitters->items[k], hit->p, v3(uxy.x, uxy.y, uz), &es) || !(es.pdf > 0.0))
            continue;
        vec3 wo = frame3_to_local(hit->sh, es.wi);
        rgb f = bsdf_eval(b, q, wo);
        if (rgb_is_black(f) || rgb_is_black(es.value) || !integrator_unoccluded(sc->shapes, hit, &es))
            continue;
        double pdf = es.pdf / n;
        double w = es.delta ? 1.0 : power_weight(pdf * d->frac_emitter, bsdf_pdf(b, q, wo) * d->frac_bsdf);
        sum = rgb_add(sum, rgb_scale(rgb_mul(f, es.value), w / (pdf * d->emitter_samples)));
    }
    return sum;
}

static rgb bsdf_strategy(const direct_data *d, const integrator_scene *sc, const surface_hit *hit,
                         const bsdf_query *q, sampler_stream *smp)
{
    const emitter_list *emitters = sc->emitters;
    double sel = emitters->count > 0 ? 1.0 / emitters->count : 0.0;
    rgb sum = rgb_gray(0.0);
    for (int i = 0; i < d->bsdf_samples; i++) {
        double u1 = sampler_next_1d(smp);
        vec2 u2 = sampler_next_2d(smp);
        bsdf_sample_rec bs;
        if (!bsdf_sample(hit->shape->bsdf, q, u1, u2, &bs) || rgb_is_black(bs.weight))
            continue;
        ray3 r = integrator_spawn(hit, v3_norm(frame3_to_world(hit->sh, bs.wo)));
        surface_hit h2;
        rgb le;
        double pdf_emitter;
        if (shape_list_intersect(sc->shapes, &r, 0.0, INFINITY, &h2)) {
            if (!h2.shape->emitter)
                continue;
            le = emitter_eval_hit(h2.shape->emitter, &h2, r.d);
            pdf_emitter = sel * emitter_pdf_hit(h2.shape->emitter, hit->p, &h2, r.d);
        } else {
            if (!emitters->env)
                continue;
            le = emitter_eval_env(emitters->env, r.d);
            pdf_emitter = sel * emitter_pdf_env(emitters->env, r.d);
        }
        if (bs.sampled_type & BSDF_DELTA)
            pdf_emitter = 0.0;
        double w = power_weight(bs.pdf * d->frac_bsdf, pdf_emitter * d->frac_emitter);
        sum = rgb_add(sum, rgb_scale(rgb_mul(bs.weight, le), w / d->bsdf_samples));
    }
    return sum;
}

static rgb direct_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray0, double tmin, double tmax,
                     sampler_stream *smp, double *aov)
{
    const direct_data *d = in->data;
    ray3 ray = *ray0;
    surface_hit hit;
    bool found = shape_list_intersect(sc->shapes, &ray, tmin, tmax, &hit);
    rgb L = rgb_gray(0.0);
    if (d->hide_emitters) {
        /* Through every area emitter along the ray. */
        while (found && hit.shape->emitter) {
            ray = integrator_spawn(&hit, ray.d);
            found = shape_list_intersect(sc->shapes, &ray, 0.0, INFINITY, &hit);
        }
    } else if (found && hit.shape->emitter) {
        L = emitter_eval_hit(hit.shape->emitter, &hit, ray.d);
    } else if (!found && sc->emitters->env) {
        L = emitter_eval_env(sc->emitters->env, ray.d);
    }
    if (aov) {
        integrator_clear_aovs(aov, found);
        if (found)
            integrator_first_hit_aovs(aov, &hit);
    }
    if (!found)
        return L;
    bsdf_query q = shape_bsdf_query(&hit, ray.d, TRANSPORT_RADIANCE);
    /* The same dimensions for the same purpose in every sample (samplers.h):
     * 4 per emitter sample, then 3 per BSDF sample. */
    sampler_seek(smp, SAMPLER_DIM_INTEGRATOR);
    if ((bsdf_flags(hit.shape->bsdf) & BSDF_SMOOTH) && sc->emitters->count > 0)
        L = rgb_add(L, emitter_strategy(d, sc, &hit, &q, smp));
    sampler_seek(smp, (uint32_t)(SAMPLER_DIM_INTEGRATOR + 4 * d->emitter_samples));
    L = rgb_add(L, bsdf_strategy(d, sc, &hit, &q, smp));
    if (!isfinite(L.r) || !isfinite(L.g) || !isfinite(L.b))
        return rgb_gray(0.0);
    return L;
}

static const integrator_ops direct_ops = {direct_li, NULL};

static integrator_t *direct_create(scene_obj *o, char *err, size_t errlen)
{
    if (scene_obj_has(o, "shading_samples") && (scene_obj_has(o, "emitter_samples") || scene_obj_has(o, "bsdf_samples"))) {
        scene_obj_error(o, err, errlen, "<integrator type=\"direct\">: give shading_samples or emitter_samples and "
                        "bsdf_samples, not both");
        return NULL;
    }
    long long shading = scene_obj_int(o, "shading_samples", 1);
    long long ne = scene_obj_int(o, "emitter_samples", shading), nb = scene_obj_int(o, "bsdf_samples", shading);
    if (ne < 0 || nb < 0 || ne + nb == 0 || ne > 100000 || nb > 100000) {
        scene_obj_error(o, err, errlen, "<integrator type=\"direct\">: emitter_samples and bsdf_samples must be "
                        "0 to 100000, not both 0 (got %lld and %lld)", ne, nb);
        return NULL;
    }
    direct_data d = {(int)ne, (int)nb, (double)ne / (double)(ne + nb), (double)nb / (double)(ne + nb),
                     scene_obj_bool(o, "hide_emitters", false)};
    return integrator_alloc(o, &direct_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl direct_params[] = {
    {"shading_samples", PARAM_INT, 0, NULL},
    {"emitter_samples", PARAM_INT, 0, NULL},
    {"bsdf_samples", PARAM_INT, 0, NULL},
    {"hide_emitters", PARAM_BOOL, 0, NULL},
    {NULL, 0, 0, NULL},
};

const integrator_plugin integrator_direct = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "direct", .params = direct_params},
    .create = direct_create,
};
