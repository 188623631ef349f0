/* The `isotropic` phase function: 1 / (4 pi) in every direction. */
#include "phases/phase_impl.h"

static phase_t *isotropic_create(scene_obj *o, char *err, size_t errlen)
{
    return phase_alloc(o, 0.0, err, errlen);
}

const phase_plugin phase_isotropic = {
    .decl = {.cls = SCENE_PHASE, .type = "isotropic"},
    .create = isotropic_create,
};
