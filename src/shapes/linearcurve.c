/* Mitsuba's `linearcurve`: tubes of linearly varying radius between
 * consecutive control points, joined and capped by spheres (curve.c). */
#include "shapes/shape_impl.h"

static int linearcurve_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                              char *err, size_t errlen)
{
    (void)opt;
    return curve_shape_create(o, ACCEL_KIND_CURVE_LINEAR, to_world, sh, err, errlen);
}

static const scene_param_decl linearcurve_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL}, SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_linearcurve = {
    .decl = {.cls = SCENE_SHAPE, .type = "linearcurve", .params = linearcurve_params, .children = shape_children},
    .create = linearcurve_create,
};
