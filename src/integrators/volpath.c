/* The `volpath` integrator (Mitsuba 3's): path tracing through participating
 * media (src/media). A ray is in the medium of the last shape boundary it
 * crossed (the shape's interior behind its normal, exterior in front; a
 * shape naming neither leaves it unchanged), none from the camera. In a
 * medium the free flight to the next surface is tracked (media.h): the path
 * scatters there by the medium's phase function, is absorbed, or reaches
 * the surface, which scatters it as in `path`.
 *
 * Next-event estimation at every surface vertex with a smooth lobe and at
 * every medium vertex (unless the medium says sample_emitters false), with
 * the power heuristic against BSDF or phase sampling; shadow rays take the
 * media's transmittance and cross thin sheets (null, mask, thindielectric:
 * BSDF_STRAIGHT_TRANSMISSION) weighted by their straight transmittance,
 * where they change medium as a path does. Crossing such a sheet straight is
 * not a vertex: it counts toward neither max_depth nor the roulette, and
 * the last real vertex's density stays the MIS reference. max_depth counts
 * scattering vertices as `path` counts segments (1: emitters seen directly,
 * 2: single scattering, -1: unbounded); Russian roulette from rr_depth with
 * survival probability min(max(beta) eta^2, 0.95). */
#include <math.h>

#include "integrators/integrator_impl.h"
#include "media/media.h"

typedef struct {
    int max_depth, rr_depth;
    bool hide_emitters;
} volpath_data;

/* Straight crossings of sheets between two vertices beyond which a path
 * (or a shadow ray) is given up (stacks of coplanar sheets). */
enum { MAX_CROSSINGS = 256 };

/* The sample dimensions of each vertex, from SAMPLER_DIM_INTEGRATOR + depth *
 * DIMS_PER_VERTEX. The tracking through media and every choice after the
 * first straight crossing draw from the vertex's own stream (DIM_STREAM
 * seeds it): their count varies from path to path. */
enum {
    DIM_STREAM = 0,        /* 1D */
    DIM_LIGHT_PICK = 1,    /* 1D */
    DIM_LIGHT_POINT = 2,   /* 2D */
    DIM_LOBE = 4,          /* 1D */
    DIM_DIRECTION = 5,     /* 2D */
    DIM_ROULETTE = 7,      /* 1D */
    DIMS_PER_VERTEX = 8,
};

/* Where a path vertex draws its numbers: the sampler's dimensions of its
 * depth, or its stream once it has crossed a sheet. */
typedef struct {
    sampler_stream *smp;
    rng_t rng;
    int depth;
    bool own; /* draw from rng */
} vertex_numbers;

static void vertex_start(vertex_numbers *v, sampler_stream *smp, int depth)
{
    v->smp = smp;
    v->depth = depth;
    v->own = false;
    sampler_seek(smp, (uint32_t)(SAMPLER_DIM_INTEGRATOR + depth * DIMS_PER_VERTEX + DIM_STREAM));
    rng_seed(&v->rng, (uint64_t)(sampler_next_1d(smp) * 0x1p53), (uint64_t)depth);
}

static double vertex_1d(vertex_numbers *v, int which)
{
    if (v->own)
        return rng_next_double(&v->rng);
    sampler_seek(v->smp, (uint32_t)(SAMPLER_DIM_INTEGRATOR + v->depth * DIMS_PER_VERTEX + which));
    return sampler_next_1d(v->smp);
}

static vec2 vertex_2d(vertex_numbers *v, int which)
{
    if (v->own) {
        double x = rng_next_double(&v->rng);
        return v2(x, rng_next_double(&v->rng));
    }
    sampler_seek(v->smp, (uint32_t)(SAMPLER_DIM_INTEGRATOR + v->depth * DIMS_PER_VERTEX + which));
    return sampler_next_2d(v->smp);
}

/* The medium a ray leaving hit along w travels in. */
static const medium_t *medium_after(const surface_hit *hit, vec3 w, const medium_t *current)
{
    const shape_t *s = hit->shape;
    if (!s->interior && !s->exterior)
        return current;
    return v3_dot(hit->ng, w) > 0.0 ? s->exterior : s->interior;
}

