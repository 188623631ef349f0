/* Brute-force reference (see sor_reference.h). Each knot span of the profile
 * is turned into power-basis cubics in long double from four Cox-de Boor
 * evaluations. A scalar function of the span parameter x is searched for roots
 * by bisection: an interval is dropped only when min(|f(a)|, |f(b)|) exceeds
 * L (b - a) / 2 for a rigorous bound L of |f'| there, which proves it holds no
 * root; every other interval is halved down to ~1e-16, so all roots are found,
 * and an interval that reaches that width without a sign change is a
 * tangency too close to call. */
#include "sor_reference.h"

#include "sor_profiles.h"

#include <math.h>
#include <stdlib.h>

typedef long double ld;

typedef struct {
    ld u0, u1;
    ld r[4], h[4];         /* power coefficients in x = (u - u0) / (u1 - u0) */
    ld rmax, drmax, dhmax; /* bounds of |r|, |dr/dx|, |dh/dx| on the span */
    ld d2rmax, d2hmax;     /* bounds of |r''|, |h''| */
} ref_span;

struct sor_ref {
    int n;
    ref_span *sp;
    ld height, rbase, rmouth;
    double size, rmax, hmin, hmax;
};

enum { MODE_RAY, MODE_RAY_FLAT, MODE_H, MODE_R };

/* What a search looks for: MODE_RAY the ray's implicit equation
 *   dy^2 r^2 - (a D^2 + 2 b dy D + c dy^2) = 0,  D = h - oy,
 * MODE_RAY_FLAT and MODE_H: h = y0, MODE_R: r = r0. */
typedef struct {
    int mode;
    ld a, b, c, dy, oy; /* the ray, re-origined */
    ld lo, hi, size;    /* the ray's t range (hi shrinks to the nearest clean hit); the object's size */
    ld tstar, d2;       /* the ray's closest approach to the axis: t and rho^2 */
    ld best, amb;       /* MODE_RAY: nearest clean and nearest ambiguous t */
    ld y0, r0;
    int n_roots, n_amb;
    struct {
        int span;
        ld x;
    } roots[64], amb_at[64];
} search;

static ld horner(const ld c[4], ld x) { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }
static ld horner_d(const ld c[4], ld x) { return (3.0L * c[3] * x + 2.0L * c[2]) * x + c[1]; }

static ld fn(const ref_span *s, const search *q, ld x, ld *r_out, ld *h_out)
{
    ld r = horner(s->r, x), h = horner(s->h, x);
    *r_out = r, *h_out = h;
    switch (q->mode) {
    case MODE_RAY: {
        ld D = h - q->oy;
        return q->dy * q->dy * r * r - (q->a * D * D + 2.0L * q->b * q->dy * D + q->c * q->dy * q->dy);
    }
    case MODE_R:
        return r - q->r0;
    default:
        return h - q->y0;
    }
}

/* MODE_RAY: can the ray, for t in (lo, hi), reach the box that bounds the
 * curve on an interval of width w with end points (ra, ha), (rb, hb)? */
static int ray_reaches(const ref_span *s, const search *q, ld ra, ld ha, ld rb, ld hb, ld w)
{
    ld pad = 1e-15L * q->size;
    ld hl = fminl(ha, hb) - 0.5L * s->dhmax * w - pad, hu = fmaxl(ha, hb) + 0.5L * s->dhmax * w + pad;
    ld rl = fmaxl(0.0L, fminl(ra, rb) - 0.5L * s->drmax * w - pad), ru = fmaxl(ra, rb) + 0.5L * s->drmax * w + pad;
    ld ta = (hl - q->oy) / q->dy, tb = (hu - q->oy) / q->dy;
    if (ta > tb) {
        ld t = ta;
        ta = tb, tb = t;
    }
    ta = fmaxl(ta, q->lo), tb = fminl(tb, q->hi);
    if (!(ta <= tb))
        return 0;
    ld fa = (q->a * ta + 2.0L * q->b) * ta + q->c, fb = (q->a * tb + 2.0L * q->b) * tb + q->c;
    ld tm = q->a > 0 ? fminl(fmaxl(-q->b / q->a, ta), tb) : ta, fm = (q->a * tm + 2.0L * q->b) * tm + q->c;
    return fmaxl(fa, fb) >= rl * rl * (1.0L - 1e-15L) && fm <= ru * ru * (1.0L + 1e-15L);
}

