/* The `path` integrator (Mitsuba 3's): unidirectional path tracing with
 * next-event estimation at every non-delta vertex and multiple importance
 * sampling (power heuristic) between emitter and BSDF sampling. Shadow rays
 * cross thin sheets (thindielectric: light passes undeviated) weighted by
 * their transmittance, where Mitsuba stops them; paths sampled straight
 * through a sheet are weighted against that estimator (docs/rendering.md). Emitters
 * are chosen uniformly. max_depth counts path segments (1: emitters seen
 * directly, 2: direct lighting, -1: unbounded); Russian roulette starts once
 * depth >= rr_depth with survival probability min(max(beta) eta^2, 0.95). */
#include <math.h>

#include "celadon/render.h"
#include "render/scene_impl.h"

/* A ray leaving hit toward w, lifted off the surface on w's side. */
static ray3 spawn(const surface_hit *h, vec3 w)
{
    double side = v3_dot(h->ng, w) >= 0.0 ? h->eps : -h->eps;
    return (ray3){v3_add(h->p, v3_scale(h->ng, side)), w};
}

/* The shadow ray from h toward the emitter sample: to the (lifted) light
 * point with t in [0, 1), or along its direction for a light at infinity. */
static ray3 shadow_ray(const surface_hit *h, const emitter_sample_rec *es, vec3 target, bool infinite)
{
    ray3 r = spawn(h, es->wi);
    if (!infinite)
        r.d = v3_sub(target, r.o);
    return r;
}

/* The fraction of the emitter sample's light that reaches h: 0 behind an
 * opaque surface; crossing thin sheets (BSDF_STRAIGHT_TRANSMISSION), their
 * straight transmittance each, at most max_sheets of them (-1: any number),
 * so that the emitter stays within the path's max_depth, as a BSDF-sampled
 * path through the same sheets would. A scene without sheets asks the
 * cheaper any-hit question; with sheets, each segment is traced once to its
 * nearest hit. */
static rgb transmittance(const struct scene *s, const surface_hit *h, const emitter_sample_rec *es, int max_sheets)
{
    bool infinite = isinf(es->dist);
    vec3 target = es->p;
    if (!infinite && es->eps > 0.0) /* lift the light point toward the receiver */
        target = v3_add(target, v3_scale(es->n, v3_dot(es->n, es->wi) < 0.0 ? es->eps : -es->eps));
    double tmax = infinite ? INFINITY : 1.0 - 1e-7;
    ray3 r = shadow_ray(h, es, target, infinite);
    if (!s->straight_shadows)
        return rgb_gray(scene_occluded(s, &r, 0.0, tmax) ? 0.0 : 1.0);
    rgb tr = rgb_gray(1.0);
    for (int crossed = 0; max_sheets < 0 || crossed <= max_sheets; crossed++) {
        surface_hit x;
        if (!scene_intersect(s, &r, 0.0, tmax, &x))
            return tr;
        const bsdf_t *b = s->shapes[x.shape].bsdf;
        if (crossed == max_sheets || !(bsdf_flags(b) & BSDF_STRAIGHT_TRANSMISSION))
            return rgb_gray(0.0);
        bsdf_query q = {frame3_to_local(x.sh, v3_neg(es->wi)), x.uv, TRANSPORT_RADIANCE};
        tr = rgb_mul(tr, bsdf_straight_transmittance(b, &q));
        if (rgb_is_black(tr))
            return tr;
        r = shadow_ray(&x, es, target, infinite);
    }
    return rgb_gray(0.0);
}

static rgb next_event(const struct scene *s, const surface_hit *h, const bsdf_t *b, const bsdf_query *q, rng_t *rng,
                      int max_sheets)
{
    int n = s->nemitters;
    int k = (int)(rng_next_double(rng) * n);
    k = k < n ? k : n - 1;
    vec3 u = v3(rng_next_double(rng), rng_next_double(rng), rng_next_double(rng));
    emitter_sample_rec es;
    if (!emitter_sample(s, &s->emitters[k], h->p, u, &es) || !(es.pdf > 0.0) || rgb_is_black(es.value))
        return rgb_gray(0.0);
    vec3 wo = frame3_to_local(h->sh, es.wi);
    rgb f = bsdf_eval(b, q, wo);
    if (rgb_is_black(f))
        return rgb_gray(0.0);
    rgb tr = transmittance(s, h, &es, max_sheets);
    if (rgb_is_black(tr))
        return rgb_gray(0.0);
    double pdf_l = es.pdf / n;
    double w = es.delta ? 1.0 : mis_power_heuristic(pdf_l, bsdf_pdf(b, q, wo));
    return rgb_scale(rgb_mul(rgb_mul(f, tr), es.value), w / pdf_l);
}