/* A scattering vertex: a surface hit with its BSDF query, or a point in a
 * medium (hit NULL) with its phase function. */
typedef struct {
    const surface_hit *hit;
    const bsdf_query *q;
    const phase_t *phase;
    vec3 p, d; /* the vertex and the direction the path arrived in */
    const medium_t *medium; /* where the vertex is (a surface: on the side the path came from) */
} vertex;

/* The vertex's scattering toward the unit world direction w (BSDF times
 * cosine, or phase function) and its density of sampling w. */
static rgb vertex_eval(const vertex *v, vec3 w, double *pdf)
{
    if (!v->hit) {
        double f = phase_eval(v->phase, v->d, w);
        *pdf = f;
        return rgb_gray(f);
    }
    const bsdf_t *b = v->hit->shape->bsdf;
    vec3 wo = frame3_to_local(v->hit->sh, w);
    *pdf = bsdf_pdf(b, v->q, wo);
    return bsdf_eval(b, v->q, wo);
}

/* The fraction of the emitter sample's light that reaches the vertex:
 * through media, crossing sheets, stopped by anything else. */
static rgb shadow_transmittance(const shape_list *shapes, const vertex *v, const emitter_sample_rec *es, rng_t *rng)
{
    bool infinite = isinf(es->dist);
    vec3 target = es->p;
    if (!infinite && es->eps > 0.0) /* lift the light point toward the receiver */
        target = v3_add(target, v3_scale(es->n, v3_dot(es->n, es->wi) < 0.0 ? es->eps : -es->eps));
    ray3 r = v->hit ? integrator_spawn(v->hit, es->wi) : (ray3){v->p, es->wi};
    const medium_t *med = v->hit ? medium_after(v->hit, es->wi, v->medium) : v->medium;
    rgb tr = rgb_gray(1.0);
    for (int crossed = 0; crossed <= MAX_CROSSINGS; crossed++) {
        double tmax = INFINITY;
        if (!infinite) {
            vec3 to = v3_sub(target, r.o);
            tmax = v3_len(to) * (1.0 - 1e-7);
            r.d = v3_scale(to, 1.0 / v3_len(to));
        }
        surface_hit x;
        bool found = shape_list_intersect(shapes, &r, 0.0, tmax, &x);
        if (med)
            tr = rgb_mul(tr, medium_transmittance(med, &r, found ? x.t : tmax, rng));
        if (!found || rgb_is_black(tr))
            return tr;
        const bsdf_t *b = x.shape->bsdf;
        if (!(bsdf_flags(b) & BSDF_STRAIGHT_TRANSMISSION))
            return rgb_gray(0.0);
        bsdf_query q = shape_bsdf_query(&x, r.d, TRANSPORT_RADIANCE);
        tr = rgb_mul(tr, bsdf_straight_transmittance(b, &q));
        med = medium_after(&x, r.d, med);
        r = integrator_spawn(&x, r.d);
    }
    return rgb_gray(0.0);
}

static rgb next_event(const integrator_scene *sc, const vertex *v, vertex_numbers *num)
{
    emitter_ref ref = {v->p, v->hit ? v->hit->ng : v3(0.0, 0.0, 0.0)};
    double pmf, part;
    const emitter_t *e = emitter_list_pick(sc->emitters, &ref, vertex_1d(num, DIM_LIGHT_PICK), &pmf, &part);
    vec2 uxy = vertex_2d(num, DIM_LIGHT_POINT);
    emitter_sample_rec es;
    if (!e || !emitter_sample(e, v->p, v3(uxy.x, uxy.y, part), &es) || !(es.pdf > 0.0) || rgb_is_black(es.value))
        return rgb_gray(0.0);
    double pdf_s;
    rgb f = vertex_eval(v, es.wi, &pdf_s);
    if (rgb_is_black(f))
        return rgb_gray(0.0);
    rgb tr = shadow_transmittance(sc->shapes, v, &es, &num->rng);
    if (rgb_is_black(tr))
        return rgb_gray(0.0);
    double pdf_l = es.pdf * pmf;
    double w = es.delta ? 1.0 : mis_power_heuristic(pdf_l, pdf_s);
    return rgb_scale(rgb_mul(rgb_mul(f, tr), es.value), w / pdf_l);
}

