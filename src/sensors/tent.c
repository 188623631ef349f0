/* Mitsuba's `tent` reconstruction filter: weight max(0, 1 - |x| / radius)
 * along each axis, `radius` 1 pixel by default. */
#include <math.h>

#include "sensors/sensors.h"

static double tent_eval(const rfilter_t *f, double x)
{
    return fmax(0.0, 1.0 - fabs(x) * f->p[0]);
}

static int tent_create(scene_obj *o, rfilter_t *out, char *err, size_t errlen)
{
    double radius = scene_obj_float(o, "radius", 1.0);
    if (!(radius > 0.0) || radius > 64.0)
        return scene_obj_error(o, err, errlen, "<rfilter type=\"tent\">: radius %g is not in (0, 64]", radius);
    *out = (rfilter_t){"tent", radius, {1.0 / radius, 0.0}, tent_eval};
    return 0;
}

static const scene_param_decl tent_params[] = {{"radius", PARAM_FLOAT, 0, NULL}, {NULL, 0, 0, NULL}};

const rfilter_plugin rfilter_tent = {
    .decl = {.cls = SCENE_RFILTER, .type = "tent", .params = tent_params},
    .create = tent_create,
};
