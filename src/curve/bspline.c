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

/* Inserts knot value u once (Boehm; Piegl & Tiller A5.1 with r = 1). k is the
 * span with U[k] <= u < U[k+1] and s the multiplicity of u already present. */
static void knot_insert_once(double *U, int *n_u, vec2 *P, int *n_pts, int p, double u, int k, int s)
{
    vec2 Q[MAX_DEGREE + 1];
    for (int i = k - p + 1; i <= k - s; i++) {
        double alpha = (u - U[i]) / (U[i + p] - U[i]);
        Q[i - (k - p + 1)] = v2_lerp(P[i - 1], P[i], alpha);
    }
    /* P[i] for i >= k-s moves up by one; the blended points replace k-p+1..k-s. */
    memmove(P + k - s + 1, P + k - s, (size_t)(*n_pts - (k - s)) * sizeof *P);
    for (int i = k - p + 1; i <= k - s; i++)
        P[i] = Q[i - (k - p + 1)];
    memmove(U + k + 2, U + k + 1, (size_t)(*n_u - k - 1) * sizeof *U);
    U[k + 1] = u;
    (*n_pts)++;
    (*n_u)++;
}

int bspline_to_bezier(const bspline_t *c, bezier3_t **out)
{
    *out = NULL;
    if (c->degree != 3 || bspline_validate(c))
        return -1;
    const int p = 3;
    int nk = bspline_n_knots(c);
    /* Every interior knot raised to multiplicity p: at most p extra per knot. */
    double *U = malloc((size_t)(nk * (p + 1)) * sizeof *U);
    vec2 *P = malloc((size_t)(c->n_ctrl + nk * p) * sizeof *P);
    if (!U || !P) {
        free(U);
        free(P);
        return -1;
    }
    memcpy(U, c->knots, (size_t)nk * sizeof *U);
    memcpy(P, c->ctrl, (size_t)c->n_ctrl * sizeof *P);
    int n_u = nk, n_pts = c->n_ctrl;
    for (int i = p + 1; i < n_u - p - 1;) {
        double u = U[i];
        int s = 1;
        while (i + s < n_u - p - 1 && U[i + s] == u)
            s++;
        for (; s < p; s++)
            knot_insert_once(U, &n_u, P, &n_pts, p, u, i + s - 1, s);
        i += s;
    }
    /* Now the knots are u0 (x4), u1 (x3), ..., un (x4): piece j spans U[3j+3]..U[3j+4]. */
    int n_pieces = (n_pts - 1) / p;
    bezier3_t *b = malloc((size_t)n_pieces * sizeof *b);
    if (!b) {
        free(U);
        free(P);
        return -1;
    }
    for (int j = 0; j < n_pieces; j++) {
        for (int q = 0; q < 4; q++)
            b[j].p[q] = P[3 * j + q];
        b[j].u0 = U[3 * j + 3];
        b[j].u1 = U[3 * j + 4];
    }
    free(U);
    free(P);
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
