/* The levels of detail of a vessel's mesh (the paper's multi-resolution
 * meshes), chosen by screen-space error.
 *
 * A mesh of N angular segments whose rings are placed by mesh_rings at the
 * matching tolerance (mesh_ring_tolerance: the curvature domains of the
 * profile, refined until every chord is within it) departs from the exact
 * surface by about e(N) = 4.93 r_max / N^2. Seen from a distance d, that is
 * e(N) / (d LOD_PIXEL_ANGLE) pixels of a headset display; a level is good
 * enough from the distance where this falls to LOD_MAX_PIXELS. The finest
 * level is chosen for the nearest viewing distance, every next one has half
 * the segments (so it takes over four times farther away). */
#ifndef CELADON_MUSEUM_LOD_H
#define CELADON_MUSEUM_LOD_H

#include "celadon/bspline.h"
#include "celadon/mesh.h"

enum { LOD_MAX_LEVELS = 8, LOD_AUTO_LEVELS = 3, LOD_MIN_SEGMENTS = 8, LOD_MAX_SEGMENTS = 4096 };
/* A standalone headset shows about 20 pixels per degree. */
#define LOD_PIXEL_ANGLE (3.14159265358979323846 / 180.0 / 20.0)
#define LOD_MAX_PIXELS 1.0

typedef struct {
    int segments;
    double error;    /* m: the mesh's distance to the surface, e(N) */
    double distance; /* m: from the vessel's base, the nearest distance the level is used at (0 for the finest) */
    mesh_t mesh;     /* metres, the vessel's base at the origin, Y up, base cap */
} lod_level;

/* Levels for a profile (px) scaled to height_m (the rim at y = height_m),
 * finest first. segments[0..n_segments) gives the segment counts (any
 * order; repeated values count once); with n_segments = 0 they are chosen
 * for the nearest viewing distance nearest_m (LOD_AUTO_LEVELS levels).
 * Returns the number of levels written to out, or -1 (bad arguments, out of
 * memory). */
int lod_make(const bspline_t *profile, double height_m, const int *segments, int n_segments, double nearest_m,
             lod_level *out);
void lod_free(lod_level *levels, int n);

#endif
