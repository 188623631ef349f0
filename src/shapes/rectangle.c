/* Mitsuba's `rectangle`: [-1,1]^2 in the z = 0 plane, normal +z,
 * uv = ((x+1)/2, (y+1)/2), as a mesh of two triangles. */
#include "shapes/shape_impl.h"

static int rectangle_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                            char *err, size_t errlen)
{
    (void)opt, (void)to_world;
    if (shape_mesh_alloc(&sh->mesh, 4, 2) != 0)
        return scene_obj_error(o, err, errlen, "<shape type=\"%s\">: out of memory", o->type);
    shape_mesh_square_face(&sh->mesh, 0, 0, 1, 2, 1.0);
    for (int v = 0; v < 4; v++) /* the rectangle lies in z = 0 */
        sh->mesh.pos[3 * v + 2] = 0.0f;
    return 0;
}

static const scene_param_decl rectangle_params[] = {SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_rectangle = {
    .decl = {.cls = SCENE_SHAPE, .type = "rectangle", .params = rectangle_params, .children = shape_children},
    .create = rectangle_create,
};
