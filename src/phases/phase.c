/* What every phase function shares: Henyey-Greenstein's lobe (isotropic is
 * its g = 0), its sampling by inversion of the CDF of cos(theta), and the
 * lifetime. */
#include <math.h>
#include <stdlib.h>

#include "phases/phase_impl.h"

/* p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)), mu = dot(d, w). */
static double hg(double g, double mu)
{
    double den = 1.0 + g * g - 2.0 * g * mu;
    return (1.0 - g * g) / (4.0 * M_PI * den * sqrt(den));
}

double phase_eval(const phase_t *p, vec3 d, vec3 w)
{
    return hg(p->g, v3_dot(d, w));
}

vec3 phase_sample(const phase_t *p, vec3 d, vec2 u, double *pdf)
{
    double g = p->g, mu;
    /* The CDF of mu inverted: mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g);
     * below |g| = 1e-3 its cancellation costs more than the lobe's shape. */
    if (fabs(g) < 1e-3)
        mu = 1.0 - 2.0 * u.x;
    else {
        double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        mu = (1.0 + g * g - s * s) / (2.0 * g);
    }
    mu = fmax(-1.0, fmin(1.0, mu));
    double sin_t = sqrt(fmax(0.0, 1.0 - mu * mu)), phi = 2.0 * M_PI * u.y;
    frame3 f = frame3_from_normal(d);
    vec3 w = v3_norm(frame3_to_world(f, v3(sin_t * cos(phi), sin_t * sin(phi), mu)));
    *pdf = hg(g, mu);
    return w;
}

void phase_destroy(phase_t *p)
{
    free(p);
}

phase_t *phase_alloc(const scene_obj *o, double g, char *err, size_t errlen)
{
    phase_t *p = malloc(sizeof *p);
    if (!p) {
        scene_obj_error(o, err, errlen, "out of memory");
        return NULL;
    }
    p->g = g;
    return p;
}

phase_t *phase_create(scene_obj *o, const scene_obj *at, char *err, size_t errlen)
{
    if (!o)
        return phase_alloc(at, 0.0, err, errlen);
    const phase_plugin *plugin = phase_plugin_find(o->type);
    if (!plugin) {
        scene_obj_error(o, err, errlen, "unsupported phase function '%s'", o->type);
        return NULL;
    }
    return plugin->create(o, err, errlen);
}
