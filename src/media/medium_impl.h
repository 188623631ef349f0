/* What a medium plugin provides. Private to src/media/. */
#ifndef CELADON_MEDIUM_IMPL_H
#define CELADON_MEDIUM_IMPL_H

#include "media/media.h"
#include "volumes/volumes.h"

struct medium {
    volume_t *sigma_t, *albedo; /* owned */
    double scale;
    phase_t *phase;             /* owned */
    bool homogeneous;           /* sigma_t constant: exact transmittance */
    bool sample_emitters;
    double majorant;            /* scale * the largest sigma_t of any channel anywhere */
};

/* The medium of a <medium> object: its sigma_t, albedo, scale, phase and
 * sample_emitters, sigma_t required constant when homogeneous. NULL with
 * "file:line: problem" in err. */
medium_t *medium_create_common(scene_obj *o, bool homogeneous, char *err, size_t errlen);

/* The parameters both plugins take. */
#define MEDIUM_PARAMS_COMMON                                                                                    \
    {"sigma_t", PARAM_COLOR | PARAM_OBJECT, 0, NULL}, {"albedo", PARAM_COLOR | PARAM_OBJECT, 0, NULL},         \
        {"scale", PARAM_FLOAT, 0, NULL}, {"sample_emitters", PARAM_BOOL, 0, NULL},                              \
        {"has_spectral_extinction", PARAM_BOOL, 0, NULL}

extern const scene_child_decl medium_children[];

#endif
