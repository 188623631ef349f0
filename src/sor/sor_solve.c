/* The exact leaf solver. On a cubic piece (r(w), h(w)) a point of the ray is a
 * hit when r(w)^2 = rho^2(s) and h(w) = hc + dy s. Eliminating s without
 * dividing by dy gives the degree-6 polynomial
 *     g(w) = dy^2 r(w)^2 - D(w) (a D(w) + 2 beta dy) - rho2c dy^2,  D = h - hc,
 * built directly in the Bernstein basis of the piece (products of its cubic
 * control values). Its real roots in [0,1] are isolated by Bernstein
 * subdivision with Descartes' rule of signs (the number of sign changes of the
 * coefficients bounds the roots and equals it when it is 0 or 1), then found
 * by safeguarded Newton, and finally polished by Newton on the 2x2 system in
 * (w, s), which stays well conditioned for near-horizontal rays where g's two
 * roots (the ray entering and leaving the wall) coalesce. For dy = 0 the
 * roots of h(w) - hc are isolated instead and the ray is horizontal. */
#include <float.h>
#include <math.h>

#include "sor_internal.h"

#define ISO_MAX_DEPTH 24  /* subdivision depth before a root cluster is taken as one seed */
#define ISO_BUDGET 160    /* spans examined per piece at most (degenerate g = 0 stops here) */
#define ISO_MAX_ITEMS 16

typedef struct {
    double lo, hi; /* a bracket with one sign change, or a seed point lo = hi */
    double clo;    /* g at lo for a bracket */
    int bracket;
    double c[7];   /* a bracket's Bernstein coefficients */
} iso_item;

typedef struct {
    double c[7];
    double lo, hi;
    int depth;
} iso_span;

static void bernstein_split_half(const double *c, int n, double *left, double *right)
{
    double tmp[7];
    for (int k = 0; k <= n; k++)
        tmp[k] = c[k];
    left[0] = tmp[0];
    right[n] = tmp[n];
    for (int j = 1; j <= n; j++) {
        for (int k = 0; k <= n - j; k++)
            tmp[k] = 0.5 * (tmp[k] + tmp[k + 1]);
        left[j] = tmp[0];
        right[n - j] = tmp[n - j];
    }
}

/* Roots of the Bernstein polynomial c (degree n <= 6) on [0,1]: brackets holding
 * exactly one simple root, and seed points (a coefficient at a span end within
 * tau of 0, or a cluster too tight to separate). */
static int isolate(const double *c, int n, double tau, iso_item *items)
{
    int ni = 0, budget = ISO_BUDGET;
    if (fabs(c[0]) <= tau)
        items[ni++] = (iso_item){0.0, 0.0, 0.0, 0, {0}};
    if (fabs(c[n]) <= tau)
        items[ni++] = (iso_item){1.0, 1.0, 0.0, 0, {0}};
    iso_span stack[ISO_MAX_DEPTH + 2];
    int sp = 0;
    stack[sp].lo = 0.0, stack[sp].hi = 1.0, stack[sp].depth = 0;
    for (int k = 0; k <= n; k++)
        stack[sp].c[k] = c[k];
    sp++;
    while (sp > 0 && ni < ISO_MAX_ITEMS - 1 && budget-- > 0) {
        iso_span *S = &stack[--sp];
        /* Ends within tau of zero are seeds already: they count as neither sign. */
        int pos = 0, neg = 0, var = 0, last = 0;
        for (int k = 0; k <= n; k++) {
            double v = S->c[k];
            int sg = ((k == 0 || k == n) && fabs(v) <= tau) ? 0 : (v > 0.0) - (v < 0.0);
            pos += sg > 0, neg += sg < 0;
            if (sg) {
                var += last && sg != last;
                last = sg;
            }
        }
        if (!pos || !neg)
            continue;
        double mid = 0.5 * (S->lo + S->hi);
        if (var == 1 && fabs(S->c[0]) > tau && fabs(S->c[n]) > tau) {
            iso_item *it = &items[ni++];
            it->lo = S->lo, it->hi = S->hi, it->clo = S->c[0], it->bracket = 1;
            for (int k = 0; k <= n; k++)
                it->c[k] = S->c[k];
            continue;
        }
        if (S->depth >= ISO_MAX_DEPTH) {
            items[ni++] = (iso_item){mid, mid, 0.0, 0, {0}};
            continue;
        }
        iso_span L, R;
        bernstein_split_half(S->c, n, L.c, R.c);
        L.lo = S->lo, L.hi = mid, R.lo = mid, R.hi = S->hi;
        L.depth = R.depth = S->depth + 1;
        if (fabs(L.c[n]) <= tau)
            items[ni++] = (iso_item){mid, mid, 0.0, 0, {0}};
        stack[sp++] = R; /* left half first: S is overwritten only after its halves are copied */
        stack[sp++] = L;
    }
    return ni;
}

typedef struct {
    double r, h, rw, hw;
} piece_point;

/* The piece and its derivative at w, by Horner on the power basis (the
 * Bernstein values stay the reference for everything exact at the ends). */
