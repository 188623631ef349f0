/* The `hg` phase function (Henyey-Greenstein): `g`, the mean cosine of the
 * scattering angle, in (-1, 1) (Mitsuba's default 0.8). */
#include "phases/phase_impl.h"

static phase_t *hg_create(scene_obj *o, char *err, size_t errlen)
{
    double g = scene_obj_float(o, "g", 0.8);
    if (!(g > -1.0 && g < 1.0)) {
        scene_obj_error(o, err, errlen, "g must be in (-1, 1)");
        return NULL;
    }
    return phase_alloc(o, g, err, errlen);
}

static const scene_param_decl hg_params[] = {
    {"g", PARAM_FLOAT, 0, NULL},
    {NULL, 0, 0, NULL},
};

const phase_plugin phase_hg = {
    .decl = {.cls = SCENE_PHASE, .type = "hg", .params = hg_params},
    .create = hg_create,
};
