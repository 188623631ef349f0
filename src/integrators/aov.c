/* Mitsuba's `aov` integrator: the arbitrary output variables `aovs` lists
 * as "name:type" pairs (albedo, depth, position, uv, geo_normal,
 * sh_normal, dp_du, dp_dv, prim_index, shape_index) of the surface the
 * camera ray meets first, and the images of the nested integrators. Each
 * nested integrator sees the pixel sample's numbers as if it rendered
 * alone (the sampler's stream restarts after the film position for each),
 * as Mitsuba renders them one after the other with the same seed. The
 * image itself (R, G, B, A) is the first nested integrator's, black
 * without one. Channels, in Mitsuba's order: for each nested integrator N,
 * N.R, N.G, N.B, N.A and its own channels N.*; then each AOV: name.R/G/B
 * (albedo), name.T (depth), name.X/Y/Z (position, normals, dp_du, dp_dv),
 * name.U/V (uv), name.I (indices). */
#include <stdio.h>
#include <string.h>

#include "integrators/integrator_impl.h"

enum { AOV_MAX = 32, AOV_NESTED_MAX = 8 };

typedef enum {
    AOV_ALBEDO,
    AOV_DEPTH,
    AOV_POSITION,
    AOV_UV,
    AOV_GEO_NORMAL,
    AOV_SH_NORMAL,
    AOV_DP_DU,
    AOV_DP_DV,
    AOV_PRIM_INDEX,
    AOV_SHAPE_INDEX,
    AOV_TYPE_COUNT
} aov_type;

static const struct {
    const char *name, *suffixes;
} aov_types[AOV_TYPE_COUNT] = {
    {"albedo", "RGB"}, {"depth", "T"},     {"position", "XYZ"}, {"uv", "UV"},         {"geo_normal", "XYZ"},
    {"sh_normal", "XYZ"}, {"dp_du", "XYZ"}, {"dp_dv", "XYZ"},   {"prim_index", "I"}, {"shape_index", "I"},
};

typedef struct {
    aov_type types[AOV_MAX];
    int ntypes;
    integrator_t *nested[AOV_NESTED_MAX];
    int nnested;
} aov_data;

static int put3(double *out, vec3 v)
{
    out[0] = v.x, out[1] = v.y, out[2] = v.z;
    return 3;
}

/* The values of one AOV at the hit (zero where the ray escapes). */
static int aov_values(aov_type t, const integrator_scene *sc, const surface_hit *h, vec3 dir, double *out)
{
    int n = (int)strlen(aov_types[t].suffixes);
    if (!h) {
        memset(out, 0, sizeof *out * (size_t)n);
        return n;
    }
    switch (t) {
    case AOV_ALBEDO: {
        rgb a = bsdf_albedo(h->shape->bsdf, h->uv);
        out[0] = a.r, out[1] = a.g, out[2] = a.b;
        return 3;
    }
    case AOV_DEPTH: out[0] = h->t; return 1;
    case AOV_POSITION: return put3(out, h->p);
    case AOV_UV: out[0] = h->uv.x, out[1] = h->uv.y; return 2;
    case AOV_GEO_NORMAL: return put3(out, h->ng);
    case AOV_SH_NORMAL: {
        bsdf_query q = shape_bsdf_query(h, dir, TRANSPORT_RADIANCE);
        return put3(out, v3_norm(frame3_to_world(h->sh, bsdf_shading_normal(h->shape->bsdf, &q))));
    }
    case AOV_DP_DU: return put3(out, h->dpdu);
    case AOV_DP_DV: return put3(out, h->dpdv);
    case AOV_PRIM_INDEX: out[0] = h->prim; return 1;
    default: /* shape_index: the shape's number from 1, as Mitsuba counts */
        out[0] = (double)(h->shape - sc->shapes->items) + 1.0;
        return 1;
    }
}

