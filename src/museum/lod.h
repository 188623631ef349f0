/* The levels of detail of a vessel's mesh (the paper's multi-resolution
 * meshes), chosen by screen-space error.
 *
 * A level of N angular segments has a stated error E(N) = 2 r_max
 * (1 - cos(pi/N)), r_max the curve's own largest radius (in metres at the
 * displayed size), and departs from the exact surface by at most E(N):
 * - its angular chords, the sagitta r (1 - cos(pi/N)) of a ring of radius
 *   r, take at most E/2;
 * - its rings, the profile's curvature domains at a chord tolerance of E/2
 *   (curve_domains_by_curvature: the profile within E/2 of the polyline
 *   through the rings), take at most the other E/2.
 * Seen from a distance d, E is E / (d LOD_PIXEL_ANGLE) pixels of a headset
 * display; a level is good enough from the distance where this falls to
 * LOD_MAX_PIXELS. The finest level is chosen for the nearest viewing
 * distance, every next one has half the segments (so it takes over four
 * times farther away).
 *
 * The rings follow the chord bound alone, not mesh_rings' second criterion
 * on the shading normals (for renders that stand a mesh in for the exact
 * surface): on real reconstructions that criterion multiplied the rings by
 * 5 to 25 (a 30 cm jar had 12 400 rings, 1.5 million triangles, at an error
 * of 1 mm), and the glb's normals are stored as bytes anyway. */
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
    double error;    /* m: E(N), a bound on the mesh's distance to the exact surface */
    double distance; /* m: from the vessel's base, the nearest distance the level is used at (0 for the finest) */
    mesh_t mesh;     /* metres, the vessel's base at the origin, Y up, base cap */
} lod_level;

/* Levels for a profile (px) scaled to height_m (the rim at y = height_m),
 * finest first. segments[0..n_segments) gives the segment counts (any
 * order; repeated values count once); with n_segments = 0 they are chosen
 * for the nearest viewing distance nearest_m (LOD_AUTO_LEVELS levels).
 * Returns the number of levels written to out, or -1 (bad arguments, a
 * profile that is not a cubic B-spline (bspline_largest), out of
 * memory). */
int lod_make(const bspline_t *profile, double height_m, const int *segments, int n_segments, double nearest_m,
             lod_level *out);
void lod_free(lod_level *levels, int n);

#endif
