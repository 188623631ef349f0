/* What a volume plugin provides. Private to src/volumes/. */
#ifndef CELADON_VOLUME_IMPL_H
#define CELADON_VOLUME_IMPL_H

#include "celadon/transform.h"
#include "volumes/volumes.h"

typedef enum { VOLUME_CLAMP, VOLUME_REPEAT, VOLUME_MIRROR } volume_wrap;

struct volume {
    /* constant: value everywhere (grid NULL) */
    rgb value;
    bool bounded; /* a <volume>: its box is the unit cube that to_local maps world points into */
    /* grid: nx * ny * nz voxels of channels (1 or 3) floats, x fastest,
     * voxel (i, j, k) centred at ((i + 0.5) / nx, ...) of the unit cube */
    float *grid;
    int nx, ny, nz, channels;
    transform4 to_local;
    volume_wrap wrap;
    bool nearest;
    double max;
};

/* A zeroed volume; NULL with err naming o when out of memory. */
volume_t *volume_alloc(const scene_obj *o, char *err, size_t errlen);

#endif
