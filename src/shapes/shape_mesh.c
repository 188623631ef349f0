/* Triangle meshes in world space: hit completion from Embree's barycentrics
 * (smooth shading normals and uvs where the file has them), placement by
 * to_world, sampling by area through a CDF over triangle areas, and what the
 * mesh plugins share to build theirs. */
#include <stdlib.h>
#include <string.h>

#include "shapes/shape_impl.h"

static vec3 mesh_pos(const shape_mesh_data *m, unsigned v)
{
    return v3(m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
}

/* What a sampled point needs (shape_mesh_point) of the hit on triangle tri
 * at barycentrics (b1, b2): the point, the geometric normal, the texture
 * coordinates; the triangle's edges and its vertices' uvs for the rest. */
static void mesh_point(const shape_t *sh, const unsigned *v, double b1, double b2, surface_hit *hit, vec3 *e1,
                       vec3 *e2)
{
    const shape_mesh_data *m = &sh->mesh;
    double b0 = 1.0 - b1 - b2;
    vec3 p0 = mesh_pos(m, v[0]), p1 = mesh_pos(m, v[1]), p2 = mesh_pos(m, v[2]);
    hit->p = v3_add(v3_add(v3_scale(p0, b0), v3_scale(p1, b1)), v3_scale(p2, b2));
    *e1 = v3_sub(p1, p0), *e2 = v3_sub(p2, p0);
    vec3 ng = v3_norm(v3_cross(*e1, *e2));
    hit->ng = sh->flip_normals ? v3_neg(ng) : ng;
    if (m->uv) {
        const float *t0 = &m->uv[2 * v[0]], *t1 = &m->uv[2 * v[1]], *t2 = &m->uv[2 * v[2]];
        hit->uv = v2(b0 * t0[0] + b1 * t1[0] + b2 * t2[0], b0 * t0[1] + b1 * t1[1] + b2 * t2[1]);
    } else {
        hit->uv = v2(b1, b2);
    }
    hit->eps = surface_hit_eps(hit->p);
    hit->local.param[0] = b1, hit->local.param[1] = b2; /* for mesh attributes (shape_bsdf_query) */
}

void shape_mesh_point(const shape_t *sh, int tri, double b1, double b2, surface_hit *hit)
{
    vec3 e1, e2;
    mesh_point(sh, &sh->mesh.tri[3 * tri], b1, b2, hit, &e1, &e2);
    hit->t = 0.0;
    hit->prim = tri;
}

void shape_mesh_finish(const shape_t *sh, int tri, double b1, double b2, double t, surface_hit *hit)
{
    const shape_mesh_data *m = &sh->mesh;
    const unsigned *v = &m->tri[3 * tri];
    vec3 e1, e2;
    mesh_point(sh, v, b1, b2, hit, &e1, &e2);
    hit->t = t;
    hit->prim = tri;
    vec3 ns = hit->ng; /* flat shading where the mesh has no normals */
    if (m->nrm && m->nrm_per_face) { /* the triangle's three are equal and unit: no interpolation */
        vec3 n = v3(m->nrm[3 * v[0]], m->nrm[3 * v[0] + 1], m->nrm[3 * v[0] + 2]);
        ns = sh->flip_normals ? v3_neg(n) : n;
    } else if (m->nrm) {
        const double b[3] = {1.0 - b1 - b2, b1, b2};
        vec3 n = v3(0, 0, 0);
        for (int k = 0; k < 3; k++)
            n = v3_add(n, v3_scale(v3(m->nrm[3 * v[k]], m->nrm[3 * v[k] + 1], m->nrm[3 * v[k] + 2]), b[k]));
        if (v3_len(n) > 1e-12)
            ns = sh->flip_normals ? v3_neg(v3_norm(n)) : v3_norm(n);
    }
    hit->sh = frame3_from_normal(ns);
    /* Without texture coordinates the parametrisation is barycentric, as in
     * Mitsuba: dp/du = p1 - p0, dp/dv = p2 - p0. */
    hit->dpdu = e1, hit->dpdv = e2;
    if (m->uv) {
        const float *t0 = &m->uv[2 * v[0]], *t1 = &m->uv[2 * v[1]], *t2 = &m->uv[2 * v[2]];
        /* The change of variables from barycentrics to uv. */
        vec2 d0 = v2(t1[0] - t0[0], t1[1] - t0[1]), d1 = v2(t2[0] - t0[0], t2[1] - t0[1]);
        double det = d0.x * d1.y - d0.y * d1.x, inv = det != 0.0 ? 1.0 / det : 0.0;
        hit->dpdu = v3_scale(v3_sub(v3_scale(e1, d1.y), v3_scale(e2, d0.y)), inv);
        hit->dpdv = v3_scale(v3_sub(v3_scale(e2, d0.x), v3_scale(e1, d1.x)), inv);
    }
}

unsigned shape_mesh_add(const shape_t *sh, accel_t *acc, char *err, size_t errlen)
{
    const shape_mesh_data *m = &sh->mesh;
    mesh_t view = {m->n_verts, m->n_tris, m->pos, m->nrm, m->uv, m->tri};
    return accel_add_mesh(acc, &view, NULL, err, errlen);
}

/* Whether each triangle's three vertex normals are the same (a rectangle's,
 * a cube's faces): the shading normal is then that normal wherever the
 * triangle is hit. */
static bool normals_per_face(const shape_mesh_data *m)
{
    for (int t = 0; t < m->n_tris && m->nrm; t++) {
        const unsigned *v = &m->tri[3 * t];
        for (int k = 1; k < 3; k++)
            if (memcmp(&m->nrm[3 * v[0]], &m->nrm[3 * v[k]], 3 * sizeof *m->nrm) != 0)
                return false;
    }
    return m->nrm != NULL;
}

void shape_mesh_transform(shape_mesh_data *m, const transform4 *to_world)
{
    for (int i = 0; i < m->n_verts; i++) {
        vec3 p = transform_point(to_world, mesh_pos(m, (unsigned)i));
        m->pos[3 * i] = (float)p.x, m->pos[3 * i + 1] = (float)p.y, m->pos[3 * i + 2] = (float)p.z;
        if (m->nrm) {
            vec3 n = v3_norm(transform_normal(to_world, v3(m->nrm[3 * i], m->nrm[3 * i + 1], m->nrm[3 * i + 2])));
            m->nrm[3 * i] = (float)n.x, m->nrm[3 * i + 1] = (float)n.y, m->nrm[3 * i + 2] = (float)n.z;
        }
    }
    m->nrm_per_face = normals_per_face(m);
}

static double tri_area(const shape_mesh_data *m, int t)
{
    const unsigned *v = &m->tri[3 * t];
    vec3 p0 = mesh_pos(m, v[0]);
    return 0.5 * v3_len(v3_cross(v3_sub(mesh_pos(m, v[1]), p0), v3_sub(mesh_pos(m, v[2]), p0)));
}

int shape_mesh_prepare_sampling(shape_mesh_data *m)
{
    double *a = malloc(sizeof *a * (size_t)(m->n_tris > 0 ? m->n_tris : 1));
    if (!a)
        return -1;
    m->area = 0.0;
    for (int t = 0; t < m->n_tris; t++)
        m->area += a[t] = tri_area(m, t);
    int rc = distribution1d_init(&m->area_cdf, a, m->n_tris);
    free(a);
    return rc != 0 || !(m->area > 0.0) ? -1 : 0;
}

/* Every triangle's unit normal within 1e-6 of one axis (a rectangle, a
 * flat polygon): the plane through vertex 0 with that normal, how far the
 * vertices lie off it and the normals, as mesh_point computes them, off
 * the axis (shape_faces_away's margins). */
static void mesh_plane(shape_t *sh)
{
    const shape_mesh_data *m = &sh->mesh;
    vec3 n = sh->normal_axis, o = mesh_pos(m, 0);
    sh->plane_n = v3(0.0, 0.0, 0.0);
    if (!(sh->normal_cos > 1.0 - 1e-6))
        return;
    double off = 0.0, turn = 0.0;
    for (int i = 0; i < m->n_verts; i++)
        off = fmax(off, fabs(v3_dot(n, v3_sub(mesh_pos(m, (unsigned)i), o))));
    for (int t = 0; t < m->n_tris; t++) {
        const unsigned *v = &m->tri[3 * t];
        vec3 p0 = mesh_pos(m, v[0]), c = v3_cross(v3_sub(mesh_pos(m, v[1]), p0), v3_sub(mesh_pos(m, v[2]), p0));
        if (!(v3_len(c) > 0.0))
            continue; /* no area: never sampled */
        vec3 ng = v3_norm(c);
        turn = fmax(turn, v3_len(v3_sub(sh->flip_normals ? v3_neg(ng) : ng, n)));
    }
    if (!(turn < 1e-6) || !isfinite(off))
        return;
    sh->plane_o = o, sh->plane_n = n;
    sh->plane_off = off, sh->plane_turn = turn;
    sh->plane_extent = v3_len(v3_sub(sh->bounds_hi, sh->bounds_lo));
}

void shape_mesh_extent(shape_t *sh)
{
    const shape_mesh_data *m = &sh->mesh;
    shape_world_bounds(sh, &sh->bounds_lo, &sh->bounds_hi);
    /* The cone around the area-weighted mean normal that holds every face
     * normal; all directions when the faces turn every way. */
    vec3 sum = v3(0.0, 0.0, 0.0);
    for (int t = 0; t < m->n_tris; t++) {
        const unsigned *v = &m->tri[3 * t];
        vec3 p0 = mesh_pos(m, v[0]);
        sum = v3_add(sum, v3_cross(v3_sub(mesh_pos(m, v[1]), p0), v3_sub(mesh_pos(m, v[2]), p0)));
    }
    vec3 axis = v3_norm(sum);
    double cos_min = v3_len(sum) > 0.0 ? 1.0 : -1.0;
    for (int t = 0; t < m->n_tris && cos_min > -1.0; t++) {
        const unsigned *v = &m->tri[3 * t];
        vec3 p0 = mesh_pos(m, v[0]);
        vec3 n = v3_norm(v3_cross(v3_sub(mesh_pos(m, v[1]), p0), v3_sub(mesh_pos(m, v[2]), p0)));
        if (v3_len(n) > 0.0)
            cos_min = fmin(cos_min, v3_dot(axis, n) - 1e-9);
    }
    sh->normal_axis = v3_len(sum) > 0.0 ? (sh->flip_normals ? v3_neg(axis) : axis) : v3(0.0, 0.0, 1.0);
    sh->normal_cos = fmax(-1.0, cos_min);
    mesh_plane(sh);
}

void shape_mesh_sample(const shape_t *sh, vec3 u, surface_hit *hit, double *pdf_area)
{
    const shape_mesh_data *m = &sh->mesh;
    double reuse;
    int t = distribution1d_sample_discrete(&m->area_cdf, u.z, NULL, &reuse);
    vec2 b = warp_square_to_uniform_triangle(v2(u.x, u.y));
    shape_mesh_point(sh, t, b.x, b.y, hit);
    *pdf_area = 1.0 / m->area;
}

void shape_mesh_data_free(shape_mesh_data *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->uv);
    free(m->tri);
    texture_mesh_free(&m->attrs);
    if (m->area_cdf.cdf)
        distribution1d_free(&m->area_cdf);
    memset(m, 0, sizeof *m);
}

