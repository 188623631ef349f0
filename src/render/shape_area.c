/* Area sampling and lifetime of any shape, dispatching to meshes or
 * analytic shapes. */
#include "render/scene_impl.h"

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