/* Size of the terms summed by fn at (r, h): its rounding noise scale. */
static ld magnitude(const search *q, ld r, ld h)
{
    switch (q->mode) {
    case MODE_RAY: {
        ld D = h - q->oy;
        return q->dy * q->dy * r * r + q->a * D * D + fabsl(2.0L * q->b * q->dy * D) + fabsl(q->c) * q->dy * q->dy;
    }
    case MODE_R:
        return fabsl(r) + fabsl(q->r0);
    default:
        return fabsl(h) + fabsl(q->y0);
    }
}

/* f'(x), for the local Lipschitz bound. */
static ld fn_deriv(const ref_span *s, const search *q, ld x)
{
    ld r = horner(s->r, x), h = horner(s->h, x), dr = horner_d(s->r, x), dh = horner_d(s->h, x);
    switch (q->mode) {
    case MODE_RAY:
        return 2.0L * q->dy * q->dy * r * dr - (2.0L * q->a * (h - q->oy) + 2.0L * q->b * q->dy) * dh;
    case MODE_R:
        return dr;
    default:
        return dh;
    }
}

/* A bound of |f''| on the span (|D| <= Dmax there). */
static ld second_bound(const ref_span *s, const search *q, ld Dmax)
{
    switch (q->mode) {
    case MODE_RAY:
        return 2.0L * q->dy * q->dy * (s->drmax * s->drmax + s->rmax * s->d2rmax) + 2.0L * q->a * s->dhmax * s->dhmax +
               (2.0L * q->a * Dmax + 2.0L * fabsl(q->b * q->dy)) * s->d2hmax;
    case MODE_R:
        return s->d2rmax;
    default:
        return s->d2hmax;
    }
}

/* A rigorous bound of |f'| on [xa, xb]: |f'(mid)| plus |f''| times half the width. */
static ld lipschitz(const ref_span *s, const search *q, ld xa, ld xb, ld ha, ld hb)
{
    ld w = xb - xa, Dmax = fmaxl(fabsl(ha - q->oy), fabsl(hb - q->oy)) + 0.5L * s->dhmax * w;
    ld L = fabsl(fn_deriv(s, q, 0.5L * (xa + xb))) + 0.5L * w * second_bound(s, q, Dmax);
    return L * (1.0L + 1e-12L) + 1e-30L;
}

/* Candidate t of the wall point (r, h) on the ray (re-origined, t' = t - t0). */
static ld ray_t(const search *q, ld r, ld h)
{
    if (q->dy * q->dy >= q->a)
        return (h - q->oy) / q->dy;
    ld S = sqrtl(fmaxl(0.0L, (r * r - q->d2) / q->a));
    ld tp = q->tstar + S, tm = q->tstar - S;
    return fabsl(h - q->oy - q->dy * tp) < fabsl(h - q->oy - q->dy * tm) ? tp : tm;
}

static void add(search *q, int amb, const ref_span *s, int span, ld x)
{
    if (q->mode == MODE_RAY) {
        ld t = ray_t(q, horner(s->r, x), horner(s->h, x));
        if (t > q->lo && t < q->hi) {
            if (amb) {
                q->amb = fminl(q->amb, t);
            } else {
                q->best = fminl(q->best, t);
                q->hi = q->best; /* farther roots no longer matter */
            }
        }
    } else if (amb && q->n_amb < 64) {
        q->amb_at[q->n_amb].span = span, q->amb_at[q->n_amb++].x = x;
    } else if (!amb && q->n_roots < 64) {
        q->roots[q->n_roots].span = span, q->roots[q->n_roots++].x = x;
    }
}

#define MIN_WIDTH 1e-16L

