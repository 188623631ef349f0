/* What every shape shares: building one from its <shape> object through its
 * plugin and placing it by to_world, sampling by area, and its lifetime. */
#include <stdio.h>
#include <string.h>

#include "shapes/shape_impl.h"

const scene_child_decl shape_children[] = {
    {SCENE_BSDF, 0, 1, NULL},
    {SCENE_EMITTER, 0, 1, "area"},
    {SCENE_SCENE, 0, 0, NULL},
};

static double det3(const transform4 *t)
{
    const double(*m)[4] = t->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

int shape_create(scene_obj *o, const transform4 *outer, const shape_options *opt, shape_t *sh, char *err,
                 size_t errlen)
{
    memset(sh, 0, sizeof *sh);
    sh->file = o->file;
    sh->line = o->line;
    sh->flip_normals = scene_obj_bool(o, "flip_normals", false);
    transform4 own = scene_obj_transform(o, "to_world");
    transform4 to_world = outer ? transform_compose(outer, &own) : own;
    const shape_plugin *plugin = shape_plugin_find(o->type);
    if (!plugin)
        return scene_obj_error(o, err, errlen, "unsupported shape '%s'", o->type);
    sh->type = plugin->decl.type;
    sh->is_mesh = true;
    if (plugin->create(o, opt, &to_world, sh, err, errlen) != 0) {
        shape_free(sh);
        return -1;
    }
    if (sh->is_mesh)
        shape_mesh_transform(&sh->mesh, &to_world);
    else
        sh->det = fabs(det3(&sh->to_world));
    return 0;
}

int shape_prepare_sampling(shape_t *sh)
{
    return sh->is_mesh ? shape_mesh_prepare_sampling(&sh->mesh) : 0;
}

void shape_sample_area(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area)
{
    if (sh->is_mesh) {
        shape_mesh_sample(sh, u, hit, pdf_area);
        return;
    }
    shape_local_hit lh;
    double pdf_obj;
    sh->ops->sample(sh->data, u, &lh, &pdf_obj);
    shape_analytic_finish(sh, &lh, hit);
    *pdf_area = shape_analytic_pdf_area(sh, &lh);
}

double shape_pdf_area(const shape_t *sh, const surface_hit *hit)
{
    return sh->is_mesh ? 1.0 / sh->mesh.area : shape_analytic_pdf_area(sh, &hit->local);
}

void shape_free(shape_t *sh)
{
    if (sh->is_mesh)
        shape_mesh_data_free(&sh->mesh);
    else if (sh->ops)
        sh->ops->destroy(sh->data);
}
