/* The `path` integrator (Mitsuba 3's): unidirectional path tracing with
 * next-event estimation at every non-delta vertex and multiple importance
 * sampling (power heuristic) between emitter and BSDF sampling. Shadow rays
 * cross thin sheets (thindielectric: light passes undeviated) weighted by
 * their transmittance, where Mitsuba stops them; paths sampled straight
 * through a sheet are weighted against that estimator (docs/rendering.md). Emitters
 * are picked by their estimated contribution (emitter_list_pick). max_depth counts path segments (1: emitters seen
 * directly, 2: direct lighting, -1: unbounded); Russian roulette starts once
 * depth >= rr_depth with survival probability min(max(beta) eta^2, 0.95). */
#include <math.h>

#include "integrators/integrator_impl.h"

typedef struct {
    int max_depth, rr_depth;
    bool hide_emitters;
} path_data;

/* The sample dimensions of the vertex at each depth, in this order from
 * SAMPLER_DIM_INTEGRATOR + depth * DIMS_PER_VERTEX, used for the same
 * purpose at every depth of every path whatever it does (skipped numbers are
 * never drawn), so a stratifying sampler stratifies each (samplers.h). */
enum {
    DIM_LIGHT_PICK = 0,     /* 1D: which emitter, and (its remainder) which part of it (a mesh's triangle) */
    DIM_LIGHT_POINT = 1,    /* 2D: where on it */
    DIM_BSDF_LOBE = 3,      /* 1D */
    DIM_BSDF_DIRECTION = 4, /* 2D */
    DIM_ROULETTE = 6,       /* 1D */
    DIMS_PER_VERTEX = 7,
};

static uint32_t vertex_dim(int depth, int which)
{
    return (uint32_t)(SAMPLER_DIM_INTEGRATOR + depth * DIMS_PER_VERTEX + which);
}

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
static rgb transmittance(const shape_list *shapes, const surface_hit *h, const emitter_sample_rec *es, int max_sheets)
{
    bool infinite = isinf(es->dist);
    vec3 target = es->p;
    if (!infinite && es->eps > 0.0) /* lift the light point toward the receiver */
        target = v3_add(target, v3_scale(es->n, v3_dot(es->n, es->wi) < 0.0 ? es->eps : -es->eps));
    double tmax = infinite ? INFINITY : 1.0 - 1e-7;
    ray3 r = shadow_ray(h, es, target, infinite);
    if (!shapes->straight_shadows)
        return rgb_gray(shape_list_occluded(shapes, &r, 0.0, tmax) ? 0.0 : 1.0);
    rgb tr = rgb_gray(1.0);
    for (int crossed = 0; max_sheets < 0 || crossed <= max_sheets; crossed++) {
        surface_hit x;
        if (!shape_list_intersect(shapes, &r, 0.0, tmax, &x))
            return tr;
        const bsdf_t *b = x.shape->bsdf;
        if (crossed == max_sheets || !(bsdf_flags(b) & BSDF_STRAIGHT_TRANSMISSION))
            return rgb_gray(0.0);
        bsdf_query q = shape_bsdf_query(&x, es->wi, TRANSPORT_RADIANCE);
        tr = rgb_mul(tr, bsdf_straight_transmittance(b, &q));
        if (rgb_is_black(tr))
            return tr;
        r = shadow_ray(&x, es, target, infinite);
    }
    return rgb_gray(0.0);
}