static piece_point piece_eval(const sor_piece *pc, double w)
{
    const double *r = pc->rp, *h = pc->hp;
    piece_point q;
    q.r = ((r[3] * w + r[2]) * w + r[1]) * w + r[0];
    q.h = ((h[3] * w + h[2]) * w + h[1]) * w + h[0];
    q.rw = (3.0 * r[3] * w + 2.0 * r[2]) * w + r[1];
    q.hw = (3.0 * h[3] * w + 2.0 * h[2]) * w + h[1];
    return q;
}

/* The function whose roots were isolated, and its derivative. */
static double leaf_fn(const sor_piece *pc, const sor_ray *ry, double w, double *deriv)
{
    piece_point q = piece_eval(pc, w);
    if (ry->dy == 0.0) {
        *deriv = q.hw;
        return q.h - ry->hc;
    }
    double D = q.h - ry->hc, dy2 = ry->dy * ry->dy, lin = 2.0 * ry->beta * ry->dy;
    *deriv = 2.0 * dy2 * q.r * q.rw - q.hw * (2.0 * ry->a * D + lin);
    return dy2 * q.r * q.r - D * (ry->a * D + lin) - ry->rho2c * dy2;
}

/* Newton safeguarded by bisection on a bracket with one sign change, started
 * where the bracket's control polygon crosses zero (c: its Bernstein
 * coefficients, n the degree). It stops once a step is below 1e-7 of the
 * piece, when the error is ~1e-14: the Newton polish in (w, s) that follows
 * takes it to rounding level. */
static double bracket_root(const sor_piece *pc, const sor_ray *ry, double lo, double hi, double clo, const double *c,
                           int n)
{
    double fp, w = 0.5 * (lo + hi);
    int slo = clo > 0.0;
    for (int k = 0; k < n; k++)
        if ((c[k] > 0.0) != (c[k + 1] > 0.0)) {
            w = lo + (hi - lo) * (k + c[k] / (c[k] - c[k + 1])) / n;
            break;
        }
    if (!(w > lo && w < hi))
        w = 0.5 * (lo + hi);
    for (int k = 0; k < 60; k++) {
        double f = leaf_fn(pc, ry, w, &fp);
        if (f == 0.0)
            return w;
        if ((f > 0.0) == slo)
            lo = w;
        else
            hi = w;
        double wn = w - f / fp;
        if (!(wn > lo && wn < hi))
            wn = 0.5 * (lo + hi);
        if (fabs(wn - w) <= 1e-7 || hi - lo <= 1e-10)
            return wn;
        w = wn;
    }
    return w;
}

/* Distance in the (r, h) half-plane between the ray point at s and the piece point at w. */
static double residual(const sor_ray *ry, const piece_point *q, double s, double *F1, double *F2)
{
    double rho2 = (ry->a * s + 2.0 * ry->beta) * s + ry->rho2c;
    *F1 = q->r * q->r - rho2;
    *F2 = q->h - ry->hc - ry->dy * s;
    double rho = sqrt(sor_max(rho2, 0.0));
    return sor_max(fabs(q->r - rho), fabs(*F2));
}

/* Newton on F1 = r(w)^2 - rho^2(s), F2 = h(w) - hc - dy s from (w, s), keeping
 * the best iterate; q is the piece at w. One step is enough from a bracketed
 * root; more are taken only while the distance to the surface exceeds tol.
 * Returns that distance. */
static double polish(const sor_piece *pc, const sor_ray *ry, double tol, piece_point q, double *w, double *s)
{
    double bw = *w, bs = *s, cw = bw, cs = bs, best = INFINITY, F1, F2;
    double rho2 = (ry->a * cs + 2.0 * ry->beta) * cs + ry->rho2c;
    F1 = q.r * q.r - rho2;
    F2 = q.h - ry->hc - ry->dy * cs;
    for (int it = 0; it < 4; it++) {
        double J11 = 2.0 * q.r * q.rw, J12 = -2.0 * (ry->a * cs + ry->beta), J21 = q.hw, J22 = -ry->dy;
        double det = J11 * J22 - J12 * J21;
        if (!(fabs(det) > 1e-14 * (fabs(J11 * J22) + fabs(J12 * J21))))
            break; /* tangent: the seed is as good as it gets */
        double inv_det = 1.0 / det;
        cw += (J12 * F2 - J22 * F1) * inv_det;
        cs += (J21 * F1 - J11 * F2) * inv_det;
        if (!(cw > -0.5 && cw < 1.5))
            break;
        q = piece_eval(pc, cw);
        double e = residual(ry, &q, cs, &F1, &F2);
        if (!(e < best))
            break;
        best = e, bw = cw, bs = cs;
        if (e <= 1e-3 * tol)
            break;
    }
    if (best > tol) { /* no step helped enough (e.g. at a tangency): judge the seed too */
        q = piece_eval(pc, *w);
        double e = residual(ry, &q, *s, &F1, &F2);
        if (e < best)
            return e;
    }
    *w = bw, *s = bs;
    return best;
}

