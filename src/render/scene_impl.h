/* The built scene: what src/render's scene build fills and its render loop
 * and queries read. Private to src/render/. */
#ifndef CELADON_SCENE_IMPL_H
#define CELADON_SCENE_IMPL_H

#include "bsdfs/bsdfs.h"
#include "celadon/scene.h"
#include "emitters/emitters.h"
#include "integrators/integrators.h"
#include "media/media.h"
#include "samplers/samplers.h"
#include "sensors/sensors.h"
#include "shapes/shapes.h"
#include "textures/textures.h"

struct scene {
    camera_t camera;
    film_settings film; /* its size is the camera's */
    sampler_t sampler;
    integrator_t *integrator;
    shape_list shapes;     /* in document order, each with its BSDF and area emitter */
    emitter_list emitters; /* area emitters in shape order, then the others in document order */
    bsdf_set bsdfs;
    texture_set textures;
    medium_set media;
    const medium_t *camera_medium; /* the sensor's <medium>, or NULL */
    uint64_t digest; /* scene_digest */
};

/* The digest of a scene built from desc (scene_digest.c). */
uint64_t scene_digest_compute(const scene_desc *desc, const struct scene *s, int mesh_segments);

#endif