/* The state of a path between vertices. */
typedef struct {
    rgb L, beta;
    double eta, prev_pdf;
    bool prev_delta;   /* no emitter sampling at the last vertex: emitters hit get weight 1 */
    emitter_ref prev;  /* the last vertex, as next-event estimation saw it */
} path_state;

/* Light of an emitter the path reached, MIS-weighted against the last
 * vertex's emitter sampling (pdf_l: that strategy's density, pmf included). */
static void add_emission(path_state *ps, rgb le, double pdf_l)
{
    double w = ps->prev_delta ? 1.0 : mis_power_heuristic(ps->prev_pdf, pdf_l);
    ps->L = rgb_add(ps->L, rgb_scale(rgb_mul(ps->beta, le), w));
}

/* Russian roulette after vertex num: false when the path ends. */
static bool roulette(const volpath_data *pd, path_state *ps, vertex_numbers *num)
{
    double beta_max = rgb_max(ps->beta) * ps->eta * ps->eta;
    if (num->depth + 1 >= pd->rr_depth) {
        double survive = fmin(beta_max, 0.95);
        if (vertex_1d(num, DIM_ROULETTE) >= survive)
            return false;
        ps->beta = rgb_scale(ps->beta, 1.0 / survive);
    }
    return beta_max > 0.0;
}

