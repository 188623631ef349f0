#include "celadon/bspline.h"

#include <stdlib.h>
#include <string.h>

enum { MAX_DEGREE = 7 };

int bspline_n_knots(const bspline_t *c) { return c->n_ctrl + c->degree + 1; }

int bspline_init(bspline_t *c, int degree, int n_ctrl)
{
    c->degree = degree;
    c->n_ctrl = n_ctrl;
    c->knots = calloc((size_t)(n_ctrl + degree + 1), sizeof *c->knots);
    c->ctrl = calloc((size_t)n_ctrl, sizeof *c->ctrl);
    if (!c->knots || !c->ctrl) {
        bspline_free(c);
        return -1;
    }
    return 0;
}

void bspline_free(bspline_t *c)
{
    free(c->knots);
    free(c->ctrl);
    c->knots = NULL;
    c->ctrl = NULL;
    c->n_ctrl = 0;
}

int bspline_copy(bspline_t *dst, const bspline_t *src)
{
    if (bspline_init(dst, src->degree, src->n_ctrl) != 0)
        return -1;
    memcpy(dst->knots, src->knots, (size_t)bspline_n_knots(src) * sizeof *src->knots);
    memcpy(dst->ctrl, src->ctrl, (size_t)src->n_ctrl * sizeof *src->ctrl);
    return 0;
}

const char *bspline_validate(const bspline_t *c)
{
    int p = c->degree, nk = bspline_n_knots(c);
    if (p < 1 || p > MAX_DEGREE)
        return "degree must be between 1 and 7";
    if (c->n_ctrl < p + 1)
        return "too few control points for the degree";
    for (int i = 0; i < c->n_ctrl; i++)
        if (!isfinite(c->ctrl[i].x) || !isfinite(c->ctrl[i].y))
            return "control point is not finite";
    for (int i = 0; i < nk; i++) {
        if (!isfinite(c->knots[i]))
            return "knot is not finite";
        if (i > 0 && c->knots[i] < c->knots[i - 1])
            return "knots are not non-decreasing";
    }
    for (int i = 1; i <= p; i++)
        if (c->knots[i] != c->knots[0] || c->knots[nk - 1 - i] != c->knots[nk - 1])
            return "knot vector is not clamped";
    if (!(c->knots[nk - 1] > c->knots[0]))
        return "empty parameter domain";
    /* An end knot repeated more than p + 1 times adds an empty span with a
     * zero basis function: no curve needs it, and the Bezier split counts
     * on exactly p + 1. */
    if (c->knots[p + 1] == c->knots[0] || c->knots[nk - 2 - p] == c->knots[nk - 1])
        return "end knot multiplicity exceeds the degree + 1";
    for (int i = p + 1, run = 1; i < nk - p - 1; i++) {
        run = c->knots[i] == c->knots[i - 1] ? run + 1 : 1;
        if (run > p)
            return "interior knot multiplicity exceeds the degree";
    }
    return NULL;
}

int bspline_find_span(const bspline_t *c, double u)
{
    int p = c->degree, n = c->n_ctrl - 1;
    const double *U = c->knots;
    if (u >= U[n + 1])
        return n; /* right end: last span */
    if (u <= U[p])
        return p;
    int lo = p, hi = n + 1;
    while (hi - lo > 1) { /* invariant: U[lo] <= u < U[hi] */
        int mid = (lo + hi) / 2;
        if (u < U[mid])
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

/* Basis functions and their derivatives at u on span k (Piegl & Tiller A2.3):
 * ders[j][r] = d^j N_{k-p+r,p}(u). */
static void basis_derivs(const bspline_t *c, int k, double u, int nder, double ders[][MAX_DEGREE + 1])
{
    int p = c->degree;
    const double *U = c->knots;
    double ndu[MAX_DEGREE + 1][MAX_DEGREE + 1], left[MAX_DEGREE + 1], right[MAX_DEGREE + 1];
    double a[2][MAX_DEGREE + 1];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = u - U[k + 1 - j];
        right[j] = U[k + j] - u;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++)
        ders[0][j] = ndu[j][p];
    for (int r = 0; r <= p; r++) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int kk = 1; kk <= nder; kk++) {
            double d = 0.0;
            int rk = r - kk, pk = p - kk;
            if (r >= kk) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = (r - 1 <= pk) ? kk - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                d += a[s2][kk] * ndu[r][pk];
            }
            ders[kk][r] = d;
            int t = s1;
            s1 = s2;
            s2 = t;
        }
    }
    double f = p;
    for (int kk = 1; kk <= nder; kk++) {
        for (int j = 0; j <= p; j++)
            ders[kk][j] *= f;
        f *= p - kk;
    }
}

