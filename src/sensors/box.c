/* Mitsuba's `box` reconstruction filter: a sample counts, with weight 1, in
 * the pixel it falls in and nowhere else (radius 1/2). */
#include "sensors/sensors.h"

static double box_eval(const rfilter_t *f, double x)
{
    (void)f;
    return x >= -0.5 && x < 0.5 ? 1.0 : 0.0;
}

static int box_create(scene_obj *o, rfilter_t *out, char *err, size_t errlen)
{
    (void)o, (void)err, (void)errlen;
    *out = (rfilter_t){"box", 0.5, {0.0, 0.0}, box_eval};
    return 0;
}

const rfilter_plugin rfilter_box = {
    .decl = {.cls = SCENE_RFILTER, .type = "box"},
    .create = box_create,
};
