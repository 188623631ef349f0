/* The `homogeneous` medium: constant `sigma_t` (a color, default 1) times
 * `scale` (1); `albedo` (0.75) a color or a <volume>, as in Mitsuba; a nested
 * <phase> (isotropic). `sample_emitters` (true): whether scattered paths
 * sample emitters; `has_spectral_extinction` changes nothing in RGB. */
#include "media/medium_impl.h"

static medium_t *homogeneous_create(scene_obj *o, char *err, size_t errlen)
{
    return medium_create_common(o, true, err, errlen);
}

static const scene_param_decl homogeneous_params[] = {
    MEDIUM_PARAMS_COMMON,
    {NULL, 0, 0, NULL},
};

const medium_plugin medium_homogeneous = {
    .decl = {.cls = SCENE_MEDIUM, .type = "homogeneous", .params = homogeneous_params, .children = medium_children},
    .create = homogeneous_create,
};