/* Area-weighted vertex normals from the faces. */
static int smooth_normals(shape_mesh_data *m)
{
    free(m->nrm);
    m->nrm = calloc((size_t)m->n_verts * 3 + 1, sizeof *m->nrm);
    if (!m->nrm)
        return -1;
    double *acc = calloc((size_t)m->n_verts * 3 + 1, sizeof *acc);
    if (!acc)
        return -1;
    for (int t = 0; t < m->n_tris; t++) {
        const unsigned *v = &m->tri[3 * t];
        vec3 p0 = mesh_pos(m, v[0]);
        vec3 n = v3_cross(v3_sub(mesh_pos(m, v[1]), p0), v3_sub(mesh_pos(m, v[2]), p0)); /* area-weighted */
        for (int k = 0; k < 3; k++)
            acc[3 * v[k]] += n.x, acc[3 * v[k] + 1] += n.y, acc[3 * v[k] + 2] += n.z;
    }
    for (int i = 0; i < m->n_verts; i++) {
        vec3 n = v3_norm(v3(acc[3 * i], acc[3 * i + 1], acc[3 * i + 2]));
        m->nrm[3 * i] = (float)n.x, m->nrm[3 * i + 1] = (float)n.y, m->nrm[3 * i + 2] = (float)n.z;
    }
    free(acc);
    return 0;
}

int shape_mesh_from_file(scene_obj *o, int rc, const char *why, shape_t *sh, char *err, size_t errlen)
{
    if (rc == 0 && scene_obj_bool(o, "face_normals", false)) {
        free(sh->mesh.nrm);
        sh->mesh.nrm = NULL;
    } else if (rc == 0 && !sh->mesh.nrm && smooth_normals(&sh->mesh) != 0) {
        rc = -1, why = "out of memory";
    }
    if (rc != 0)
        return scene_obj_error(o, err, errlen, "<shape type=\"%s\">: %s", o->type, why);
    return 0;
}

int shape_mesh_alloc(shape_mesh_data *m, int nv, int nt)
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

void shape_mesh_square_face(shape_mesh_data *m, int f, int a, int b, int c, double s)
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
