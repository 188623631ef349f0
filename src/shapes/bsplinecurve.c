/* Mitsuba's `bsplinecurve`: uniform cubic B-spline curves, every four
 * consecutive control points a segment, swept by a sphere whose radius the
 * same basis interpolates (curve.c). */
#include "shapes/shape_impl.h"

static int bsplinecurve_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                               char *err, size_t errlen)
{
    (void)opt;
    return curve_shape_create(o, ACCEL_KIND_CURVE_BSPLINE, to_world, sh, err, errlen);
}

static const scene_param_decl bsplinecurve_params[] = {
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL}, SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_bsplinecurve = {
    .decl = {.cls = SCENE_SHAPE, .type = "bsplinecurve", .params = bsplinecurve_params, .children = shape_children},
    .create = bsplinecurve_create,
};
