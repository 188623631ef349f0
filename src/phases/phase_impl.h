/* What a phase plugin provides. Private to src/phases/. */
#ifndef CELADON_PHASE_IMPL_H
#define CELADON_PHASE_IMPL_H

#include "phases/phases.h"

/* Every plugin is Henyey-Greenstein's family: isotropic is g = 0. */
struct phase {
    double g; /* the mean cosine, in (-1, 1) */
};

/* A phase function of mean cosine g; NULL with err naming o when out of
 * memory. */
phase_t *phase_alloc(const scene_obj *o, double g, char *err, size_t errlen);

#endif
