/* The `heterogeneous` medium: `sigma_t` and `albedo` as <volume>s (or
 * colors), sigma_t times `scale`; otherwise as `homogeneous`. Its flights
 * are tracked against the largest extinction of the grid (media.h). */
#include "media/medium_impl.h"

static medium_t *heterogeneous_create(scene_obj *o, char *err, size_t errlen)
{
    return medium_create_common(o, false, err, errlen);
}

static const scene_param_decl heterogeneous_params[] = {
    MEDIUM_PARAMS_COMMON,
    {NULL, 0, 0, NULL},
};

const medium_plugin medium_heterogeneous = {
    .decl = {.cls = SCENE_MEDIUM, .type = "heterogeneous", .params = heterogeneous_params, .children = medium_children},
    .create = heterogeneous_create,
};