void bspline_eval_derivs(const bspline_t *c, double u, int nder, vec2 *out)
{
    int p = c->degree;
    if (nder > 3)
        nder = 3;
    double lo = c->knots[0], hi = c->knots[bspline_n_knots(c) - 1];
    u = u < lo ? lo : (u > hi ? hi : u);
    int k = bspline_find_span(c, u);
    double ders[4][MAX_DEGREE + 1];
    int nd = nder < p ? nder : p;
    basis_derivs(c, k, u, nd, ders);
    for (int j = 0; j <= nder; j++) {
        vec2 s = {0.0, 0.0};
        if (j <= nd)
            for (int r = 0; r <= p; r++)
                s = v2_add(s, v2_scale(c->ctrl[k - p + r], ders[j][r]));
        out[j] = s;
    }
}

vec2 bspline_eval(const bspline_t *c, double u)
{
    vec2 out[1];
    bspline_eval_derivs(c, u, 0, out);
    return out[0];
}

double bspline_curvature(const bspline_t *c, double u)
{
    vec2 d[3];
    bspline_eval_derivs(c, u, 2, d);
    double sp = v2_len(d[1]);
    return sp > 0.0 ? v2_cross(d[1], d[2]) / (sp * sp * sp) : 0.0;
}

/* The number of non-empty knot spans: the Bezier pieces of the curve. */
static int count_spans(const bspline_t *c)
{
    int n = 0, m = bspline_n_knots(c) - 1;
    for (int i = c->degree; i < m - c->degree; i++)
        n += c->knots[i + 1] > c->knots[i];
    return n;
}

/* Piegl & Tiller's DecomposeCurve (A5.6): each interior knot is raised to
 * multiplicity p by Boehm insertion within the current piece only, so the
 * cost is O(p^2) per piece, linear in the control points. */
int bspline_to_bezier(const bspline_t *c, bezier3_t **out)
{
    *out = NULL;
    if (c->degree != 3 || bspline_validate(c))
        return -1;
    const int p = 3, m = bspline_n_knots(c) - 1;
    const double *U = c->knots;
    const vec2 *P = c->ctrl;
    int n_pieces = count_spans(c);
    bezier3_t *b = malloc((size_t)n_pieces * sizeof *b);
    if (!b)
        return -1;
    for (int i = 0; i <= p; i++)
        b[0].p[i] = P[i];
    int a = p, k = p + 1, nb = 0;
    while (k < m) {
        int i = k;
        while (k < m && U[k + 1] == U[k])
            k++;
        int mult = k - i + 1;
        b[nb].u0 = U[a], b[nb].u1 = U[k];
        if (mult < p) {
            double alphas[3], numer = U[k] - U[a];
            for (int j = p; j > mult; j--)
                alphas[j - mult - 1] = numer / (U[a + j] - U[a]);
            int r = p - mult;
            for (int j = 1; j <= r; j++) {
                int save = r - j, s = mult + j;
                for (int q = p; q >= s; q--)
                    b[nb].p[q] = v2_lerp(b[nb].p[q - 1], b[nb].p[q], alphas[q - s]);
                if (k < m)
                    b[nb + 1].p[save] = b[nb].p[p];
            }
        }
        nb++;
        if (k < m) {
            for (int q = p - mult; q <= p; q++)
                b[nb].p[q] = P[k - p + q];
            a = k;
            k++;
        }
    }
    *out = b;
    return n_pieces;
}

vec2 bezier3_eval(const bezier3_t *b, double s)
{
    double t = 1.0 - s;
    double b0 = t * t * t, b1 = 3.0 * s * t * t, b2 = 3.0 * s * s * t, b3 = s * s * s;
    return v2(b0 * b->p[0].x + b1 * b->p[1].x + b2 * b->p[2].x + b3 * b->p[3].x,
              b0 * b->p[0].y + b1 * b->p[1].y + b2 * b->p[2].y + b3 * b->p[3].y);
}

vec2 bezier3_deriv(const bezier3_t *b, double s)
{
    double t = 1.0 - s;
    vec2 d0 = v2_sub(b->p[1], b->p[0]), d1 = v2_sub(b->p[2], b->p[1]), d2 = v2_sub(b->p[3], b->p[2]);
    return v2_scale(v2_add(v2_add(v2_scale(d0, t * t), v2_scale(d1, 2.0 * s * t)), v2_scale(d2, s * s)), 3.0);
}