static void bisect(const ref_span *s, int span, search *q, ld xa, ld xb, ld fa, ld fb, ld ra, ld rb, ld ha,
                   ld hb)
{
    ld w = xb - xa;
    int change = (fa < 0) != (fb < 0);
    if (!change && fminl(fabsl(fa), fabsl(fb)) > 0.5L * lipschitz(s, q, xa, xb, ha, hb) * w)
        return;
    if (q->mode == MODE_RAY && !ray_reaches(s, q, ra, ha, rb, hb, w))
        return;
    if (change && w <= 1e-3L) {
        /* A short bracket: finish by Illinois regula falsi, still bracketing. */
        int side = 0;
        for (int it = 0; it < 200 && xb - xa > MIN_WIDTH; it++) {
            ld xm = (xa * fb - xb * fa) / (fb - fa), rm, hm;
            if (!(xm > xa && xm < xb))
                xm = 0.5L * (xa + xb);
            ld fm = fn(s, q, xm, &rm, &hm);
            if (fm == 0)
                xa = xb = xm;
            else if ((fm < 0) == (fa < 0)) {
                xa = xm, fa = fm;
                if (side == -1)
                    fb *= 0.5L;
                side = -1;
            } else {
                xb = xm, fb = fm;
                if (side == 1)
                    fa *= 0.5L;
                side = 1;
            }
        }
        w = 0.0L;
    }
    if (w <= MIN_WIDTH) {
        ld x = 0.5L * (xa + xb), r, h;
        fn(s, q, x, &r, &h);
        /* A clean crossing changes sign, clear of rounding noise, within a
         * small distance of x; otherwise it is part of a tangency whose
         * location double precision cannot pin down. */
        ld thr = 1e-16L * magnitude(q, r, h);
        int clean = 0;
        for (ld d = 1e-15L; change && !clean && d <= 1e-10L; d *= 10.0L) {
            ld fm = fn(s, q, fmaxl(0.0L, x - d), &r, &h), fp = fn(s, q, fminl(1.0L, x + d), &r, &h);
            clean = (fm < 0) != (fp < 0) && fabsl(fm) > thr && fabsl(fp) > thr;
        }
        add(q, !clean, s, span, x);
        return;
    }
    ld xm = 0.5L * (xa + xb), rm, hm, fm = fn(s, q, xm, &rm, &hm);
    bisect(s, span, q, xa, xm, fa, fm, ra, rm, ha, hm);
    bisect(s, span, q, xm, xb, fm, fb, rm, rb, hm, hb);
}

static void search_all(const sor_ref *ref, search *q)
{
    q->n_roots = q->n_amb = 0;
    q->size = ref->size;
    for (int k = 0; k < ref->n; k++) {
        ld ra, rb, ha, hb;
        ld fa = fn(&ref->sp[k], q, 0.0L, &ra, &ha), fb = fn(&ref->sp[k], q, 1.0L, &rb, &hb);
        bisect(&ref->sp[k], k, q, 0.0L, 1.0L, fa, fb, ra, rb, ha, hb);
    }
}

/* Cox-de Boor: the curve at u on span k (Piegl & Tiller A2.2), long double. */
static void deboor(const bspline_t *c, int k, ld u, ld *r, ld *h)
{
    const double *U = c->knots;
    ld N[4], left[4], right[4];
    N[0] = 1.0L;
    for (int j = 1; j <= 3; j++) {
        left[j] = u - U[k + 1 - j];
        right[j] = U[k + j] - u;
        ld saved = 0.0L;
        for (int i = 0; i < j; i++) {
            ld tmp = N[i] / (right[i + 1] + left[j - i]);
            N[i] = saved + right[i + 1] * tmp;
            saved = left[j - i] * tmp;
        }
        N[j] = saved;
    }
    *r = *h = 0.0L;
    for (int i = 0; i < 4; i++) {
        *r += N[i] * c->ctrl[k - 3 + i].x;
        *h += N[i] * c->ctrl[k - 3 + i].y;
    }
}

/* Power coefficients in x of the cubic through v at x = 0, 1/3, 2/3, 1. */
static void interpolate(const ld v[4], ld c[4])
{
    ld d1 = v[1] - v[0], d2 = v[2] - 2.0L * v[1] + v[0], d3 = v[3] - 3.0L * v[2] + 3.0L * v[1] - v[0];
    c[0] = v[0];
    c[1] = 3.0L * (d1 - d2 / 2.0L + d3 / 3.0L);
    c[2] = 9.0L * (d2 / 2.0L - d3 / 2.0L);
    c[3] = 27.0L * d3 / 6.0L;
}

/* Hull bounds of |p| and |p'| on [0,1] from the Bernstein form. */
static void bounds(const ld c[4], ld *pmax, ld *dmax)
{
    ld b[4] = {c[0], c[0] + c[1] / 3.0L, c[0] + 2.0L * c[1] / 3.0L + c[2] / 3.0L, c[0] + c[1] + c[2] + c[3]};
    ld d[3] = {c[1], c[1] + c[2], c[1] + 2.0L * c[2] + 3.0L * c[3]};
    *pmax = fmaxl(fmaxl(fabsl(b[0]), fabsl(b[1])), fmaxl(fabsl(b[2]), fabsl(b[3])));
    /* One ulp-scale pad keeps the bound rigorous despite rounding in c. */
    *dmax = fmaxl(fmaxl(fabsl(d[0]), fabsl(d[1])), fabsl(d[2])) * (1.0L + 1e-15L) + 1e-18L;
}