static rgb next_event(const integrator_scene *sc, const surface_hit *h, const bsdf_t *b, const bsdf_query *q,
                      sampler_stream *smp, int depth, int max_sheets)
{
    emitter_ref ref = {h->p, h->ng};
    double pmf, part;
    /* A light that cannot reach h gets no numbers drawn (each dimension's
     * numbers are the same whatever was drawn before: samplers.h), but for
     * a sampler whose numbers come in the order drawn: it draws them all. */
    bool in_order = smp->sampler->in_order;
    const emitter_t *only = emitter_list_only(sc->emitters);
    bool away = only && emitter_faces_away(only, h->p);
    if (away && !in_order)
        return rgb_gray(0.0);
    sampler_seek(smp, vertex_dim(depth, DIM_LIGHT_PICK));
    const emitter_t *e = emitter_list_pick(sc->emitters, &ref, sampler_next_1d(smp), &pmf, &part);
    if (e && !only)
        away = emitter_faces_away(e, h->p);
    if ((!e || away) && !in_order)
        return rgb_gray(0.0);
    sampler_seek(smp, vertex_dim(depth, DIM_LIGHT_POINT));
    vec2 uxy = sampler_next_2d(smp);
    if (!e || away)
        return rgb_gray(0.0);
    vec3 u = v3(uxy.x, uxy.y, part);
    emitter_sample_rec es;
    if (!emitter_sample(e, h->p, u, &es) || !(es.pdf > 0.0) || rgb_is_black(es.value))
        return rgb_gray(0.0);
    vec3 wo = frame3_to_local(h->sh, es.wi);
    rgb f = bsdf_eval(b, q, wo);
    if (rgb_is_black(f))
        return rgb_gray(0.0);
    rgb tr = transmittance(sc->shapes, h, &es, max_sheets);
    if (rgb_is_black(tr))
        return rgb_gray(0.0);
    double pdf_l = es.pdf * pmf;
    double w = es.delta ? 1.0 : mis_power_heuristic(pdf_l, bsdf_pdf(b, q, wo));
    return rgb_scale(rgb_mul(rgb_mul(f, tr), es.value), w / pdf_l);
}

/* The lobes that make a path specular when sampled at its first rough
 * vertex (integrators.h, INTEGRATOR_AOV_SPECULAR). */
static const unsigned SPECULAR_LOBES =
    BSDF_GLOSSY_REFLECTION | BSDF_DELTA_REFLECTION | BSDF_GLOSSY_TRANSMISSION | BSDF_DELTA_TRANSMISSION;

/* L += c, and the specular part too when the path is specular: the
 * diffuse part L - L_specular is (up to rounding) the sum of the other
 * terms. */
static void add_radiance(rgb *L, rgb *L_specular, bool specular, rgb c)
{
    *L = rgb_add(*L, c);
    if (specular)
        *L_specular = rgb_add(*L_specular, c);
}

/* The light seen from hit in the mirror direction of d about the shading
 * normal: the emitter the mirrored ray meets (or the environment where it
 * escapes), into aov[INTEGRATOR_AOV_MIRROR...]. A denoising feature: it
 * says where a coat's highlights are, in every sample, not only in those
 * that sample the coat's lobe. */
static void mirror_light_aov(const integrator_scene *sc, const surface_hit *hit, vec3 d, double *aov)
{
    vec3 n = hit->sh.n;
    ray3 r = spawn(hit, v3_norm(v3_sub(d, v3_scale(n, 2.0 * v3_dot(d, n)))));
    surface_hit h;
    rgb le = rgb_gray(0.0);
    if (shape_list_intersect(sc->shapes, &r, 0.0, INFINITY, &h)) {
        if (h.shape->emitter)
            le = emitter_eval_hit(h.shape->emitter, &h, r.d);
    } else if (sc->emitters->env) {
        le = emitter_eval_env(sc->emitters->env, r.d);
    }
    aov[INTEGRATOR_AOV_MIRROR] = le.r, aov[INTEGRATOR_AOV_MIRROR + 1] = le.g, aov[INTEGRATOR_AOV_MIRROR + 2] = le.b;
}

/* The denoising features of a path that reflected off a sheet (thin glass)
 * before its first rough vertex: those of what lies straight behind the
 * sheet, as for the paths that went through, so that a glass case's
 * reflections do not speckle the features of what it holds. */
static void features_through_sheets(const integrator_scene *sc, const surface_hit *hit, vec3 d, double path_length,
                                    rgb beta, double *aov)
{
    ray3 r = spawn(hit, d);
    surface_hit h;
    for (int k = 0; k < 64; k++) { /* 64 sheets in a row: give up, keep the last */
        if (!shape_list_intersect(sc->shapes, &r, 0.0, INFINITY, &h)) {
            integrator_clear_rough_aovs(aov);
            return;
        }
        path_length += h.t;
        if (integrator_rough_hit_aovs(aov, &h, path_length, beta) ||
            !(bsdf_flags(h.shape->bsdf) & BSDF_STRAIGHT_TRANSMISSION))
            return;
        r = spawn(&h, d);
    }
}

