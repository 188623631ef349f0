/* Revolving a profile curve into a triangle mesh (the layout is in mesh.h). */
#include "celadon/mesh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void mesh_free(mesh_t *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->uv);
    free(m->tri);
    memset(m, 0, sizeof *m);
}

/* The outward unit normal of the profile in the (r, h) half-plane, (h', -r')
 * normalised. Where the derivative vanishes (a cusp, or repeated control
 * points) or overflows, the direction comes from a small central chord
 * instead; failing that, the radial direction. */
static vec2 profile_normal(const bspline_t *c, double u, vec2 d1)
{
    double len = v2_len(d1);
    if (!(len > 1e-12) || !isfinite(len)) {
        double lo = c->knots[0], hi = c->knots[bspline_n_knots(c) - 1], du = 1e-6 * (hi - lo);
        double ua = u - du < lo ? lo : u - du, ub = u + du > hi ? hi : u + du;
        d1 = v2_sub(bspline_eval(c, ub), bspline_eval(c, ua));
        len = v2_len(d1);
        if (!(len > 0.0) || !isfinite(len))
            return v2(1.0, 0.0);
    }
    return v2(d1.y / len, -d1.x / len);
}

/* Texture u (docs/conventions.md): 1 - phi/pi on [0, pi], phi/pi - 1 on [pi, 2 pi]. */
static double texture_u(double phi) { return phi <= M_PI ? 1.0 - phi / M_PI : phi / M_PI - 1.0; }

static int rings_valid(const bspline_t *c, const double *u, int n)
{
    double lo = c->knots[0], hi = c->knots[bspline_n_knots(c) - 1];
    for (int i = 0; i < n; i++) {
        if (!isfinite(u[i]) || u[i] < lo || u[i] > hi)
            return 0;
        if (i > 0 && !(u[i] > u[i - 1]))
            return 0;
    }
    return 1;
}

/* One ring of vertices: radius r and height y (object space), normal (nr, ny)
 * in the half-plane, texture v. cs/sn/tu: per-segment cos, sin, texture u. */
static void emit_ring(mesh_t *m, int first, int segments, double r, double y, double nr, double ny, double v,
                      const double *cs, const double *sn, const float *tu)
{
    float *p = m->pos + 3 * (size_t)first, *n = m->nrm + 3 * (size_t)first, *t = m->uv + 2 * (size_t)first;
    float fy = (float)y, fny = (float)ny, fv = (float)v;
    for (int j = 0; j < segments; j++) {
        p[3 * j] = (float)(r * cs[j]);
        p[3 * j + 1] = fy;
        p[3 * j + 2] = (float)(r * sn[j]);
        n[3 * j] = (float)(nr * cs[j]);
        n[3 * j + 1] = fny;
        n[3 * j + 2] = (float)(nr * sn[j]);
        t[2 * j] = tu[j];
        t[2 * j + 1] = fv;
    }
}

/* A cap: a copy of the ring at (r, y) with normal (0, ny, 0), and a fan wound
 * counter-clockwise as seen from the side ny points to, around one centre
 * vertex per segment: the centre of a polar texture map has every u, so each
 * triangle's centre takes its own segment's middle u (one shared centre at
 * u = 0.5 would drag the cap's texture toward the u = 0.5 meridian). */
static void emit_cap(mesh_t *m, int *nv, int *nt, int segments, double r, double y, double ny, double v,
                     const double *cs, const double *sn, const float *tu)
{
    int ring = *nv, centre = ring + segments;
    emit_ring(m, ring, segments, r, y, 0.0, ny, v, cs, sn, tu);
    uint32_t *f = m->tri + 3 * (size_t)*nt;
    for (int j = 0; j < segments; j++) {
        int jn = j + 1 == segments ? 0 : j + 1;
        float *p = m->pos + 3 * (size_t)(centre + j), *n = m->nrm + 3 * (size_t)(centre + j);
        float *t = m->uv + 2 * (size_t)(centre + j);
        p[0] = 0.0f, p[1] = (float)y, p[2] = 0.0f;
        n[0] = 0.0f, n[1] = (float)ny, n[2] = 0.0f;
        t[0] = 0.5f * (tu[j] + tu[jn]), t[1] = (float)v;
        uint32_t a = (uint32_t)(ring + j), b = (uint32_t)(ring + jn);
        f[3 * j] = (uint32_t)(centre + j);
        /* (centre, j, j+1) faces -Y: see the winding note in mesh_revolve. */
        f[3 * j + 1] = ny < 0 ? a : b;
        f[3 * j + 2] = ny < 0 ? b : a;
    }
    *nv += 2 * segments;
    *nt += segments;
}

