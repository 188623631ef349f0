/* The film's metadata (film.h: film_metadata) in an OpenEXR header, both
 * ways. Private to src/render/ (exr_write.c writes it, exr_read.c reads it
 * back for the parts' merge). */
#ifndef CELADON_EXR_METADATA_H
#define CELADON_EXR_METADATA_H

#include <openexr.h>

#include "celadon/film.h"

/* Sets the attributes "spp", "seed", "renderer", "integrator", "camera",
 * "worldToCamera", "capDate" and "utcOffset" of the part (the
 * "celadon/..." ones are the writer's: film_info.h). */
exr_result_t exr_metadata_write(exr_context_t ctx, int part, const film_metadata *meta);

/* What exr_metadata_write wrote, and the sampler, scene digest, scene
 * path and command line of the "celadon/..." attributes: meta->spp is 0
 * when the header has no "spp", strings are empty where their attribute
 * is missing. */
void exr_metadata_read(exr_const_context_t ctx, int part, film_metadata *meta);

#endif