sor_ref *sor_ref_create(const bspline_t *c, double height, unsigned caps)
{
    if (c->degree != 3 || bspline_validate(c) || !(height > 0.0))
        return NULL;
    sor_ref *ref = calloc(1, sizeof *ref);
    ref->sp = calloc((size_t)c->n_ctrl, sizeof *ref->sp);
    ld scale = (ld)height / (ld)c->ctrl[c->n_ctrl - 1].y;
    ref->height = height;
    ref->rmax = 0.0, ref->hmin = 0.0, ref->hmax = height;
    for (int k = 3; k < c->n_ctrl; k++) {
        if (!(c->knots[k] < c->knots[k + 1]))
            continue;
        ref_span *s = &ref->sp[ref->n++];
        s->u0 = c->knots[k], s->u1 = c->knots[k + 1];
        ld vr[4], vh[4];
        for (int i = 0; i < 4; i++) {
            deboor(c, k, s->u0 + (s->u1 - s->u0) * (ld)i / 3.0L, &vr[i], &vh[i]);
            vr[i] *= scale, vh[i] *= scale;
        }
        interpolate(vr, s->r);
        interpolate(vh, s->h);
        ld hmax;
        bounds(s->r, &s->rmax, &s->drmax);
        bounds(s->h, &hmax, &s->dhmax);
        s->d2rmax = (2.0L * fabsl(s->r[2]) + 6.0L * fabsl(s->r[3])) * (1.0L + 1e-15L);
        s->d2hmax = (2.0L * fabsl(s->h[2]) + 6.0L * fabsl(s->h[3])) * (1.0L + 1e-15L);
        for (int i = 0; i <= 64; i++) {
            ld x = i / 64.0L, r = horner(s->r, x), h = horner(s->h, x);
            ref->rmax = fmax(ref->rmax, (double)r);
            ref->hmin = fmin(ref->hmin, (double)h);
            ref->hmax = fmax(ref->hmax, (double)h);
        }
    }
    ref->rbase = (caps & 1u) ? (ld)c->ctrl[0].x * scale : -1.0L;
    ref->rmouth = (caps & 2u) ? (ld)c->ctrl[c->n_ctrl - 1].x * scale : -1.0L;
    ref->size = fmax(ref->hmax - ref->hmin, 2.0 * ref->rmax);
    return ref;
}

sor_ref *sor_ref_create_profile(int i, unsigned caps)
{
    bspline_t c;
    sor_test_profile(i, &c);
    sor_ref *ref = sor_ref_create(&c, 1.0, caps);
    bspline_free(&c);
    return ref;
}

void sor_ref_destroy(sor_ref *ref)
{
    if (ref) {
        free(ref->sp);
        free(ref);
    }
}

double sor_ref_size(const sor_ref *ref) { return ref->size; }
double sor_ref_rmax(const sor_ref *ref) { return ref->rmax; }
double sor_ref_hmin(const sor_ref *ref) { return ref->hmin; }
double sor_ref_hmax(const sor_ref *ref) { return ref->hmax; }
double sor_ref_cap_radius(const sor_ref *ref, int mouth)
{
    ld r = mouth ? ref->rmouth : ref->rbase;
    return r < 0 ? 0.0 : (double)r;
}

