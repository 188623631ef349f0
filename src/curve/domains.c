/* Curvature-adaptive domains: recursive bisection of each knot span until
 * the chord sagitta and the normal's departure from linear interpolation are
 * within tolerance (criteria in curve_domains.h). */
#include "celadon/curve_domains.h"

#include <math.h>
#include <stdlib.h>

enum { SAMPLES = 16, MAX_DEPTH = 16 };

typedef struct {
    double tol_px, tol_normal; /* tol_normal in radians; INFINITY: not checked */
} criteria;

/* Whether the curve on [a, b] meets both criteria, from one set of samples:
 * the ends and SAMPLES interior points, evenly spaced in u.
 * - Chord sagitta: the largest distance from the samples to the chord.
 * - Normal departure: the largest difference between the tangent angle and
 *   its linear interpolation in arc length between the ends (arc length
 *   accumulated along the samples' chords). The angle is linear in arc
 *   length exactly where the curvature is constant, so this measures the
 *   curvature variation on the domain: about |dk/ds| L^2 / 8. Angles are
 *   taken relative to the start tangent: no wrap-around on a domain that
 *   turns less than half a circle. */
static int within_tolerance(const bspline_t *c, double a, double b, const criteria *cr)
{
    enum { N = SAMPLES + 2 };
    vec2 pos[N], tan[N];
    for (int i = 0; i < N; i++) {
        vec2 d[2];
        bspline_eval_derivs(c, i == N - 1 ? b : a + (b - a) * i / (N - 1.0), 1, d);
        pos[i] = d[0];
        tan[i] = d[1];
    }
    vec2 chord = v2_sub(pos[N - 1], pos[0]);
    double l2 = v2_dot(chord, chord);
    for (int i = 1; i < N - 1; i++) {
        vec2 x = v2_sub(pos[i], pos[0]);
        double t = l2 > 0.0 ? v2_dot(x, chord) / l2 : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        if (v2_len(v2_sub(x, v2_scale(chord, t))) > cr->tol_px)
            return 0;
    }
    if (isinf(cr->tol_normal))
        return 1;
    double ang[N], s[N];
    for (int i = 0; i < N; i++) {
        ang[i] = atan2(tan[0].x * tan[i].y - tan[0].y * tan[i].x, v2_dot(tan[0], tan[i]));
        s[i] = i ? s[i - 1] + v2_len(v2_sub(pos[i], pos[i - 1])) : 0.0;
    }
    if (!(s[N - 1] > 0.0))
        return 1;
    for (int i = 1; i < N - 1; i++)
        if (fabs(ang[i] - ang[N - 1] * s[i] / s[N - 1]) > cr->tol_normal)
            return 0;
    return 1;
}

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
    if (depth < MAX_DEPTH && !within_tolerance(c, a, b, cr)) {
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
