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
    if (sh->is_mesh) {
        shape_mesh_transform(&sh->mesh, &to_world);
        sh->to_world = to_world;
    } else {
        sh->det = fabs(det3(&sh->to_world));
    }
    return 0;
}

/* The area as the mean of 1 / pdf over a stratified grid of area samples
 * (exact for a sphere, disk or cylinder under a similarity; light selection
 * needs no more). */
static double analytic_area(const shape_t *sh)
{
    enum { N = 64 };
    double sum = 0.0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            surface_hit h;
            double pdf;
            shape_sample_area(sh, v3((i + 0.5) / N, (j + 0.5) / N, (i * N + j + 0.5) / (N * N)), &h, &pdf);
            sum += pdf > 0.0 ? 1.0 / pdf : 0.0;
        }
    return sum / (N * N);
}

void shape_world_bounds(const shape_t *sh, vec3 *lo, vec3 *hi)
{
    *lo = v3(INFINITY, INFINITY, INFINITY);
    *hi = v3(-INFINITY, -INFINITY, -INFINITY);
    int n = sh->is_mesh ? sh->mesh.n_verts : 8;
    vec3 olo, ohi;
    if (!sh->is_mesh)
        sh->ops->bounds(sh->data, &olo, &ohi);
    for (int i = 0; i < n; i++) {
        /* a mesh's vertices are in world space; an analytic shape's object
         * bounds' corners placed */
        vec3 p = sh->is_mesh ? v3(sh->mesh.pos[3 * i], sh->mesh.pos[3 * i + 1], sh->mesh.pos[3 * i + 2])
                             : transform_point(&sh->to_world, v3(i & 1 ? ohi.x : olo.x, i & 2 ? ohi.y : olo.y,
                                                                 i & 4 ? ohi.z : olo.z));
        /* fmin and fmax would pass over a NaN: it spreads instead */
        *lo = v3(p.x < lo->x || p.x != p.x ? p.x : lo->x, p.y < lo->y || p.y != p.y ? p.y : lo->y,
                 p.z < lo->z || p.z != p.z ? p.z : lo->z);
        *hi = v3(p.x > hi->x || p.x != p.x ? p.x : hi->x, p.y > hi->y || p.y != p.y ? p.y : hi->y,
                 p.z > hi->z || p.z != p.z ? p.z : hi->z);
    }
}

/* World bounds and normal cone of an analytic shape: its flat normal if it
 * has one. */
static void analytic_extent(shape_t *sh)
{
    shape_world_bounds(sh, &sh->bounds_lo, &sh->bounds_hi);
    vec3 n;
    if (sh->ops->flat_normal && sh->ops->flat_normal(sh->data, &n)) {
        n = v3_norm(transform_normal(&sh->to_world, n));
        sh->normal_axis = sh->flip_normals ? v3_neg(n) : n;
        sh->normal_cos = 1.0;
    } else {
        sh->normal_axis = v3(0.0, 0.0, 1.0);
        sh->normal_cos = -1.0;
    }
}

int shape_prepare_sampling(shape_t *sh)
{
    if (sh->is_mesh) {
        if (shape_mesh_prepare_sampling(&sh->mesh) != 0)
            return -1;
        sh->area = sh->mesh.area;
        shape_mesh_extent(sh);
    } else {
        sh->area = analytic_area(sh);
        analytic_extent(sh);
    }
    return sh->area > 0.0 ? 0 : -1;
}

void shape_sample_from(const shape_t *sh, vec3 ref, vec3 u, surface_hit *hit, double *pdf)
{
    if (sh->solid_angle && (*pdf = sh->solid_angle->sample(sh, ref, v2(u.x, u.y), hit)) > 0.0)
        return;
    double pdf_area;
    shape_sample_area(sh, u, hit, &pdf_area);
    vec3 d = v3_sub(hit->p, ref);
    double dist2 = v3_dot(d, d), cos_l = fabs(v3_dot(hit->ng, d));
    *pdf = dist2 > 0.0 && cos_l > 0.0 ? pdf_area * dist2 * sqrt(dist2) / cos_l : 0.0;
}

bool shape_faces_away(const shape_t *sh, vec3 ref)
{
    vec3 n = sh->plane_n;
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0)
        return false;
    /* For a point p of the shape, with unit normal ng: dot(ng, p - ref) =
     * dot(n, p - o) - h + dot(ng - n, p - ref) >= -plane_off - h -
     * plane_turn |p - ref|, and |p - ref| <= |ref - o|_1 + plane_extent;
     * the slack (1e-9 of that, 1e-12 of the coordinates) covers the
     * rounding of p and of these sums. */
    vec3 o = sh->plane_o, r = v3_sub(ref, o);
    double h = v3_dot(n, r);
    double reach = fabs(r.x) + fabs(r.y) + fabs(r.z) + sh->plane_extent;
    double size = fabs(o.x) + fabs(o.y) + fabs(o.z) + fabs(ref.x) + fabs(ref.y) + fabs(ref.z);
    return -h > 2.0 * sh->plane_off + (sh->plane_turn + 1e-9) * reach + 1e-12 * size;
}

double shape_pdf_from(const shape_t *sh, vec3 ref, const surface_hit *hit)
{
    double pdf;
    if (sh->solid_angle && (pdf = sh->solid_angle->pdf(sh, ref)) > 0.0)
        return pdf;
    vec3 d = v3_sub(hit->p, ref);
    double dist2 = v3_dot(d, d), cos_l = fabs(v3_dot(hit->ng, d));
    return dist2 > 0.0 && cos_l > 0.0 ? shape_pdf_area(sh, hit) * dist2 * sqrt(dist2) / cos_l : 0.0;
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

bsdf_query shape_bsdf_query(const surface_hit *hit, vec3 dir, transport_mode mode)
{
    bsdf_query q = {.wi = frame3_to_local(hit->sh, v3_neg(dir)), .uv = hit->uv, .mode = mode};
    q.dpdu = frame3_to_local(hit->sh, hit->dpdu);
    q.dpdv = frame3_to_local(hit->sh, hit->dpdv);
    q.ng = frame3_to_local(hit->sh, hit->ng);
    const shape_t *s = hit->shape;
    if (s->is_mesh && s->mesh.attrs.count > 0) {
        q.mesh = &s->mesh.attrs;
        q.prim = hit->prim;
        q.b1 = hit->local.param[0], q.b2 = hit->local.param[1];
    }
    return q;
}

void shape_free(shape_t *sh)
{
    if (sh->is_mesh)
        shape_mesh_data_free(&sh->mesh);
    else if (sh->ops)
        sh->ops->destroy(sh->data);
}