static rgb volpath_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray0, double tmin, double tmax,
                      sampler_stream *smp, double *aov)
{
    const volpath_data *pd = in->data;
    const emitter_list *emitters = sc->emitters;
    double len = v3_len(ray0->d);
    ray3 ray = {ray0->o, v3_scale(ray0->d, 1.0 / len)};
    double t0 = tmin * len, t1 = tmax * len;
    path_state ps = {rgb_gray(0.0), rgb_gray(1.0), 1.0, 1.0, true, {ray.o, v3(0.0, 0.0, 0.0)}};
    const medium_t *med = sc->camera_medium;
    if (aov)
        integrator_clear_aovs(aov, emitters->env && !pd->hide_emitters); /* Mitsuba's valid ray */
    vertex_numbers num;
    vertex_start(&num, smp, 0);
    for (int crossings = 0; crossings <= MAX_CROSSINGS;) {
        int depth = num.depth;
        bool show = !(depth == 0 && pd->hide_emitters);
        surface_hit hit;
        bool found = shape_list_intersect(sc->shapes, &ray, t0, t1, &hit);
        if (med) {
            double t;
            medium_event ev = medium_sample(med, &ray, found ? hit.t : t1, &num.rng, &ps.beta, &t);
            if (ev == MEDIUM_ABSORBED)
                break;
            if (ev == MEDIUM_SCATTERED) {
                if (aov)
                    aov[INTEGRATOR_AOV_ALPHA] = 1.0;
                if (pd->max_depth >= 0 && depth + 1 >= pd->max_depth)
                    break;
                vertex v = {NULL, NULL, medium_phase(med), v3_add(ray.o, v3_scale(ray.d, t)), ray.d, med};
                bool nee = medium_samples_emitters(med) && emitters->count > 0;
                if (nee)
                    ps.L = rgb_add(ps.L, rgb_mul(ps.beta, next_event(sc, &v, &num)));
                double pdf;
                vec3 w = phase_sample(v.phase, ray.d, vertex_2d(&num, DIM_DIRECTION), &pdf);
                ps.prev_delta = !nee, ps.prev_pdf = pdf, ps.prev = (emitter_ref){v.p, v3(0.0, 0.0, 0.0)};
                ray = (ray3){v.p, w};
                t0 = 0.0, t1 = INFINITY;
                if (!roulette(pd, &ps, &num))
                    break;
                vertex_start(&num, smp, depth + 1);
                crossings = 0;
                continue;
            }
        }
        if (!found) {
            if (emitters->env && show) {
                const emitter_t *e = emitters->env;
                add_emission(&ps, emitter_eval_env(e, ray.d),
                             emitter_list_pmf(emitters, &ps.prev, e) * emitter_pdf_env(e, ray.d));
            }
            break;
        }
        const shape_t *sh = hit.shape;
        if (depth == 0 && crossings == 0 && aov)
            integrator_first_hit_aovs(aov, &hit);
        if (sh->emitter && show) {
            const emitter_t *e = sh->emitter;
            rgb le = emitter_eval_hit(e, &hit, ray.d);
            if (!rgb_is_black(le))
                add_emission(&ps, le, emitter_list_pmf(emitters, &ps.prev, e) * emitter_pdf_hit(e, ps.prev.p, &hit, ray.d));
        }
        if (pd->max_depth >= 0 && depth + 1 >= pd->max_depth) {
            if (aov && sh->emitter && !pd->hide_emitters)
                aov[INTEGRATOR_AOV_ALPHA] = 1.0;
            break;
        }
        bsdf_query q = shape_bsdf_query(&hit, ray.d, TRANSPORT_RADIANCE);
        vertex v = {&hit, &q, NULL, hit.p, ray.d, med};
        bool nee = (bsdf_flags(sh->bsdf) & BSDF_SMOOTH) && emitters->count > 0;
        if (nee)
            ps.L = rgb_add(ps.L, rgb_mul(ps.beta, next_event(sc, &v, &num)));
        bsdf_sample_rec bs;
        double u1 = vertex_1d(&num, DIM_LOBE);
        bool sampled = bsdf_sample(sh->bsdf, &q, u1, vertex_2d(&num, DIM_DIRECTION), &bs);
        if (aov && !(bs.sampled_type & BSDF_NULL))
            aov[INTEGRATOR_AOV_ALPHA] = 1.0;
        if (!sampled || rgb_is_black(bs.weight))
            break;
        ps.beta = rgb_mul(ps.beta, bs.weight);
        ps.eta *= bs.eta;
        vec3 w = v3_norm(frame3_to_world(hit.sh, bs.wo));
        med = medium_after(&hit, w, med);
        ray = integrator_spawn(&hit, w);
        t0 = 0.0, t1 = INFINITY;
        if (bs.sampled_type & BSDF_STRAIGHT_TRANSMISSION) { /* not a vertex: the same numbers go on */
            crossings++;
            num.own = true;
            continue;
        }
        ps.prev_delta = (bs.sampled_type & BSDF_DELTA) != 0, ps.prev_pdf = bs.pdf;
        ps.prev = (emitter_ref){hit.p, hit.ng};
        if (!roulette(pd, &ps, &num))
            break;
        vertex_start(&num, smp, depth + 1);
        crossings = 0;
    }
    rgb L = ps.L;
    if (!isfinite(L.r) || !isfinite(L.g) || !isfinite(L.b))
        return rgb_gray(0.0);
    return L;
}

static const integrator_ops volpath_ops = {volpath_li, NULL};

integrator_t *integrator_volpath_create(scene_obj *o, char *err, size_t errlen)
{
    long long md = scene_obj_int(o, "max_depth", -1), rr = scene_obj_int(o, "rr_depth", 5);
    if (md < -1 || md > 1000000 || rr < 1 || rr > 1000000) {
        scene_obj_error(o, err, errlen, "max_depth must be -1 or >= 0 and rr_depth >= 1");
        return NULL;
    }
    volpath_data d = {(int)md, (int)rr, scene_obj_bool(o, "hide_emitters", false)};
    return integrator_alloc(o, &volpath_ops, &d, sizeof d, err, errlen);
}

const scene_param_decl integrator_volpath_params[] = {
    {"max_depth", PARAM_INT, 0, NULL},
    {"rr_depth", PARAM_INT, 0, NULL},
    {"hide_emitters", PARAM_BOOL, 0, NULL},
    {NULL, 0, 0, NULL},
};

const integrator_plugin integrator_volpath = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "volpath", .params = integrator_volpath_params},
    .create = integrator_volpath_create,
};
