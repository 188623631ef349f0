/* mesh_revolve against the surface it samples: counts, every wall vertex on
 * the B-spline surface, unit outward normals agreeing with the winding, a
 * closed 2-manifold with both caps, the texture convention. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/mesh.h"
#include "test_curve_shapes.h"

static const float *P(const mesh_t *m, uint32_t i) { return m->pos + 3 * (size_t)i; }

static void tri_normal(const mesh_t *m, int t, double n[3])
{
    const float *a = P(m, m->tri[3 * t]), *b = P(m, m->tri[3 * t + 1]), *c = P(m, m->tri[3 * t + 2]);
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

Test(mesh_revolve, counts_follow_the_layout)
{
    bspline_t c = test_vase_curve();
    const int cases[][3] = {{3, 2, 0}, {16, 10, 1}, {360, 57, 3}, {7, 2, 2}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        int S = cases[k][0], R = cases[k][1], caps = cases[k][2];
        int ncaps = (caps & 1) + ((caps >> 1) & 1);
        mesh_t m;
        cr_assert_eq(mesh_revolve(&c, NULL, R, 1.0, S, (unsigned)caps, &m), 0);
        cr_assert_eq(m.n_verts, R * S + ncaps * 2 * S, "S=%d R=%d caps=%d", S, R, caps);
        cr_assert_eq(m.n_tris, 2 * S * (R - 1) + ncaps * S);
        for (int i = 0; i < 3 * m.n_tris; i++)
            cr_assert_lt(m.tri[i], (uint32_t)m.n_verts);
        mesh_free(&m);
    }
    bspline_free(&c);
}

Test(mesh_revolve, wall_vertices_lie_on_the_surface)
{
    bspline_t c = test_vase_curve();
    const double u[] = {0.0, 0.03, 0.1, 0.2, 0.35, 0.351, 0.6, 0.9, 1.0};
    const int R = 9, S = 37;
    const double height = 0.32, scale = height / 140.0;
    mesh_t m;
    cr_assert_eq(mesh_revolve(&c, u, R, height, S, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    for (int i = 0; i < R; i++) {
        vec2 q = bspline_eval(&c, u[i]);
        for (int j = 0; j < S; j++) {
            const float *p = P(&m, (uint32_t)(i * S + j));
            double r = hypot(p[0], p[2]), phi = atan2(p[2], p[0]);
            if (phi < 0)
                phi += 2 * M_PI;
            cr_assert_float_eq(r, q.x * scale, 1e-5 * q.x * scale, "ring %d seg %d", i, j);
            cr_assert_float_eq(p[1], q.y * scale, 1e-6);
            double phij = 2 * M_PI * j / S;
            cr_assert(fabs(phi - phij) < 1e-5 || fabs(phi - phij) > 2 * M_PI - 1e-5, "seg %d phi %g", j, phi);
        }
    }
    /* The rim is at the requested height. */
    cr_assert_float_eq(P(&m, (uint32_t)((R - 1) * S))[1], height, 1e-7);
    mesh_free(&m);
    bspline_free(&c);
}

