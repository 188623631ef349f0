/* The museum's diffuse surfaces whose light is baked (docs/museum.md,
 * "Light"): the floor, the ceiling, the four walls and every pedestal's five
 * faces, as quads in world coordinates, shared by museum.glb (their meshes)
 * and the bake (its texels), so a texel of a lightmap is where the glb
 * draws it.
 *
 * A lightmap holds a row of tiles, one per quad, each TILE_w x TILE_h
 * texels inside a one-texel gutter that repeats its border (so bilinear
 * filtering never mixes two faces). Rows of the image run down; a quad's
 * (s, t) = (0, 0) corner is its first corner, s along du, t along dv, and
 * t = 0 is the tile's bottom row. */
#ifndef CELADON_MUSEUM_ROOM_SURFACES_H
#define CELADON_MUSEUM_ROOM_SURFACES_H

#include "celadon/vecmath.h"
#include "museum/layout.h"

/* A quad corner + [0,1] du + [0,1] dv, facing du x dv. */
typedef struct {
    vec3 corner, du, dv;
} quad_spec;

enum { ROOM_FLOOR, ROOM_CEILING, ROOM_BACK_WALL, ROOM_ENTRANCE_WALL, ROOM_LEFT_WALL, ROOM_RIGHT_WALL, ROOM_SURFACES };
enum { PEDESTAL_FACES = 5 };

/* Texels per metre of the room's lightmaps (at most ROOM_TEXELS_MAX a
 * side) and of the pedestals' (at least PEDESTAL_TEXELS_MIN a side). */
#define ROOM_TEXELS_PER_M 16.0
#define ROOM_TEXELS_MAX 256
#define PEDESTAL_TEXELS_PER_M 48.0
#define PEDESTAL_TEXELS_MIN 8

/* The room's six surfaces, facing into the room, in the order above. */
void room_surfaces(const layout_t *l, quad_spec q[ROOM_SURFACES]);
extern const char *const room_surface_names[ROOM_SURFACES];

/* The pedestal's faces (front +z, back, right +x, left, top), facing out. */
void pedestal_faces(const layout_exhibit *e, quad_spec q[PEDESTAL_FACES]);

/* A lightmap of n quads, each a tile of tile_w x tile_h texels. */
typedef struct {
    int n, tile_w, tile_h;
    int width, height; /* of the image: n (tile_w + 2) x (tile_h + 2) */
} lightmap_layout;

/* The layout for n quads of the largest side `extent` m, at texels_per_m,
 * each tile side in [lo, hi] texels. */
lightmap_layout lightmap_layout_for(const quad_spec *q, int n, double texels_per_m, int lo, int hi);
/* The image coordinates (u right, v down, in [0,1]) of point (s, t) of quad k. */
void lightmap_uv(const lightmap_layout *m, int k, double s, double t, double *u, double *v);
/* The point (s, t) of quad k that texel (x, y) of its tile (x right, y down, inside the gutter) samples. */
void lightmap_texel_st(const lightmap_layout *m, int x, int y, double *s, double *t);

#endif
