/* The museum's levels of detail (src/museum/lod.c): every level lies within
 * its stated error of the exact surface (measured against a dense polyline
 * of the exact profile, brute force), and its rings are no denser than the
 * chord bound needs (against the asymptotic count of an optimal chord
 * polyline, the integral of sqrt(kappa / 8 tol) along the curve). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "museum/lod.h"
#include "support/sor_profiles.h"

enum { POLYLINE = 4000 };

/* The exact profile scaled to metres, as POLYLINE + 1 points. */
static vec2 *scaled_profile(const bspline_t *c, double m_per_px)
{
    vec2 *p = malloc((POLYLINE + 1) * sizeof *p);
    cr_assert(p);
    for (int i = 0; i <= POLYLINE; i++)
        p[i] = v2_scale(bspline_eval(c, (double)i / POLYLINE), m_per_px);
    return p;
}

/* Distance from q (radius, height) to the polyline. */
static double polyline_distance(const vec2 *p, vec2 q)
{
    double best = INFINITY;
    for (int i = 0; i < POLYLINE; i++) {
        vec2 a = p[i], ab = v2_sub(p[i + 1], a), aq = v2_sub(q, a);
        if (fabs(aq.y) > best + fabs(ab.y) && fabs(aq.x) > best + fabs(ab.x))
            continue;
        double l2 = v2_dot(ab, ab), t = l2 > 0 ? v2_dot(aq, ab) / l2 : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, v2_len(v2_sub(aq, v2_scale(ab, t))));
    }
    return best;
}

/* The point w0 v0 + w1 v1 + w2 v2 of a triangle, in the meridian plane (radius, height). */
static vec2 meridian(const float *const v[3], double w0, double w1, double w2)
{
    double x[3];
    for (int k = 0; k < 3; k++)
        x[k] = w0 * v[0][k] + w1 * v[1][k] + w2 * v[2][k];
    return (vec2){sqrt(x[0] * x[0] + x[2] * x[2]), x[1]};
}

/* The wall's triangles come first (mesh.h): 2 N (rings - 1) of them. */
static int wall_triangles(const bspline_t *c, const lod_level *l)
{
    int caps = bspline_eval(c, 0.0).x > 0 ? 1 : 0, n = l->segments;
    return 2 * n * ((l->mesh.n_verts - 2 * n * caps) / n - 1);
}

Test(museum_lod, every_level_is_within_its_stated_error_of_the_exact_surface)
{
    for (int k = 0; k < sor_test_profile_count(); k++) {
        bspline_t c;
        sor_test_profile(k, &c);
        lod_level lv[LOD_MAX_LEVELS];
        double height = 0.3;
        int n = lod_make(&c, height, NULL, 0, 0.6, lv);
        cr_assert_geq(n, 2, "%s", sor_test_profile_name(k));
        vec2 *p = scaled_profile(&c, height / bspline_eval(&c, 1.0).y);
        for (int j = 0; j < n; j++) {
            const mesh_t *m = &lv[j].mesh;
            double worst = 0;
            /* Every 13th wall triangle: its edges' midpoints (one of them a
             * quad's middle, where a planar facet is farthest out) and centroid. */
            for (int t = 0; t < wall_triangles(&c, &lv[j]); t += 13) {
                const float *v[3];
                for (int i = 0; i < 3; i++)
                    v[i] = m->pos + 3 * m->tri[3 * t + i];
                static const double w[4][3] = {
                    {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1 / 3.0, 1 / 3.0, 1 / 3.0}};
                for (int i = 0; i < 4; i++)
                    worst = fmax(worst, polyline_distance(p, meridian(v, w[i][0], w[i][1], w[i][2])));
            }
            cr_log_info("%s LOD %d: %.4g of %.4g mm", sor_test_profile_name(k), j, worst * 1e3, lv[j].error * 1e3);
            cr_expect_leq(worst, lv[j].error * (1 + 1e-3) + 1e-7,
                          "%s LOD %d (%d segments): %.4g mm from the surface, stated %.4g mm",
                          sor_test_profile_name(k), j, lv[j].segments, worst * 1e3, lv[j].error * 1e3);
            cr_expect_gt(worst, 0.25 * lv[j].error, "%s LOD %d: the bound is not slack (%.4g of %.4g mm)",
                         sor_test_profile_name(k), j, worst * 1e3, lv[j].error * 1e3);
        }
        free(p);
        lod_free(lv, n);
        bspline_free(&c);
    }
}

/* The rings an optimal chord polyline of tolerance tol needs on [a, b]: an
 * arc of curvature kappa stays within tol of chords of length sqrt(8 tol /
 * kappa), so about the integral of sqrt(kappa / 8 tol) ds (metres). */
static double optimal_chords(const bspline_t *c, double m_per_px, double tol, double a, double b)
{
    enum { STEPS = 400 };
    double sum = 0;
    for (int i = 0; i < STEPS; i++) {
        vec2 d[3];
        bspline_eval_derivs(c, a + (b - a) * (i + 0.5) / STEPS, 2, d);
        double speed = v2_len(d[1]), kappa = fabs(d[1].x * d[2].y - d[1].y * d[2].x) / (speed * speed * speed);
        sum += sqrt(kappa / m_per_px / (8 * tol)) * speed * m_per_px * (b - a) / STEPS;
    }
    return sum;
}

Test(museum_lod, rings_are_no_denser_than_the_chord_bound_needs)
{
    /* Bisection of each knot span keeps pieces at least half as long as
     * the bound allows: at most twice the optimum, plus one per span. The
     * rippled "recon" profile is where a criterion on the normals (not a
     * geometric error) had added rings. */
    for (int k = 0; k < sor_test_profile_count(); k++) {
        bspline_t c;
        sor_test_profile(k, &c);
        lod_level lv[LOD_MAX_LEVELS];
        double height = 0.3, m_per_px = height / bspline_eval(&c, 1.0).y;
        int n = lod_make(&c, height, NULL, 0, 0.6, lv);
        cr_assert_geq(n, 1);
        for (int j = 0; j < n; j++) {
            double bound = 1;
            for (int s = c.degree; s < c.n_ctrl; s++)
                if (c.knots[s + 1] > c.knots[s])
                    bound += 2 * optimal_chords(&c, m_per_px, 0.5 * lv[j].error, c.knots[s], c.knots[s + 1]) + 1;
            int rings = wall_triangles(&c, &lv[j]) / (2 * lv[j].segments) + 1;
            cr_log_info("%s LOD %d: %d rings, bound %.1f", sor_test_profile_name(k), j, rings, bound);
            cr_expect_leq(rings, bound, "%s LOD %d: %d rings where the chord bound needs %.1f",
                          sor_test_profile_name(k), j, rings, bound);
        }
        lod_free(lv, n);
        bspline_free(&c);
    }
}