int sor_ref_intersect(const sor_ref *ref, const ray3 *ray, double tmin, double tmax, long double *t_out)
{
    ld ox = ray->o.x, oy = ray->o.y, oz = ray->o.z, dx = ray->d.x, dy = ray->d.y, dz = ray->d.z;
    ld dd = dx * dx + dy * dy + dz * dz;
    if (!(dd > 0))
        return SOR_REF_MISS;
    /* Re-origin at the point nearest the object's centre. */
    ld cy = 0.5L * (ld)(ref->hmin + ref->hmax);
    ld t0 = -(ox * dx + (oy - cy) * dy + oz * dz) / dd;
    ox += t0 * dx, oy += t0 * dy, oz += t0 * dz;
    search q = {0};
    q.a = dx * dx + dz * dz, q.b = ox * dx + oz * dz, q.c = ox * ox + oz * oz, q.dy = dy, q.oy = oy;
    ld cr = ox * dz - oz * dx;
    q.tstar = q.a > 0 ? -q.b / q.a : 0.0L, q.d2 = q.a > 0 ? cr * cr / q.a : q.c;
    q.lo = (ld)tmin - t0, q.hi = (ld)tmax - t0;
    q.best = q.amb = INFINITY;
    ld sz = ref->size, tol2 = 1e-13L * sz * sz;
    if (dy != 0) {
        for (int mouth = 0; mouth < 2; mouth++) {
            ld R = mouth ? ref->rmouth : ref->rbase, y = mouth ? ref->height : 0.0L;
            ld t = (y - oy) / dy, x = ox + t * dx, z = oz + t * dz, rho2 = x * x + z * z;
            if (R < 0 || !(t > q.lo && t < q.hi))
                continue;
            if (rho2 <= R * R)
                q.best = fminl(q.best, t);
            else if (rho2 - R * R <= tol2)
                q.amb = fminl(q.amb, t); /* grazing the cap's rim */
        }
        q.hi = fminl(q.hi, q.best);
        q.mode = MODE_RAY;
        search_all(ref, &q);
    } else {
        q.mode = MODE_RAY_FLAT, q.y0 = oy;
        search_all(ref, &q);
        if (q.n_amb)
            q.amb = -INFINITY; /* the ray runs along a horizontal tangent of h */
        for (int k = 0; k < q.n_roots; k++) {
            const ref_span *s = &ref->sp[q.roots[k].span];
            ld r = horner(s->r, q.roots[k].x), e = r * r - q.d2;
            if (fabsl(e) <= tol2) {
                q.amb = fminl(q.amb, q.tstar); /* touches the wall where the ray is tangent to it */
                continue;
            }
            if (e < 0)
                continue;
            ld S = sqrtl(e / q.a);
            for (int sg = -1; sg <= 1; sg += 2) {
                ld t = q.tstar + sg * S;
                if (t > q.lo && t < q.hi)
                    q.best = fminl(q.best, t);
            }
        }
    }
    if (q.amb < q.best - 1e-9L * sz)
        return SOR_REF_AMBIGUOUS;
    if (!isfinite(q.best))
        return SOR_REF_MISS;
    *t_out = q.best + t0;
    return SOR_REF_HIT;
}

int sor_ref_inside(const sor_ref *ref, vec3 p)
{
    ld rho = sqrtl((ld)p.x * p.x + (ld)p.z * p.z), y = p.y, eps = 1e-12L * ref->size;
    if (fabsl(y) <= eps || fabsl(y - ref->height) <= eps)
        return -1;
    search q = {0};
    q.mode = MODE_H, q.y0 = y;
    search_all(ref, &q);
    if (q.n_amb)
        return -1;
    int count = 0;
    for (int k = 0; k < q.n_roots; k++) {
        ld r = horner(ref->sp[q.roots[k].span].r, q.roots[k].x);
        if (fabsl(r - rho) <= eps)
            return -1;
        count += r > rho;
    }
    return count & 1;
}

double sor_ref_surface_distance(const sor_ref *ref, vec3 p)
{
    ld rho = sqrtl((ld)p.x * p.x + (ld)p.z * p.z), y = p.y, best = INFINITY;
    search q = {0};
    q.mode = MODE_H, q.y0 = y;
    search_all(ref, &q);
    for (int k = 0; k < q.n_roots + q.n_amb; k++) {
        int a = k >= q.n_roots;
        const ref_span *s = &ref->sp[a ? q.amb_at[k - q.n_roots].span : q.roots[k].span];
        best = fminl(best, fabsl(horner(s->r, a ? q.amb_at[k - q.n_roots].x : q.roots[k].x) - rho));
    }
    q.mode = MODE_R, q.r0 = rho;
    search_all(ref, &q);
    for (int k = 0; k < q.n_roots + q.n_amb; k++) {
        int a = k >= q.n_roots;
        const ref_span *s = &ref->sp[a ? q.amb_at[k - q.n_roots].span : q.roots[k].span];
        best = fminl(best, fabsl(horner(s->h, a ? q.amb_at[k - q.n_roots].x : q.roots[k].x) - y));
    }
    if (ref->rbase >= 0 && rho <= ref->rbase)
        best = fminl(best, fabsl(y));
    if (ref->rmouth >= 0 && rho <= ref->rmouth)
        best = fminl(best, fabsl(y - ref->height));
    return (double)best;
}