static rgb path_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray0, double tmin, double tmax,
                   sampler_stream *smp, double *aov)
{
    const path_data *pd = in->data;
    const emitter_list *emitters = sc->emitters;
    rgb L = rgb_gray(0.0), beta = rgb_gray(1.0);
    double eta = 1.0, prev_pdf = 1.0, t0 = tmin, t1 = tmax;
    bool prev_delta = true;
    ray3 ray = *ray0;
    emitter_ref prev = {ray.o, v3(0.0, 0.0, 0.0)}; /* the last scattering vertex, as NEE saw it */
    bool rough_pending = aov != NULL; /* the first rough vertex is still to be found */
    bool features_pending = rough_pending; /* and the denoising features (found past sheets apart) */
    /* The path left its first rough vertex by a glossy or delta lobe: what
     * it gathers from then on is the specular AOV's too. */
    bool specular = false;
    rgb L_specular = rgb_gray(0.0);
    double path_length = 0.0;         /* the ray directions are unit: t is a distance */
    if (aov) {
        for (int i = 0; i < INTEGRATOR_AOV_COUNT; i++)
            aov[i] = 0.0;
        aov[INTEGRATOR_AOV_ALPHA] = emitters->env && !pd->hide_emitters; /* Mitsuba's valid ray */
    }
    for (int depth = 0;; depth++) {
        surface_hit hit;
        bool found = shape_list_intersect(sc->shapes, &ray, t0, t1, &hit);
        bool show = !(depth == 0 && pd->hide_emitters);
        if (!found) {
            if (features_pending)
                integrator_clear_rough_aovs(aov);
            if (emitters->env && show) {
                const emitter_t *e = emitters->env;
                double w = prev_delta ? 1.0
                                      : mis_power_heuristic(prev_pdf, emitter_list_pmf(emitters, &prev, e) *
                                                                          emitter_pdf_env(e, ray.d));
                add_radiance(&L, &L_specular, specular, rgb_scale(rgb_mul(beta, emitter_eval_env(e, ray.d)), w));
            }
            break;
        }
        const shape_t *sh = hit.shape;
        path_length += hit.t;
        if (depth == 0 && aov)
            integrator_first_hit_aovs(aov, &hit);
        bool at_rough = rough_pending && (bsdf_flags(sh->bsdf) & BSDF_SMOOTH);
        rough_pending = rough_pending && !at_rough;
        if (features_pending)
            features_pending = !integrator_rough_hit_aovs(aov, &hit, path_length, beta);
        if (at_rough && (bsdf_flags(sh->bsdf) & BSDF_DELTA_REFLECTION))
            mirror_light_aov(sc, &hit, ray.d, aov);
        if (sh->emitter && show) {
            const emitter_t *e = sh->emitter;
            rgb le = emitter_eval_hit(e, &hit, ray.d);
            if (!rgb_is_black(le)) {
                double w = prev_delta ? 1.0
                                      : mis_power_heuristic(prev_pdf, emitter_list_pmf(emitters, &prev, e) *
                                                                          emitter_pdf_hit(e, prev.p, &hit, ray.d));
                add_radiance(&L, &L_specular, specular, rgb_scale(rgb_mul(beta, le), w));
            }
        }
        if (pd->max_depth >= 0 && depth + 1 >= pd->max_depth) {
            if (aov && sh->emitter && !pd->hide_emitters)
                aov[INTEGRATOR_AOV_ALPHA] = 1.0;
            break;
        }

        bsdf_query q = shape_bsdf_query(&hit, ray.d, TRANSPORT_RADIANCE);
        if ((bsdf_flags(sh->bsdf) & BSDF_SMOOTH) && emitters->count > 0) {
            /* The emitter at depth + 1 + sheets must not pass max_depth - 1. */
            int max_sheets = pd->max_depth < 0 ? -1 : pd->max_depth - 2 - depth;
            add_radiance(&L, &L_specular, specular,
                         rgb_mul(beta, next_event(sc, &hit, sh->bsdf, &q, smp, depth, max_sheets)));
        }

        bsdf_sample_rec bs;
        sampler_seek(smp, vertex_dim(depth, DIM_BSDF_LOBE));
        double u1 = sampler_next_1d(smp);
        sampler_seek(smp, vertex_dim(depth, DIM_BSDF_DIRECTION));
        vec2 u2 = sampler_next_2d(smp);
        bool sampled = bsdf_sample(sh->bsdf, &q, u1, u2, &bs);
        if (aov && !(bs.sampled_type & BSDF_NULL)) /* a surface, not a null one: covered */
            aov[INTEGRATOR_AOV_ALPHA] = 1.0;
        if (!sampled || rgb_is_black(bs.weight))
            break;
        if (at_rough)
            specular = (bs.sampled_type & SPECULAR_LOBES) != 0;
        if (features_pending && (bsdf_flags(sh->bsdf) & BSDF_STRAIGHT_TRANSMISSION) &&
            !(bs.sampled_type & BSDF_STRAIGHT_TRANSMISSION)) {
            features_through_sheets(sc, &hit, ray.d, path_length, beta, aov);
            features_pending = false;
        }
        beta = rgb_mul(beta, bs.weight);
        eta *= bs.eta;
        /* Straight through a thin sheet, the path keeps the last scattering
         * vertex's density for MIS: next-event estimation from that vertex
         * saw the emitter through the sheet too (transmittance above). */
        if (!(bs.sampled_type & BSDF_STRAIGHT_TRANSMISSION)) {
            prev_delta = (bs.sampled_type & BSDF_DELTA) != 0;
            prev_pdf = bs.pdf;
            prev = (emitter_ref){hit.p, hit.ng};
        }
        ray = spawn(&hit, v3_norm(frame3_to_world(hit.sh, bs.wo)));
        t0 = 0.0, t1 = INFINITY;

        double beta_max = rgb_max(beta) * eta * eta;
        if (depth + 1 >= pd->rr_depth) {
            double survive = fmin(beta_max, 0.95);
            sampler_seek(smp, vertex_dim(depth, DIM_ROULETTE));
            if (sampler_next_1d(smp) >= survive)
                break;
            beta = rgb_scale(beta, 1.0 / survive);
        }
        if (!(beta_max > 0.0))
            break;
    }
    if (!isfinite(L.r) || !isfinite(L.g) || !isfinite(L.b))
        L = L_specular = rgb_gray(0.0);
    if (aov) {
        aov[INTEGRATOR_AOV_SPECULAR] = L_specular.r;
        aov[INTEGRATOR_AOV_SPECULAR + 1] = L_specular.g;
        aov[INTEGRATOR_AOV_SPECULAR + 2] = L_specular.b;
    }
    return L;
}

static const integrator_ops path_ops = {path_li, NULL};

static integrator_t *path_create(scene_obj *o, char *err, size_t errlen)
{
    long long md = scene_obj_int(o, "max_depth", -1), rr = scene_obj_int(o, "rr_depth", 5);
    if (md < -1 || md > 1000000 || rr < 1 || rr > 1000000) {
        scene_obj_error(o, err, errlen, "max_depth must be -1 or >= 0 and rr_depth >= 1");
        return NULL;
    }
    path_data d = {(int)md, (int)rr, scene_obj_bool(o, "hide_emitters", false)};
    return integrator_alloc(o, &path_ops, &d, sizeof d, err, errlen);
}

static const scene_param_decl path_params[] = {
    {"max_depth", PARAM_INT, 0, NULL},
    {"rr_depth", PARAM_INT, 0, NULL},
    {"hide_emitters", PARAM_BOOL, 0, NULL},
    {NULL, 0, 0, NULL},
};

const integrator_plugin integrator_path = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "path", .params = path_params},
    .create = path_create,
};
