/* Mitsuba's `moment` integrator: the image of its first nested integrator,
 * and as channels, for each nested integrator N (in order, drawing on the
 * same pixel sample's numbers one after the other), its own channels N.*
 * and its radiance as CIE XYZ (N.X, N.Y, N.Z: Mitsuba's srgb_to_xyz), then
 * the squares of all of those ("m2_" + their names). The film averages
 * them, so m2_N.Y - N.Y^2 is the variance of one sample's Y in the pixel
 * (for the box filter; the filter-weighted one otherwise). */
#include <stdio.h>

#include "integrators/integrator_impl.h"

enum { MOMENT_NESTED_MAX = 8 };

typedef struct {
    integrator_t *nested[MOMENT_NESTED_MAX];
    int nnested;
    int nfirst; /* channels before the m2_ ones */
} moment_data;

static rgb moment_li(const integrator_t *in, const integrator_scene *sc, const ray3 *ray, double tmin, double tmax,
                     sampler_stream *smp, double *aov)
{
    static const double to_xyz[3][3] = {
        {0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}};
    const moment_data *d = in->data;
    double *own = aov + INTEGRATOR_AOV_COUNT, *m1 = own;
    rgb result = rgb_gray(0.0);
    for (int i = 0; i < d->nnested; i++) {
        rgb L = integrator_nested_li(d->nested[i], sc, ray, tmin, tmax, smp, i == 0 ? aov : NULL, own);
        if (i == 0)
            result = L;
        own += integrator_channel_count(d->nested[i]);
        double c[3] = {L.r, L.g, L.b};
        for (int r = 0; r < 3; r++)
            *own++ = to_xyz[r][0] * c[0] + to_xyz[r][1] * c[1] + to_xyz[r][2] * c[2];
    }
    for (int k = 0; k < d->nfirst; k++)
        m1[d->nfirst + k] = m1[k] * m1[k];
    return result;
}

static void moment_release(void *data)
{
    moment_data *d = data;
    for (int i = 0; i < d->nnested; i++)
        integrator_destroy(d->nested[i]);
}

static const integrator_ops moment_ops = {moment_li, moment_release};

static integrator_t *moment_create(scene_obj *o, char *err, size_t errlen)
{
    moment_data d = {.nnested = 0};
    d.nnested = integrator_nested(o, d.nested, MOMENT_NESTED_MAX, err, errlen);
    if (d.nnested < 0)
        return NULL;
    integrator_t *in = integrator_alloc(o, &moment_ops, &d, sizeof d, err, errlen);
    if (!in) {
        moment_release(&d);
        return NULL;
    }
    int rc = 0;
    for (int i = 0; i < d.nnested; i++) {
        char name[64];
        integrator_nested_name(o, i, name, sizeof name);
        rc |= integrator_add_nested_channels(in, name, d.nested[i]);
        rc |= integrator_add_channel(in, name, "X") | integrator_add_channel(in, name, "Y") |
              integrator_add_channel(in, name, "Z");
    }
    moment_data *md = in->data;
    md->nfirst = integrator_channel_count(in);
    for (int k = 0; k < md->nfirst && rc == 0; k++) {
        char m2[160];
        snprintf(m2, sizeof m2, "m2_%s", integrator_channel_name(in, k));
        rc |= integrator_add_channel(in, m2, "");
    }
    if (rc != 0) {
        integrator_destroy(in);
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    return in;
}

static const scene_child_decl moment_children[] = {{SCENE_INTEGRATOR, 1, MOMENT_NESTED_MAX, NULL},
                                                   {SCENE_SCENE, 0, 0, NULL}};

const integrator_plugin integrator_moment = {
    .decl = {.cls = SCENE_INTEGRATOR, .type = "moment", .children = moment_children},
    .create = moment_create,
};
