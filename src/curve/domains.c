/* Curvature-adaptive domains: recursive bisection of each knot span until
 * the chord sagitta and the normal's departure from linear interpolation are
 * within tolerance (criteria in curve_domains.h). */
#include "celadon/curve_domains.h"

#include <math.h>
#include <stdlib.h>

enum { SAGITTA_SAMPLES = 16, MAX_DEPTH = 16 };

/* Largest distance from the curve on [a, b] to the chord C(a) C(b). */
static double sagitta(const bspline_t *c, double a, double b)
{
    vec2 p = bspline_eval(c, a), q = bspline_eval(c, b), d = v2_sub(q, p);
    double l2 = v2_dot(d, d), worst = 0.0;
    for (int i = 1; i <= SAGITTA_SAMPLES; i++) {
        vec2 x = v2_sub(bspline_eval(c, a + (b - a) * i / (SAGITTA_SAMPLES + 1.0)), p);
        double t = l2 > 0.0 ? v2_dot(x, d) / l2 : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        worst = fmax(worst, v2_len(v2_sub(x, v2_scale(d, t))));
    }
    return worst;
}

/* Largest difference, in radians, between the tangent angle of the curve on
 * [a, b] and its linear interpolation in arc length between the ends. The
 * angle is linear in arc length exactly where the curvature is constant, so
 * this measures the curvature variation on the domain: about |dk/ds| L^2 / 8.
 * Arc length is accumulated along the samples' chords. */
static double normal_departure(const bspline_t *c, double a, double b)
{
    enum { N = SAGITTA_SAMPLES + 2 };
    double ang[N], s[N];
    vec2 d[2], t0 = v2(0, 0), prev = v2(0, 0);
    for (int i = 0; i < N; i++) {
        bspline_eval_derivs(c, a + (b - a) * i / (N - 1.0), 1, d);
        if (i == 0)
            t0 = d[1];
        /* Angle relative to the start tangent: no wrap-around on a domain
         * that turns less than half a circle. */
        ang[i] = atan2(t0.x * d[1].y - t0.y * d[1].x, v2_dot(t0, d[1]));
        s[i] = i ? s[i - 1] + v2_len(v2_sub(d[0], prev)) : 0.0;
        prev = d[0];
    }
    if (!(s[N - 1] > 0.0))
        return 0.0;
    double worst = 0.0;
    for (int i = 1; i < N - 1; i++)
        worst = fmax(worst, fabs(ang[i] - ang[N - 1] * s[i] / s[N - 1]));
    return worst;
}

typedef struct {
    double tol_px, tol_normal;
} criteria;

typedef struct {
    double *u;
    int n, cap;
} boundaries;

static int push(boundaries *b, double u)
{
    if (b->n == b->cap) {
        int cap = b->cap ? 2 * b->cap : 256;
        double *nu = realloc(b->u, (size_t)cap * sizeof *nu);
        if (!nu)
            return -1;
        b->u = nu;
        b->cap = cap;
    }
    b->u[b->n++] = u;
    return 0;
}

/* Appends the interior boundaries of [a, b] in increasing order, then b. */
static int split(const bspline_t *c, double a, double b, const criteria *cr, int depth, boundaries *out)
{
    if (depth < MAX_DEPTH && (sagitta(c, a, b) > cr->tol_px || normal_departure(c, a, b) > cr->tol_normal)) {
        double m = 0.5 * (a + b);
        return split(c, a, m, cr, depth + 1, out) || split(c, m, b, cr, depth + 1, out) ? -1 : 0;
    }
    return push(out, b);
}

int curve_domains_by_curvature(const bspline_t *c, double tol_px, double **u, int *n)
{
    return curve_domains_by_curvature_variation(c, tol_px, INFINITY, u, n);
}

int curve_domains_by_curvature_variation(const bspline_t *c, double tol_px, double tol_normal_deg, double **u,
                                         int *n)
{
    *u = NULL;
    *n = 0;
    if (!c || bspline_validate(c) || !(tol_px > 0.0) || !isfinite(tol_px) || !(tol_normal_deg > 0.0))
        return -1;
    criteria cr = {tol_px, tol_normal_deg * M_PI / 180.0};
    boundaries b = {0};
    int p = c->degree;
    if (push(&b, c->knots[p]) != 0)
        return -1;
    for (int k = p; k < c->n_ctrl; k++)
        if (c->knots[k + 1] > c->knots[k] && split(c, c->knots[k], c->knots[k + 1], &cr, 0, &b) != 0) {
            free(b.u);
            return -1;
        }
    *u = b.u;
    *n = b.n;
    return 0;
}
