/* Dispatch to an integrator plugin, its allocation and output channels,
 * and the nested integrators of the plugins that hold some. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "integrators/integrator_impl.h"

rgb integrator_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                  sampler_stream *smp, double *aov)
{
    return in->ops->li(in, sc, ray, tmin, tmax, smp, aov);
}

int integrator_channel_count(const integrator_t *in) { return in->nchannels; }
const char *integrator_channel_name(const integrator_t *in, int i) { return in->channels[i]; }
const char *integrator_type(const integrator_t *in) { return in->type; }

integrator_t *integrator_alloc(const scene_obj *o, const integrator_ops *ops, const void *data, size_t data_size,
                               char *err, size_t errlen)
{
    void *at;
    integrator_t *in = record_alloc(sizeof *in, data, data_size, &at);
    if (!in) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    in->ops = ops;
    in->type = integrator_plugin_find(o->type)->decl.type; /* static: o goes with the description */
    in->data = at;
    in->channels = NULL;
    in->nchannels = 0;
    return in;
}

/* Depth, normal and albedo (times weight) of hit at aov[at...]. */
static void hit_features(double *aov, int at_depth, int at_normal, int at_albedo, const surface_hit *hit, double depth,
                         rgb weight)
{
    aov[at_depth] = depth;
    double *n = aov + at_normal, *albedo = aov + at_albedo;
    n[0] = hit->sh.n.x, n[1] = hit->sh.n.y, n[2] = hit->sh.n.z;
    rgb a = rgb_mul(bsdf_albedo(hit->shape->bsdf, hit->uv), weight);
    albedo[0] = a.r, albedo[1] = a.g, albedo[2] = a.b;
}

void integrator_first_hit_aovs(double *aov, const surface_hit *hit)
{
    hit_features(aov, INTEGRATOR_AOV_DEPTH, INTEGRATOR_AOV_NORMAL, INTEGRATOR_AOV_ALBEDO, hit, hit->t, rgb_gray(1.0));
    integrator_rough_hit_aovs(aov, hit, hit->t, rgb_gray(1.0));
}

bool integrator_rough_hit_aovs(double *aov, const surface_hit *hit, double path_length, rgb weight)
{
    hit_features(aov, INTEGRATOR_AOV_ROUGH_DEPTH, INTEGRATOR_AOV_ROUGH_NORMAL, INTEGRATOR_AOV_ROUGH_ALBEDO, hit,
                 path_length, weight);
    return (bsdf_flags(hit->shape->bsdf) & BSDF_SMOOTH) != 0;
}

void integrator_clear_rough_aovs(double *aov)
{
    for (int i = INTEGRATOR_AOV_ROUGH_DEPTH; i < INTEGRATOR_AOV_ROUGH_ALBEDO + 3; i++)
        aov[i] = 0.0;
}

void integrator_clear_aovs(double *aov, bool covered)
{
    for (int i = 0; i < INTEGRATOR_AOV_COUNT; i++)
        aov[i] = 0.0;
    aov[INTEGRATOR_AOV_ALPHA] = covered;
}

ray3 integrator_spawn(const surface_hit *hit, vec3 w)
{
    double side = v3_dot(hit->ng, w) >= 0.0 ? hit->eps : -hit->eps;
    return (ray3){v3_add(hit->p, v3_scale(hit->ng, side)), w};
}

bool integrator_unoccluded(const shape_list *shapes, const surface_hit *hit, const emitter_sample_rec *es)
{
    ray3 r = integrator_spawn(hit, es->wi);
    if (isinf(es->dist))
        return !shape_list_occluded(shapes, &r, 0.0, INFINITY);
    vec3 target = es->p;
    if (es->eps > 0.0) /* lift the light point toward the receiver */
        target = v3_add(target, v3_scale(es->n, v3_dot(es->n, es->wi) < 0.0 ? es->eps : -es->eps));
    r.d = v3_sub(target, r.o);
    return !shape_list_occluded(shapes, &r, 0.0, 1.0 - 1e-7);
}

rgb integrator_nested_li(const integrator_t *nested, const integrator_scene *sc, const ray3 *ray, double tmin,
                         double tmax, sampler_stream *smp, double *fixed, double *own)
{
    int k = nested->nchannels;
    double local[64], *buf = INTEGRATOR_AOV_COUNT + k <= 64 ? local : malloc(sizeof(double) * (size_t)(INTEGRATOR_AOV_COUNT + k));
    if (!buf)
        abort();
    rgb L = nested->ops->li(nested, sc, ray, tmin, tmax, smp, buf);
    if (fixed)
        memcpy(fixed, buf, sizeof(double) * INTEGRATOR_AOV_COUNT);
    memcpy(own, buf + INTEGRATOR_AOV_COUNT, sizeof(double) * (size_t)k);
    if (buf != local)
        free(buf);
    return L;
}

int integrator_add_channel(integrator_t *in, const char *prefix, const char *suffix)
{
    char **a = realloc(in->channels, sizeof *a * (size_t)(in->nchannels + 1));
    if (!a)
        return -1;
    in->channels = a;
    size_t n = strlen(prefix) + strlen(suffix) + 2;
    char *s = malloc(n);
    if (!s)
        return -1;
    snprintf(s, n, "%s%s%s", prefix, *prefix && *suffix ? "." : "", suffix);
    a[in->nchannels++] = s;
    return 0;
}

int integrator_add_nested_channels(integrator_t *in, const char *name, const integrator_t *nested)
{
    int rc = 0;
    for (int c = 0; c < nested->nchannels; c++)
        rc |= integrator_add_channel(in, name, nested->channels[c]);
    return rc;
}

void integrator_nested_name(const scene_obj *o, int i, char *buf, size_t len)
{
    const scene_obj *child = NULL;
    int unnamed = 0, k = 0;
    for (int c = 0; c < o->nchildren; c++) {
        if (o->children[c]->cls != SCENE_INTEGRATOR)
            continue;
        if (k++ == i) {
            child = o->children[c];
            break;
        }
        unnamed += o->children[c]->name == NULL;
    }
    if (child && child->name)
        snprintf(buf, len, "%s", child->name);
    else
        snprintf(buf, len, "_arg_%d", unnamed);
}

int integrator_nested(scene_obj *o, integrator_t **out, int max, char *err, size_t errlen)
{
    scene_obj *nested[16];
    int n = scene_obj_children(o, SCENE_INTEGRATOR, nested, 16);
    if (n > max || n > 16)
        return scene_obj_error(o, err, errlen, "<integrator type=\"%s\">: at most %d nested integrators", o->type,
                               max < 16 ? max : 16);
    for (int i = 0; i < n; i++) {
        const integrator_plugin *plugin = integrator_plugin_find(nested[i]->type);
        out[i] = plugin->create(nested[i], err, errlen);
        if (!out[i]) {
            while (i-- > 0)
                integrator_destroy(out[i]);
            return -1;
        }
    }
    return n;
}

void integrator_destroy(integrator_t *in)
{
    if (!in)
        return;
    if (in->ops->release)
        in->ops->release(in->data);
    for (int i = 0; i < in->nchannels; i++)
        free(in->channels[i]);
    free(in->channels);
    free(in);
}