rgb integrator_path_li(const scene_t *s, const ray3 *ray0, double tmin, double tmax, rng_t *rng, double *aov)
{
    rgb L = rgb_gray(0.0), beta = rgb_gray(1.0);
    double eta = 1.0, prev_pdf = 1.0, t0 = tmin, t1 = tmax;
    bool prev_delta = true;
    ray3 ray = *ray0;
    vec3 prev_p = ray.o;
    double sel = s->nemitters > 0 ? 1.0 / s->nemitters : 0.0;
    if (aov)
        for (int i = 0; i < 7; i++)
            aov[i] = 0.0;
    for (int depth = 0;; depth++) {
        surface_hit hit;
        bool found = scene_intersect(s, &ray, t0, t1, &hit);
        bool show = !(depth == 0 && s->hide_emitters);
        if (!found) {
            if (s->env >= 0 && show) {
                const emitter_t *e = &s->emitters[s->env];
                double w = prev_delta ? 1.0 : mis_power_heuristic(prev_pdf, sel * emitter_env_pdf(e, ray.d));
                L = rgb_add(L, rgb_scale(rgb_mul(beta, emitter_env_eval(e, ray.d)), w));
            }
            break;
        }
        const shape_t *sh = &s->shapes[hit.shape];
        if (depth == 0 && aov) {
            aov[0] = hit.t;
            aov[1] = hit.sh.n.x, aov[2] = hit.sh.n.y, aov[3] = hit.sh.n.z;
            rgb a = bsdf_albedo(sh->bsdf, hit.uv);
            aov[4] = a.r, aov[5] = a.g, aov[6] = a.b;
        }
        if (sh->emitter >= 0 && show) {
            const emitter_t *e = &s->emitters[sh->emitter];
            rgb le = emitter_area_eval(s, e, &hit, ray.d);
            if (!rgb_is_black(le)) {
                double w = prev_delta ? 1.0
                                      : mis_power_heuristic(prev_pdf, sel * emitter_area_pdf(s, e, prev_p, &hit, ray.d));
                L = rgb_add(L, rgb_scale(rgb_mul(beta, le), w));
            }
        }
        if (s->max_depth >= 0 && depth + 1 >= s->max_depth)
            break;

        bsdf_query q = {frame3_to_local(hit.sh, v3_neg(ray.d)), hit.uv, TRANSPORT_RADIANCE};
        if ((bsdf_flags(sh->bsdf) & BSDF_SMOOTH) && s->nemitters > 0) {
            /* The emitter at depth + 1 + sheets must not pass max_depth - 1. */
            int max_sheets = s->max_depth < 0 ? -1 : s->max_depth - 2 - depth;
            L = rgb_add(L, rgb_mul(beta, next_event(s, &hit, sh->bsdf, &q, rng, max_sheets)));
        }

        bsdf_sample_rec bs;
        double u1 = rng_next_double(rng);
        vec2 u2 = v2(rng_next_double(rng), rng_next_double(rng));
        if (!bsdf_sample(sh->bsdf, &q, u1, u2, &bs) || rgb_is_black(bs.weight))
            break;
        beta = rgb_mul(beta, bs.weight);
        eta *= bs.eta;
        /* Straight through a thin sheet, the path keeps the last scattering
         * vertex's density for MIS: next-event estimation from that vertex
         * saw the emitter through the sheet too (transmittance above). */
        if (!((bs.sampled_type & BSDF_DELTA_TRANSMISSION) && (bsdf_flags(sh->bsdf) & BSDF_STRAIGHT_TRANSMISSION))) {
            prev_delta = (bs.sampled_type & BSDF_DELTA) != 0;
            prev_pdf = bs.pdf;
            prev_p = hit.p;
        }
        ray = spawn(&hit, v3_norm(frame3_to_world(hit.sh, bs.wo)));
        t0 = 0.0, t1 = INFINITY;

        double beta_max = rgb_max(beta) * eta * eta;
        if (depth + 1 >= s->rr_depth) {
            double survive = fmin(beta_max, 0.95);
            if (rng_next_double(rng) >= survive)
                break;
            beta = rgb_scale(beta, 1.0 / survive);
        }
        if (!(beta_max > 0.0))
            break;
    }
    if (!isfinite(L.r) || !isfinite(L.g) || !isfinite(L.b))
        return rgb_gray(0.0);
    return L;
}
