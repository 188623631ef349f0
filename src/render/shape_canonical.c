/* Mitsuba's canonical flat shapes as object-space meshes: `rectangle`
 * ([-1,1]^2 at z = 0, normal +z, uv = ((x+1)/2, (y+1)/2)) and `cube`
 * ([-1,1]^3, flat faces with outward normals). */
#include <stdlib.h>
#include <string.h>

#include "render/scene_impl.h"

static int mesh_alloc(shape_mesh_data *m, int nv, int nt)
{
    memset(m, 0, sizeof *m);
    m->n_verts = nv, m->n_tris = nt;
    m->pos = calloc((size_t)nv * 3 + 1, sizeof(float));
    m->nrm = calloc((size_t)nv * 3, sizeof(float));
    m->uv = calloc((size_t)nv * 2, sizeof(float));
    m->tri = calloc((size_t)nt * 3, sizeof(unsigned));
    if (m->pos && m->nrm && m->uv && m->tri)
        return 0;
    shape_mesh_data_free(m);
    return -1;
}

/* Writes face f: the square spanned by axes a, b at +-1 along axis c (sign s),
 * counter-clockwise seen from outside. */
static void square_face(shape_mesh_data *m, int f, int a, int b, int c, double s)
{
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; k++) {
        int v = 4 * f + k;
        double p[3];
        p[a] = corner[k][0], p[b] = s * corner[k][1], p[c] = s;
        for (int i = 0; i < 3; i++) {
            m->pos[3 * v + i] = (float)p[i];
            m->nrm[3 * v + i] = i == c ? (float)s : 0.0f;
        }
        m->uv[2 * v] = (float)(0.5 * (corner[k][0] + 1.0));
        m->uv[2 * v + 1] = (float)(0.5 * (corner[k][1] + 1.0));
    }
    unsigned base = 4u * (unsigned)f;
    const unsigned idx[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++)
        m->tri[6 * f + i] = base + idx[i];
}

int shape_rectangle_mesh(shape_mesh_data *m)
{
    if (mesh_alloc(m, 4, 2) != 0)
        return -1;
    square_face(m, 0, 0, 1, 2, 1.0);
    for (int v = 0; v < 4; v++) /* the rectangle lies in z = 0 */
        m->pos[3 * v + 2] = 0.0f;
    return 0;
}

int shape_cube_mesh(shape_mesh_data *m)
{
    if (mesh_alloc(m, 24, 12) != 0)
        return -1;
    /* (a, b, c): a x b = +c keeps the winding counter-clockwise from outside;
     * the negative face mirrors b. */
    square_face(m, 0, 0, 1, 2, 1.0);
    square_face(m, 1, 0, 1, 2, -1.0);
    square_face(m, 2, 1, 2, 0, 1.0);
    square_face(m, 3, 1, 2, 0, -1.0);
    square_face(m, 4, 2, 0, 1, 1.0);
    square_face(m, 5, 2, 0, 1, -1.0);
    return 0;
}