Test(mesh_revolve, normals_are_unit_outward_and_match_the_winding)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    cr_assert_eq(mesh_revolve(&c, NULL, 40, 1.0, 24, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    int wall_verts = 40 * 24;
    for (int v = 0; v < m.n_verts; v++) {
        const float *n = m.nrm + 3 * v, *p = P(&m, (uint32_t)v);
        cr_assert_float_eq(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
        /* h' > 0 everywhere on this profile, so the wall normal leans outward. */
        if (v < wall_verts)
            cr_assert_gt(n[0] * p[0] + n[2] * p[2], 0.0, "vertex %d", v);
    }
    /* Against the analytic normal (h', -r') of the profile at a few rings. */
    for (int i = 0; i < 40; i += 13) {
        vec2 d[2];
        bspline_eval_derivs(&c, i / 39.0, 1, d);
        vec2 nn = v2_norm(v2(d[1].y, -d[1].x));
        const float *n = m.nrm + 3 * (i * 24 + 5);
        double phi = 2 * M_PI * 5 / 24;
        cr_assert_float_eq(n[0], nn.x * cos(phi), 1e-6);
        cr_assert_float_eq(n[1], nn.y, 1e-6);
        cr_assert_float_eq(n[2], nn.x * sin(phi), 1e-6);
    }
    for (int t = 0; t < m.n_tris; t++) {
        double g[3];
        tri_normal(&m, t, g);
        double avg[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                avg[a] += m.nrm[3 * m.tri[3 * t + k] + a];
        cr_assert_gt(g[0] * avg[0] + g[1] * avg[1] + g[2] * avg[2], 0.0, "triangle %d is wound inward", t);
    }
    mesh_free(&m);
    bspline_free(&c);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Welds vertices with identical positions, then checks that every directed
 * edge occurs exactly once and its reverse exactly once: a closed, consistently
 * oriented 2-manifold. */
static void assert_closed(const mesh_t *m)
{
    uint32_t *id = malloc((size_t)m->n_verts * sizeof *id);
    for (int v = 0; v < m->n_verts; v++) {
        id[v] = (uint32_t)v;
        for (int w = 0; w < v; w++)
            if (!memcmp(P(m, (uint32_t)v), P(m, (uint32_t)w), 3 * sizeof(float))) {
                id[v] = id[w];
                break;
            }
    }
    size_t ne = 3 * (size_t)m->n_tris;
    uint64_t *e = malloc(ne * sizeof *e);
    for (int t = 0; t < m->n_tris; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = id[m->tri[3 * t + k]], b = id[m->tri[3 * t + (k + 1) % 3]];
            cr_assert_neq(a, b, "degenerate triangle %d", t);
            e[3 * t + k] = (uint64_t)a << 32 | b;
        }
    qsort(e, ne, sizeof *e, cmp_u64);
    for (size_t i = 0; i < ne; i++) {
        cr_assert(i == 0 || e[i] != e[i - 1], "directed edge used twice");
        uint64_t rev = e[i] << 32 | e[i] >> 32;
        cr_assert_not_null(bsearch(&rev, e, ne, sizeof *e, cmp_u64), "open edge");
    }
    free(e);
    free(id);
}

Test(mesh_revolve, closed_with_both_caps)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    cr_assert_eq(mesh_revolve(&c, NULL, 12, 2.0, 17, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    assert_closed(&m);
    /* Caps: flat, facing down at the base and up at the mouth. */
    for (int t = 2 * 17 * 11; t < m.n_tris; t++) {
        double g[3];
        tri_normal(&m, t, g);
        int base = t < 2 * 17 * 11 + 17;
        cr_assert(base ? g[1] < 0 : g[1] > 0);
        cr_assert_float_eq(g[0], 0.0, 1e-9);
        cr_assert_float_eq(g[2], 0.0, 1e-9);
    }
    mesh_free(&m);
    bspline_free(&c);
}

Test(mesh_revolve, texture_coordinates_follow_the_convention)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    const int S = 8, R = 5;
    cr_assert_eq(mesh_revolve(&c, NULL, R, 3.0, S, 0, &m), 0);
    for (int i = 0; i < R; i++)
        for (int j = 0; j < S; j++) {
            int v = i * S + j;
            double phi = 2 * M_PI * j / S, want = phi <= M_PI ? 1 - phi / M_PI : phi / M_PI - 1;
            cr_assert_float_eq(m.uv[2 * v], want, 1e-7);
            cr_assert_float_eq(m.uv[2 * v + 1], m.pos[3 * v + 1] / 3.0, 1e-6);
        }
    cr_assert_float_eq(m.uv[2 * 0], 1.0, 0);     /* phi = 0 */
    cr_assert_float_eq(m.uv[2 * (S / 2)], 0.0, 0); /* phi = pi */
    cr_assert_float_eq(m.uv[1], 0.0, 0);           /* base */
    cr_assert_float_eq(m.uv[2 * (R - 1) * S + 1], 1.0, 1e-7);
    mesh_free(&m);
    bspline_free(&c);
}

/* On a cap, u follows the angle as on the analytic cap (the u of phi of docs/conventions.md):
 * at any point of a cap triangle the interpolated u is within half a
 * segment's u span (1/S) of the u of the point's own angle. A single centre
 * vertex would pull the middle of the cap toward one u. */
Test(mesh_revolve, cap_texture_follows_the_angle)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    const int S = 16, R = 6;
    cr_assert_eq(mesh_revolve(&c, NULL, R, 1.0, S, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    for (int t = 2 * S * (R - 1); t < m.n_tris; t++) {
        const uint32_t *v = m.tri + 3 * t;
        for (int k = 0; k < 16; k++) { /* barycentric grid, interior points */
            double l[3] = {(k % 4 + 0.25) / 4.5, (k / 4 + 0.25) / 4.5, 0};
            l[2] = 1 - l[0] - l[1];
            if (l[2] <= 0)
                continue;
            double x = 0, z = 0, u = 0;
            for (int i = 0; i < 3; i++) {
                x += l[i] * m.pos[3 * v[i]];
                z += l[i] * m.pos[3 * v[i] + 2];
                u += l[i] * m.uv[2 * v[i]];
            }
            double phi = atan2(z, x);
            phi = phi < 0 ? phi + 2 * M_PI : phi;
            double want = phi <= M_PI ? 1 - phi / M_PI : phi / M_PI - 1;
            cr_assert_leq(fabs(u - want), 1.0 / S + 1e-6, "triangle %d: u %g at phi %g, want %g", t, u, phi, want);
        }
    }
    mesh_free(&m);
    bspline_free(&c);
}

Test(mesh_revolve, profile_on_the_axis)
{
    bspline_t c = test_bowl_curve();
    mesh_t m;
    cr_assert_eq(mesh_revolve(&c, NULL, 20, 1.0, 16, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    /* No base cap (zero area), the mouth cap is there. */
    cr_assert_eq(m.n_verts, 20 * 16 + 2 * 16);
    for (int v = 0; v < m.n_verts; v++) {
        const float *n = m.nrm + 3 * v;
        cr_assert(isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]));
        cr_assert_float_eq(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
    }
    /* At the pole the tangent is horizontal: the normal points straight down. */
    cr_assert_float_eq(m.nrm[1], -1.0, 1e-6);
    mesh_free(&m);
    bspline_free(&c);
}

Test(mesh_revolve, rejects_bad_arguments)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    const double decreasing[] = {0, 0.5, 0.4, 1}, outside[] = {0, 0.5, 1.5}, nan_u[] = {0, NAN, 1};
    cr_assert_eq(mesh_revolve(&c, NULL, 1, 1.0, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, NULL, 4, 1.0, 2, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, NULL, 4, 0.0, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, NULL, 4, NAN, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, decreasing, 4, 1.0, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, outside, 3, 1.0, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, nan_u, 3, 1.0, 16, 0, &m), -1);
    cr_assert_eq(mesh_revolve(&c, NULL, 100000, 1.0, 100000, 0, &m), -1); /* indices overflow */
    cr_assert_null(m.pos);
    c.ctrl[3].x = 1e300; /* beyond float range once scaled */
    cr_assert_eq(mesh_revolve(&c, NULL, 4, 1.0, 16, 0, &m), -1);
    c.ctrl[3].x = 20;
    c.ctrl[7].y = -5; /* rim below the base */
    cr_assert_eq(mesh_revolve(&c, NULL, 4, 1.0, 16, 0, &m), -1);
    c.ctrl[7].y = 140;
    c.knots[5] = 0.05; /* invalid knot vector */
    cr_assert_eq(mesh_revolve(&c, NULL, 4, 1.0, 16, 0, &m), -1);
    bspline_free(&c);
}