static rgb aov_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                  sampler_stream *smp, double *aov)
{
    const aov_data *d = in->data;
    if (!aov) /* no channels at all */
        return rgb_gray(0.0);
    double *own = aov + INTEGRATOR_AOV_COUNT;
    rgb result = rgb_gray(0.0);
    const sampler_stream start = *smp;
    integrator_clear_aovs(aov, false);
    for (int i = 0; i < d->nnested; i++) {
        *smp = start;
        double fixed[INTEGRATOR_AOV_COUNT];
        rgb L = integrator_nested_li(d->nested[i], sc, ray, tmin, tmax, smp, fixed, own + 4);
        *own++ = L.r, *own++ = L.g, *own++ = L.b, *own++ = fixed[INTEGRATOR_AOV_ALPHA];
        own += integrator_channel_count(d->nested[i]);
        if (i == 0) {
            result = L;
            memcpy(aov, fixed, sizeof fixed);
        }
    }
    surface_hit hit;
    bool found = shape_list_intersect(sc->shapes, ray, tmin, tmax, &hit);
    for (int i = 0; i < d->ntypes; i++)
        own += aov_values(d->types[i], sc, found ? &hit : NULL, ray->d, own);
    return result;
}

static void aov_release(void *data)
{
    aov_data *d = data;
    for (int i = 0; i < d->nnested; i++)
        integrator_destroy(d->nested[i]);
}

static const integrator_ops aov_ops = {aov_li, aov_release};

/* Reads "name:type, name:type" into d and the channel names into in. */
static int parse_aovs(scene_obj *o, const char *spec, aov_data *d, char (*names)[64], char *err, size_t errlen)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", spec);
    char *save, *tok = strtok_r(buf, ", ", &save);
    for (; tok; tok = strtok_r(NULL, ", ", &save)) {
        char *colon = strchr(tok, ':');
        int t = 0;
        while (colon && t < AOV_TYPE_COUNT && strcmp(colon + 1, aov_types[t].name) != 0)
            t++;
        if (!colon || colon == tok)
            return scene_obj_error(o, err, errlen, "<integrator type=\"aov\">: '%s' is not a name:type pair", tok);
        if (strcmp(colon + 1, "duv_dx") == 0 || strcmp(colon + 1, "duv_dy") == 0)
            return scene_obj_error(o, err, errlen, "<integrator type=\"aov\">: AOV type '%s' needs ray "
                                   "differentials, which celadon does not trace", colon + 1);
        if (t == AOV_TYPE_COUNT)
            return scene_obj_error(o, err, errlen, "<integrator type=\"aov\">: unknown AOV type '%s'", colon + 1);
        if (d->ntypes == AOV_MAX)
            return scene_obj_error(o, err, errlen, "<integrator type=\"aov\">: at most %d AOVs", AOV_MAX);
        *colon = '\0';
        snprintf(names[d->ntypes], 64, "%s", tok);
        d->types[d->ntypes++] = (aov_type)t;
    }
    return 0;
}

static integrator_t *aov_create(scene_obj *o, char *err, size_t errlen)
{
    aov_data d = {.ntypes = 0};
    char names[AOV_MAX][64];
    if (parse_aovs(o, scene_obj_string(o, "aovs", ""), &d, names, err, errlen) != 0)
        return NULL;
    d.nnested = integrator_nested(o, d.nested, AOV_NESTED_MAX, err, errlen);
    if (d.nnested < 0)
        return NULL;
    integrator_t *in = integrator_alloc(o, &aov_ops, &d, sizeof d, err, errlen);
    if (!in) {
        aov_release(&d);
        return NULL;
    }
    int rc = 0;
    for (int i = 0; i < d.nnested; i++) {
        char name[64];
        integrator_nested_name(o, i, name, sizeof name);
        for (int c = 0; c < 4; c++)
            rc |= integrator_add_channel(in, name, (const char *[]){"R", "G", "B", "A"}[c]);
        rc |= integrator_add_nested_channels(in, name, d.nested[i]);
    }
    for (int i = 0; i < d.ntypes; i++)
        for (const char *s = aov_types[d.types[i]].suffixes; *s; s++)
            rc |= integrator_add_channel(in, names[i], (char[]){*s, '\0'});
    if (rc != 0) {
        integrator_destroy(in);
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    return in;
}

static const scene_param_decl aov_params[] = {{"aovs", PARAM_STRING, PARAM_REQUIRED, NULL}, {NULL, 0, 0, NULL}};
static const scene_child_decl aov_children[] = {{SCENE_INTEGRATOR, 0, AOV_NESTED_MAX, NULL},
                                                {SCENE_SCENE, 0, 0, NULL}};

const integrator_plugin integrator_aov = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "aov", .params = aov_params, .children = aov_children},
    .create = aov_create,
};
