/* Curvature-adaptive domains: recursive bisection of each knot span until
 * the chord sagitta is within tolerance (criterion in curve_domains.h). */
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
static int split(const bspline_t *c, double a, double b, double tol, int depth, boundaries *out)
{
    if (depth < MAX_DEPTH && sagitta(c, a, b) > tol) {
        double m = 0.5 * (a + b);
        return split(c, a, m, tol, depth + 1, out) || split(c, m, b, tol, depth + 1, out) ? -1 : 0;
    }
    return push(out, b);
}

int curve_domains_by_curvature(const bspline_t *c, double tol_px, double **u, int *n)
{
    *u = NULL;
    *n = 0;
    if (!c || bspline_validate(c) || !(tol_px > 0.0) || !isfinite(tol_px))
        return -1;
    boundaries b = {0};
    int p = c->degree;
    if (push(&b, c->knots[p]) != 0)
        return -1;
    for (int k = p; k < c->n_ctrl; k++)
        if (c->knots[k + 1] > c->knots[k] && split(c, c->knots[k], c->knots[k + 1], tol_px, 0, &b) != 0) {
            free(b.u);
            return -1;
        }
    *u = b.u;
    *n = b.n;
    return 0;
}