static const ref_span *span_at(const sor_ref *ref, double u, ld *x)
{
    int k = 0;
    while (k < ref->n - 1 && u > ref->sp[k].u1)
        k++;
    *x = ((ld)u - ref->sp[k].u0) / (ref->sp[k].u1 - ref->sp[k].u0);
    return &ref->sp[k];
}

vec3 sor_ref_wall_point(const sor_ref *ref, double u, double phi)
{
    ld x;
    const ref_span *s = span_at(ref, u, &x);
    ld r = horner(s->r, x), h = horner(s->h, x);
    return v3((double)(r * cosl(phi)), (double)h, (double)(r * sinl(phi)));
}

int sor_ref_joint_count(const sor_ref *ref) { return ref->n - 1; }
double sor_ref_joint(const sor_ref *ref, int k) { return (double)ref->sp[k].u1; }

vec3 sor_ref_wall_normal(const sor_ref *ref, double u, double phi)
{
    ld x;
    const ref_span *s = span_at(ref, u, &x);
    ld dr = horner_d(s->r, x), dh = horner_d(s->h, x);
    return v3((double)(dh * cosl(phi)), (double)-dr, (double)(dh * sinl(phi)));
}

double sor_rng_uniform(sor_rng *g)
{
    /* splitmix64 */
    uint64_t z = (g->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

static vec3 random_unit(sor_rng *g)
{
    double y = 2.0 * sor_rng_uniform(g) - 1.0, phi = 2.0 * M_PI * sor_rng_uniform(g), s = sqrt(fmax(0.0, 1.0 - y * y));
    return v3(s * cos(phi), y, s * sin(phi));
}

/* A point in the box around the object, 10% larger on every side. */
static vec3 random_in_box(const sor_ref *ref, sor_rng *g)
{
    double R = 1.1 * ref->rmax, h0 = ref->hmin - 0.1 * ref->size, h1 = ref->hmax + 0.1 * ref->size;
    return v3(R * (2.0 * sor_rng_uniform(g) - 1.0), h0 + (h1 - h0) * sor_rng_uniform(g),
              R * (2.0 * sor_rng_uniform(g) - 1.0));
}

ray3 sor_ref_random_ray(const sor_ref *ref, sor_rng *g)
{
    double k = sor_rng_uniform(g), sz = ref->size;
    vec3 centre = v3(0.0, 0.5 * (ref->hmin + ref->hmax), 0.0);
    vec3 far = v3_add(centre, v3_scale(random_unit(g), 2.0 * sz));
    ray3 r;
    if (k < 0.35) { /* from afar through a point near the object */
        r.o = far;
        r.d = v3_sub(random_in_box(ref, g), far);
    } else if (k < 0.55) { /* from afar at a wall point */
        r.o = far;
        double u = sor_rng_uniform(g), phi = 2.0 * M_PI * sor_rng_uniform(g);
        r.d = v3_sub(sor_ref_wall_point(ref, u, phi), far);
    } else if (k < 0.75) { /* nearly horizontal, tilt from 1e-2 down to 1e-14 */
        r.o = far;
        r.o.y = centre.y + (sor_rng_uniform(g) - 0.5) * 1.2 * (ref->hmax - ref->hmin);
        vec3 tgt = random_in_box(ref, g);
        r.d = v3_sub(tgt, r.o);
        double len = hypot(r.d.x, r.d.z);
        r.d.y = len * pow(10.0, -2.0 - 12.0 * sor_rng_uniform(g)) * (sor_rng_uniform(g) < 0.5 ? -1.0 : 1.0);
    } else if (k < 0.85) { /* nearly vertical, tilt from 1e-2 down to 1e-14, some exactly vertical */
        vec3 tgt = random_in_box(ref, g);
        double up = sor_rng_uniform(g) < 0.5 ? -1.0 : 1.0, tilt = pow(10.0, -2.0 - 12.0 * sor_rng_uniform(g));
        if (sor_rng_uniform(g) < 0.2)
            tilt = 0.0;
        double ang = 2.0 * M_PI * sor_rng_uniform(g);
        r.d = v3(tilt * cos(ang), up, tilt * sin(ang));
        r.o = v3_sub(tgt, v3_scale(r.d, 2.0 * sz));
    } else { /* from a point near the object in any direction */
        r.o = random_in_box(ref, g);
        r.d = random_unit(g);
    }
    return r;
}
