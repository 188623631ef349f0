/* The baked surfaces' quads and lightmap layout. See room_surfaces.h. */
#include "museum/room_surfaces.h"

#include <math.h>

const char *const room_surface_names[ROOM_SURFACES] = {"Floor", "Ceiling", "Back wall", "Entrance wall",
                                                       "Left wall", "Right wall"};

void room_surfaces(const layout_t *l, quad_spec q[ROOM_SURFACES])
{
    double w = l->width / 2, d = l->depth / 2, h = l->height;
    q[ROOM_FLOOR] = (quad_spec){{-w, 0, d}, {2 * w, 0, 0}, {0, 0, -2 * d}};
    q[ROOM_CEILING] = (quad_spec){{-w, h, -d}, {2 * w, 0, 0}, {0, 0, 2 * d}};
    q[ROOM_BACK_WALL] = (quad_spec){{-w, 0, -d}, {2 * w, 0, 0}, {0, h, 0}};
    q[ROOM_ENTRANCE_WALL] = (quad_spec){{w, 0, d}, {-2 * w, 0, 0}, {0, h, 0}};
    q[ROOM_LEFT_WALL] = (quad_spec){{-w, 0, d}, {0, 0, -2 * d}, {0, h, 0}};
    q[ROOM_RIGHT_WALL] = (quad_spec){{w, 0, -d}, {0, 0, 2 * d}, {0, h, 0}};
}

void pedestal_faces(const layout_exhibit *e, quad_spec q[PEDESTAL_FACES])
{
    double s = e->width / 2, h = e->pedestal_height, x = e->centre.x, z = e->centre.z;
    q[0] = (quad_spec){{x - s, 0, z + s}, {2 * s, 0, 0}, {0, h, 0}};
    q[1] = (quad_spec){{x + s, 0, z - s}, {-2 * s, 0, 0}, {0, h, 0}};
    q[2] = (quad_spec){{x + s, 0, z + s}, {0, 0, -2 * s}, {0, h, 0}};
    q[3] = (quad_spec){{x - s, 0, z - s}, {0, 0, 2 * s}, {0, h, 0}};
    q[4] = (quad_spec){{x - s, h, z + s}, {2 * s, 0, 0}, {0, 0, -2 * s}};
}

static int texels(double len, double per_m, int lo, int hi)
{
    int t = (int)ceil(len * per_m);
    return t < lo ? lo : t > hi ? hi : t;
}

lightmap_layout lightmap_layout_for(const quad_spec *q, int n, double texels_per_m, int lo, int hi)
{
    double su = 0, sv = 0;
    for (int k = 0; k < n; k++)
        su = fmax(su, v3_len(q[k].du)), sv = fmax(sv, v3_len(q[k].dv));
    lightmap_layout m = {n, texels(su, texels_per_m, lo, hi), texels(sv, texels_per_m, lo, hi), 0, 0};
    m.width = n * (m.tile_w + 2);
    m.height = m.tile_h + 2;
    return m;
}

void lightmap_uv(const lightmap_layout *m, int k, double s, double t, double *u, double *v)
{
    *u = (k * (m->tile_w + 2) + 1 + s * m->tile_w) / m->width;
    *v = (1 + (1 - t) * m->tile_h) / m->height;
}

void lightmap_texel_st(const lightmap_layout *m, int x, int y, double *s, double *t)
{
    *s = (x + 0.5) / m->tile_w;
    *t = 1 - (y + 0.5) / m->tile_h;
}