int mesh_revolve(const bspline_t *profile, const double *u_rings, int n_rings, double height, int segments,
                 unsigned caps, mesh_t *out)
{
    memset(out, 0, sizeof *out);
    if (!profile || bspline_validate(profile) || n_rings < 2 || segments < 3 || !isfinite(height) ||
        !(height > 0.0) || (u_rings && !rings_valid(profile, u_rings, n_rings)))
        return -1;
    double ulo = profile->knots[0], uhi = profile->knots[bspline_n_knots(profile) - 1];
    double h_rim = bspline_eval(profile, uhi).y;
    if (!(h_rim > 0.0) || !isfinite(h_rim))
        return -1;
    double scale = height / h_rim;
    /* The curve lies in the hull of its control points: if they fit in float
     * range after scaling, every vertex does. */
    for (int i = 0; i < profile->n_ctrl; i++)
        if (!(fabs(profile->ctrl[i].x) * scale < 0.5 * FLT_MAX) || !(fabs(profile->ctrl[i].y) * scale < 0.5 * FLT_MAX))
            return -1;

    vec2 d_first[2], d_last[2];
    bspline_eval_derivs(profile, u_rings ? u_rings[0] : ulo, 1, d_first);
    bspline_eval_derivs(profile, u_rings ? u_rings[n_rings - 1] : uhi, 1, d_last);
    int cap_base = (caps & MESH_CAP_BASE) && d_first[0].x != 0.0;
    int cap_mouth = (caps & MESH_CAP_MOUTH) && d_last[0].x != 0.0;
    long long nv = (long long)n_rings * segments + (cap_base + cap_mouth) * 2LL * segments;
    long long nt = 2LL * segments * (n_rings - 1) + (long long)(cap_base + cap_mouth) * segments;
    if (nv > INT32_MAX || 3 * nt > INT32_MAX)
        return -1;

    out->pos = malloc((size_t)(3 * nv + 1) * sizeof *out->pos);
    out->nrm = malloc((size_t)(3 * nv) * sizeof *out->nrm);
    out->uv = malloc((size_t)(2 * nv) * sizeof *out->uv);
    out->tri = malloc((size_t)(3 * nt) * sizeof *out->tri);
    double *cs = malloc((size_t)segments * 2 * sizeof *cs);
    float *tu = malloc((size_t)segments * sizeof *tu);
    if (!out->pos || !out->nrm || !out->uv || !out->tri || !cs || !tu) {
        free(cs);
        free(tu);
        mesh_free(out);
        return -1;
    }
    out->pos[3 * nv] = 0.0f;
    double *sn = cs + segments;
    for (int j = 0; j < segments; j++) {
        double phi = 2.0 * M_PI * j / segments;
        cs[j] = cos(phi);
        sn[j] = sin(phi);
        tu[j] = (float)texture_u(phi);
    }

    for (int i = 0; i < n_rings; i++) {
        double u = u_rings ? u_rings[i] : (i == n_rings - 1 ? uhi : ulo + (uhi - ulo) * i / (n_rings - 1));
        vec2 d[2];
        bspline_eval_derivs(profile, u, 1, d);
        vec2 nrm = profile_normal(profile, u, d[1]);
        emit_ring(out, i * segments, segments, d[0].x * scale, d[0].y * scale, nrm.x, nrm.y, d[0].y / h_rim, cs,
                  sn, tu);
    }
    /* Winding: at phi = 0 the ring direction dP/dphi is +Z and the profile
     * direction dP/du is (r', h', 0); (dP/du) x (dP/dphi) = (h', -r', 0) is the
     * outward normal, so (ring i, j), (ring i+1, j), (ring i, j+1) is
     * counter-clockwise from outside. For a cap, (centre, j, j+1) has normal
     * P_j x P_{j+1} = -Y. */
    uint32_t *f = out->tri;
    for (int i = 0; i + 1 < n_rings; i++) {
        uint32_t r0 = (uint32_t)(i * segments), r1 = r0 + (uint32_t)segments;
        for (int j = 0; j < segments; j++) {
            uint32_t jn = j + 1 == segments ? 0u : (uint32_t)j + 1u;
            f[0] = r0 + (uint32_t)j, f[1] = r1 + (uint32_t)j, f[2] = r0 + jn;
            f[3] = r0 + jn, f[4] = r1 + (uint32_t)j, f[5] = r1 + jn;
            f += 6;
        }
    }
    int n_v = n_rings * segments, n_t = 2 * segments * (n_rings - 1);
    if (cap_base)
        emit_cap(out, &n_v, &n_t, segments, d_first[0].x * scale, d_first[0].y * scale, -1.0, d_first[0].y / h_rim,
                 cs, sn, tu);
    if (cap_mouth)
        emit_cap(out, &n_v, &n_t, segments, d_last[0].x * scale, d_last[0].y * scale, 1.0, d_last[0].y / h_rim, cs,
                 sn, tu);
    out->n_verts = n_v;
    out->n_tris = n_t;
    free(cs);
    free(tu);
    return 0;
}

void mesh_to_z_up(mesh_t *m)
{
    for (int i = 0; i < m->n_verts; i++) {
        float *p = &m->pos[3 * i], *n = &m->nrm[3 * i];
        float py = p[1], ny = n[1];
        p[1] = -p[2], p[2] = py;
        n[1] = -n[2], n[2] = ny;
    }
}
