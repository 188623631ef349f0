/* Analytic shapes placed in the world by an affine to_world: accel traces
 * them in object space; hits move back to the world here. */
#include <math.h>

#include "shapes/shape_impl.h"

void shape_analytic_finish(const shape_t *sh, const shape_local_hit *lh, surface_hit *hit)
{
    hit->t = lh->t;
    hit->p = transform_point(&sh->to_world, lh->p);
    vec3 n = v3_norm(transform_normal(&sh->to_world, lh->n));
    if (sh->flip_normals)
        n = v3_neg(n);
    hit->ng = n;
    vec3 ns = n;
    if (sh->ops->shading_normal) {
        ns = v3_norm(transform_normal(&sh->to_world, sh->ops->shading_normal(sh->data, lh)));
        if (sh->flip_normals)
            ns = v3_neg(ns);
    }
    hit->sh = frame3_from_normal(ns);
    vec3 du, dv;
    sh->ops->tangents(sh->data, lh, &du, &dv);
    hit->dpdu = transform_vector(&sh->to_world, du);
    hit->dpdv = transform_vector(&sh->to_world, dv);
    hit->uv = lh->uv;
    hit->eps = surface_hit_eps(hit->p);
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

void shape_analytic_local_hit(const void *data, const accel_hit *ah, shape_local_hit *h)
{
    (void)data;
    h->t = ah->t;
    h->p = ah->p_obj;
    h->n = ah->n_obj;
    h->uv = ah->uv;
    h->part = (int)ah->part;
    h->param[0] = ah->param[0];
    h->param[1] = ah->param[1];
}
