/* Analytic shapes placed in the world by an affine to_world: rays move to
 * object space (t is unchanged by an affine map), hits move back. */
#include <math.h>

#include "render/scene_impl.h"

static double max_abs3(vec3 p) { return fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z))); }

void shape_analytic_finish(const shape_t *sh, const shape_local_hit *lh, surface_hit *hit)
{
    hit->t = lh->t;
    hit->p = transform_point(&sh->to_world, lh->p);
    vec3 n = v3_norm(transform_normal(&sh->to_world, lh->n));
    if (sh->flip_normals)
        n = v3_neg(n);
    hit->ng = n;
    hit->sh = frame3_from_normal(n);
    hit->uv = lh->uv;
    /* Double-precision hits are accurate to ~1e-12 relative; the offset only
     * has to clear the root polishing tolerance of the SOR solver. */
    hit->eps = 1e-7 * (1.0 + max_abs3(hit->p));
    hit->prim = lh->part;
    hit->local = *lh;
}

/* dA_world = |det M| |M^-T n| dA_object for a unit object normal n. */
double shape_analytic_pdf_area(const shape_t *sh, const shape_local_hit *lh)
{
    double jac = sh->det * v3_len(transform_normal(&sh->to_world, lh->n));
    double pdf = sh->ops->pdf(sh->data, lh);
    return jac > 0.0 ? pdf / jac : 0.0;
}

int shape_analytic_intersect(const shape_t *sh, const ray3 *r, double tmin, double tmax, surface_hit *hit)
{
    ray3 lr = {transform_point(&sh->to_object, r->o), transform_vector(&sh->to_object, r->d)};
    shape_local_hit lh;
    if (!sh->ops->intersect(sh->data, &lr, tmin, tmax, &lh))
        return 0;
    shape_analytic_finish(sh, &lh, hit);
    return 1;
}