/* Offers the hit candidates at piece parameter w, a root isolated in
 * [wlo, whi]: s from whichever equation determines it better, then polished
 * and checked. A shallow ray meets the circle of radius r(w) at two s. From a
 * bracketed root the height tells which; should the polish leave the bracket
 * (it went to another root), the other s is tried. A seed may stand for a
 * cluster of roots (the entry and exit of a nearly horizontal ray at almost
 * the same w), so seeds try both. */
static int offer(const sor_t *sor, const sor_piece *pc, int idx, const sor_ray *ry, double w, double wlo, double whi,
                 int seed, double smin, sor_best *best)
{
    piece_point q = piece_eval(pc, w);
    double cand[2];
    int nc = 0, both = 1;
    if (ry->steep) {
        cand[nc++] = (q.h - ry->hc) * ry->inv_dy;
    } else {
        double S = sqrt(sor_max(0.0, (q.r * q.r - ry->d2) / ry->a));
        double sp = ry->s_star + S, sm = ry->s_star - S;
        double ep = fabs(q.h - ry->hc - ry->dy * sp), em = fabs(q.h - ry->hc - ry->dy * sm);
        cand[nc++] = ep < em ? sp : sm;
        if (S > 0.0)
            cand[nc++] = ep < em ? sm : sp;
        both = seed || sor_max(ep, em) <= sor->tol;
    }
    int found = 0;
    for (int k = 0; k < nc; k++) {
        double cw = w, cs = cand[k];
        double e = polish(pc, ry, sor->tol, q, &cw, &cs);
        if (!(e <= sor->tol && cw >= wlo - 1e-9 && cw <= whi + 1e-9))
            continue;
        if (cs > smin && cs < best->s) {
            best->s = cs, best->w = sor_min(1.0, sor_max(0.0, cw)), best->piece = idx, best->part = SOR_PART_WALL;
            found = 1;
        }
        if (!both)
            break;
    }
    return found;
}

int sor_piece_intersect(const sor_t *sor, const sor_piece *pc, int idx, const sor_ray *ry, double smin,
                        sor_best *best)
{
    double c[7], mag = 0.0;
    int n;
    if (ry->dy != 0.0) {
        double p[4], q[4], dy2 = ry->dy * ry->dy, lin = 2.0 * ry->beta * ry->dy, K = ry->rho2c * dy2;
        for (int i = 0; i < 4; i++) {
            p[i] = pc->h[i] - ry->hc;
            q[i] = ry->a * p[i] + lin;
        }
        double pq[7];
        pq[0] = p[0] * q[0];
        pq[1] = 0.5 * (p[0] * q[1] + p[1] * q[0]);
        pq[2] = (p[0] * q[2] + 3.0 * p[1] * q[1] + p[2] * q[0]) * 0.2;
        pq[3] = (p[0] * q[3] + 9.0 * (p[1] * q[2] + p[2] * q[1]) + p[3] * q[0]) * 0.05;
        pq[4] = (p[1] * q[3] + 3.0 * p[2] * q[2] + p[3] * q[1]) * 0.2;
        pq[5] = 0.5 * (p[2] * q[3] + p[3] * q[2]);
        pq[6] = p[3] * q[3];
        unsigned positive = 0; /* bit k: c[k] > 0 */
#pragma GCC unroll 7
        for (int k = 0; k < 7; k++) {
            double A = dy2 * pc->r2[k], B = pq[k] + K;
            c[k] = A - B;
            mag = sor_max(mag, fabs(A) + fabs(B));
            positive |= (unsigned)(c[k] > 0.0) << k;
        }
        n = 6;
        /* Fast paths, the common cases: the hull of g stays clear of zero, or
         * crosses it once with both ends clear of zero (exactly one root).
         * Bit k of `change` marks a sign change between c[k] and c[k+1]. */
        unsigned change = (positive ^ (positive >> 1)) & 0x3fu;
        double tau = 64.0 * DBL_EPSILON * mag;
        if (fabs(c[0]) > tau && fabs(c[6]) > tau && (change & (change - 1)) == 0) {
            if (change == 0)
                return 0;
            return offer(sor, pc, idx, ry, bracket_root(pc, ry, 0.0, 1.0, c[0], c, 6), 0.0, 1.0, 0, smin, best);
        }
    } else {
        for (int i = 0; i < 4; i++) {
            c[i] = pc->h[i] - ry->hc;
            mag = sor_max(mag, fabs(pc->h[i]) + fabs(ry->hc));
        }
        n = 3;
    }
    double tau = 64.0 * DBL_EPSILON * mag;
    iso_item items[ISO_MAX_ITEMS];
    int ni = isolate(c, n, tau, items);
    int found = 0;
    for (int k = 0; k < ni; k++) {
        const iso_item *it = &items[k];
        if (it->bracket)
            found |= offer(sor, pc, idx, ry, bracket_root(pc, ry, it->lo, it->hi, it->clo, it->c, n), it->lo, it->hi, 0,
                           smin, best);
        else
            found |= offer(sor, pc, idx, ry, it->lo, 0.0, 1.0, 1, smin, best);
    }
    return found;
}
