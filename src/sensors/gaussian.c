/* Mitsuba's `gaussian` reconstruction filter, its film default: along each
 * axis exp(-x^2 / (2 stddev^2)) less its value at the cut-off radius of 4
 * standard deviations (so it falls to zero there), `stddev` 0.5 pixel by
 * default. Mitsuba evaluates a polynomial fit of the same function and
 * tabulates it; the weights here are exact. */
#include <math.h>

#include "sensors/sensors.h"

static double gaussian_eval(const rfilter_t *f, double x)
{
    return fmax(0.0, exp(f->p[0] * x * x) - f->p[1]);
}

static int gaussian_create(scene_obj *o, rfilter_t *out, char *err, size_t errlen)
{
    double stddev = scene_obj_float(o, "stddev", 0.5);
    if (!(stddev > 0.0) || stddev > 16.0)
        return scene_obj_error(o, err, errlen, "<rfilter type=\"gaussian\">: stddev %g is not in (0, 16]", stddev);
    double a = -0.5 / (stddev * stddev), r = 4.0 * stddev;
    *out = (rfilter_t){"gaussian", r, {a, exp(a * r * r)}, gaussian_eval};
    return 0;
}

static const scene_param_decl gaussian_params[] = {{"stddev", PARAM_FLOAT, 0, NULL}, {NULL, 0, 0, NULL}};

const rfilter_plugin rfilter_gaussian = {
    .decl = {.cls = SCENE_RFILTER, .type = "gaussian", .params = gaussian_params},
    .create = gaussian_create,
};
