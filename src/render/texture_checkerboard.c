/* Mitsuba's checkerboard: color0 where both fractional uv parts are on the same
 * side of 1/2, color1 elsewhere. */
#include <stdlib.h>

#include "render/texture_impl.h"

texture_checkerboard_params texture_checkerboard_defaults(void)
{
    texture_checkerboard_params p = {rgb_gray(0.4), rgb_gray(0.2), uv_transform_identity()};
    return p;
}

texture_t *texture_create_checkerboard(const texture_checkerboard_params *params)
{
    texture_t *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    t->kind = TEXTURE_KIND_CHECKERBOARD;
    t->to_uv = params->to_uv;
    t->u.checker.color0 = params->color0;
    t->u.checker.color1 = params->color1;
    t->mean = rgb_scale(rgb_add(params->color0, params->color1), 0.5);
    return t;
}

rgb texture_checkerboard_lookup(const texture_t *t, vec2 uv)
{
    int mu = uv.x - floor(uv.x) > 0.5, mv = uv.y - floor(uv.y) > 0.5;
    return mu == mv ? t->u.checker.color0 : t->u.checker.color1;
}
