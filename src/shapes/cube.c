/* Mitsuba's `cube`: [-1,1]^3 with flat faces and outward normals, as a mesh
 * of twelve triangles. Each face maps onto [0,1]^2 with Mitsuba's own
 * orientation (its cube's vertex table): u = (1 + su p[au]) / 2,
 * v = (1 + sv p[av]) / 2 with, per face,
 *   +z: u along +y, v along +x     -z: u along -y, v along +x
 *   +x: u along +y, v along -z     -x: u along +y, v along +z
 *   +y: u along -x, v along -z     -y: u along +z, v along +x
 * A checkerboard with an odd count per face is inverted on the x faces and
 * on -y under any other choice. */
#include "shapes/shape_impl.h"

static int cube_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                       size_t errlen)
{
    (void)opt, (void)to_world;
    if (shape_mesh_alloc(&sh->mesh, 24, 12) != 0)
        return scene_obj_error(o, err, errlen, "<shape type=\"%s\">: out of memory", o->type);
    /* (a, b, c): a x b = +c keeps the winding counter-clockwise from outside;
     * the negative face mirrors b. */
    shape_mesh_square_face(&sh->mesh, 0, 0, 1, 2, 1.0);
    shape_mesh_square_face(&sh->mesh, 1, 0, 1, 2, -1.0);
    shape_mesh_square_face(&sh->mesh, 2, 1, 2, 0, 1.0);
    shape_mesh_square_face(&sh->mesh, 3, 1, 2, 0, -1.0);
    shape_mesh_square_face(&sh->mesh, 4, 2, 0, 1, 1.0);
    shape_mesh_square_face(&sh->mesh, 5, 2, 0, 1, -1.0);
    /* per face (in the order above): au, su, av, sv */
    static const int uv_axes[6][4] = {{1, 1, 0, 1}, {1, -1, 0, 1}, {1, 1, 2, -1},
                                      {1, 1, 2, 1}, {0, -1, 2, -1}, {2, 1, 0, 1}};
    for (int v = 0; v < 24; v++) {
        const int *a = uv_axes[v / 4];
        const float *p = &sh->mesh.pos[3 * v];
        sh->mesh.uv[2 * v] = 0.5f * (1.0f + (float)a[1] * p[a[0]]);
        sh->mesh.uv[2 * v + 1] = 0.5f * (1.0f + (float)a[3] * p[a[2]]);
    }
    return 0;
}

static const scene_param_decl cube_params[] = {SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_cube = {
    .decl = {.cls = SCENE_SHAPE, .type = "cube", .params = cube_params, .children = shape_children},
    .create = cube_create,
};
