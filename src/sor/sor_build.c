/* Building an SOR: the profile's Bézier pieces are scaled to object space,
 * split where r'(u) or h'(u) vanishes (Baciu, Jia & Lam 2001) so that r and h
 * are monotone on every piece, subdivided into short leaves, and grouped
 * into monotone intervals, each the subtree of one strip tree of annuli
 * (Ballard 1981; Kajiya 1983). On a monotone piece the endpoints bound it
 * exactly, so every node's annulus is tight. Every node also gets a strip,
 * a thin box along its chord in the (r^2, h) plane. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sor_internal.h"

/* A leaf is subdivided until its (r, h) box is below this fraction of the
 * object's size, at most LEAF_MAX_DEPTH halvings. */
#define LEAF_FRACTION 0.125
#define LEAF_MAX_DEPTH 6
/* Tree boxes are inflated by this fraction of the size so rounding in the
 * cull can never reject a leaf that holds a hit. */
#define BOX_SLACK 1e-9
/* Accepted distance of a hit from the surface, as a fraction of the size. */
#define HIT_TOLERANCE 1e-11
/* Strips are widened by this times size^2: far more than the hit tolerance
 * (2e-11 size^2 in r^2) and the solver's 1e-9 slack in w (a few 1e-9 size^2)
 * need, and still far thinner than any curved arc. */
#define STRIP_SLACK 1e-8
/* Each leaf's control polygons are split into this many parts before their
 * points bound a strip: the hull of the parts hugs the arc (quadratically in
 * their length) much closer than one polygon does. */
#define STRIP_PARTS 4

void sor_bernstein_square3(const double p[4], double out[7])
{
    out[0] = p[0] * p[0];
    out[1] = p[0] * p[1];
    out[2] = (6.0 * p[0] * p[2] + 9.0 * p[1] * p[1]) / 15.0;
    out[3] = (2.0 * p[0] * p[3] + 18.0 * p[1] * p[2]) / 20.0;
    out[4] = (6.0 * p[1] * p[3] + 9.0 * p[2] * p[2]) / 15.0;
    out[5] = p[2] * p[3];
    out[6] = p[3] * p[3];
}

void sor_cubic_split(const double p[4], double w, double left[4], double right[4])
{
    double a = p[0] + w * (p[1] - p[0]), b = p[1] + w * (p[2] - p[1]), c = p[2] + w * (p[3] - p[2]);
    double ab = a + w * (b - a), bc = b + w * (c - b);
    double m = ab + w * (bc - ab);
    left[0] = p[0], left[1] = a, left[2] = ab, left[3] = m;
    right[0] = m, right[1] = bc, right[2] = c, right[3] = p[3];
}

static void power_basis(const double b[4], double p[4])
{
    p[0] = b[0];
    p[1] = 3.0 * (b[1] - b[0]);
    p[2] = 3.0 * (b[2] - 2.0 * b[1] + b[0]);
    p[3] = b[3] - 3.0 * b[2] + 3.0 * b[1] - b[0];
}

static void piece_finish(sor_piece *pc)
{
    sor_bernstein_square3(pc->r, pc->r2);
    power_basis(pc->r, pc->rp);
    power_basis(pc->h, pc->hp);
    pc->tangent_floor = 1e-12 * (fabs(pc->r[3] - pc->r[0]) + fabs(pc->h[3] - pc->h[0]) + fabs(pc->r[1] - pc->r[0]) +
                                 fabs(pc->h[1] - pc->h[0]) + fabs(pc->r[2] - pc->r[3]) + fabs(pc->h[2] - pc->h[3]));
}

/* Splits pc at local parameter w into two pieces sharing the split point bit for bit. */
static void piece_split(const sor_piece *pc, double w, sor_piece *left, sor_piece *right)
{
    sor_cubic_split(pc->r, w, left->r, right->r);
    sor_cubic_split(pc->h, w, left->h, right->h);
    double um = pc->u0 + w * (pc->u1 - pc->u0);
    left->u0 = pc->u0, left->u1 = um;
    right->u0 = um, right->u1 = pc->u1;
    piece_finish(left);
    piece_finish(right);
}

/* Roots in (0,1) of the derivative of the cubic with Bernstein values p,
 * appended to roots[]; returns the new count. */
static int derivative_roots(const double p[4], double *roots, int n)
{
    double d0 = p[1] - p[0], d1 = p[2] - p[1], d2 = p[3] - p[2];
    double A = d0 - 2.0 * d1 + d2, B = 2.0 * (d1 - d0), C = d0; /* A w^2 + B w + C */
    double cand[2];
    int nc = 0;
    double scale = fabs(d0) + fabs(d1) + fabs(d2);
    if (scale == 0.0)
        return n;
    if (fabs(A) <= 1e-14 * scale) {
        if (B != 0.0)
            cand[nc++] = -C / B;
    } else {
        double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            cand[nc++] = q / A;
            if (q != 0.0)
                cand[nc++] = C / q;
        }
    }
    for (int i = 0; i < nc; i++)
        if (cand[i] > 1e-9 && cand[i] < 1.0 - 1e-9)
            roots[n++] = cand[i];
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct {
    sor_piece *v;
    int n, cap;
} piece_vec;

static int push_piece(piece_vec *pv, const sor_piece *pc)
{
    if (pv->n == pv->cap) {
        int cap = pv->cap ? 2 * pv->cap : 64;
        sor_piece *v = realloc(pv->v, (size_t)cap * sizeof *v);
        if (!v)
            return -1;
        pv->v = v, pv->cap = cap;
    }
    pv->v[pv->n++] = *pc;
    return 0;
}

/* Halves pc until its box is small, appending the leaves in order. */
static int push_leaves(piece_vec *pv, const sor_piece *pc, double limit, int depth)
{
    double dr = fabs(pc->r[3] - pc->r[0]), dh = fabs(pc->h[3] - pc->h[0]);
    if (depth >= LEAF_MAX_DEPTH || dr + dh <= limit)
        return push_piece(pv, pc);
    sor_piece l, r;
    piece_split(pc, 0.5, &l, &r);
    if (push_leaves(pv, &l, limit, depth + 1) != 0)
        return -1;
    return push_leaves(pv, &r, limit, depth + 1);
}

static int sgn(double x) { return (x > 0.0) - (x < 0.0); }

/* Builds the subtree over leaves [lo, hi); interval boundaries are always split
 * first so that every monotone interval is one subtree. Returns its index. */
typedef struct {
    sor_t *s;
    const int *iv_of_leaf; /* monotone interval of each leaf */
    int *range_lo, *range_hi;
} tree_build;

static int build_node(tree_build *tb, int lo, int hi)
{
    sor_t *s = tb->s;
    int idx = s->n_nodes++;
    sor_node *nd = &s->nodes[idx];
    tb->range_lo[idx] = lo, tb->range_hi[idx] = hi;
    if (hi - lo == 1) {
        const sor_piece *pc = &s->pieces[lo];
        double r0 = fmin(pc->r[0], pc->r[3]), r1 = fmax(pc->r[0], pc->r[3]);
        double slack = BOX_SLACK * s->size;
        r0 = fmax(0.0, r0 - slack), r1 += slack;
        nd->q0 = r0 * r0, nd->q1 = r1 * r1;
        nd->h0 = fmin(pc->h[0], pc->h[3]) - slack, nd->h1 = fmax(pc->h[0], pc->h[3]) + slack;
        nd->piece = lo, nd->skip = -1;
        return idx;
    }
    int mid = (lo + hi) / 2;
    if (tb->iv_of_leaf[lo] != tb->iv_of_leaf[hi - 1]) {
        int best = -1;
        for (int k = lo + 1; k < hi; k++)
            if (tb->iv_of_leaf[k] != tb->iv_of_leaf[k - 1] && (best < 0 || abs(k - mid) < abs(best - mid)))
                best = k;
        mid = best;
    }
    nd->piece = -1;
    int a = build_node(tb, lo, mid);
    int b = build_node(tb, mid, hi);
    nd = &s->nodes[idx];
    nd->skip = b;
    const sor_node *na = &s->nodes[a], *nb = &s->nodes[b];
    nd->q0 = fmin(na->q0, nb->q0), nd->q1 = fmax(na->q1, nb->q1);
    nd->h0 = fmin(na->h0, nb->h0), nd->h1 = fmax(na->h1, nb->h1);
    return idx;
}

static int fail(char *err, size_t errlen, const char *msg)
{
    if (err && errlen)
        snprintf(err, errlen, "%s", msg);
    return -1;
}

/* Fitted profiles may miss r >= 0 and h(0) = 0 by rounding: within this of
 * the profile's extent they are snapped, beyond that rejected. */
static double snap_distance(const bspline_t *profile)
{
    double ext = 0.0;
    for (int i = 0; i < profile->n_ctrl; i++)
        ext = fmax(ext, fmax(fabs(profile->ctrl[i].x), fabs(profile->ctrl[i].y)));
    return 1e-9 * ext;
}

const char *sor_profile_check(const bspline_t *profile)
{
    const char *why = bspline_validate(profile);
    if (why)
        return why;
    if (profile->degree != 3)
        return "must be a cubic B-spline";
    for (int i = 0; i < profile->n_ctrl; i++)
        if (fabs(profile->ctrl[i].x) > SOR_PROFILE_MAX_COORD || fabs(profile->ctrl[i].y) > SOR_PROFILE_MAX_COORD)
            return "a control point lies beyond 1e9 px";
    bezier3_t *bz;
    int n = bspline_to_bezier(profile, &bz);
    if (n <= 0)
        return "out of memory";
    double snap = snap_distance(profile), h1 = bz[n - 1].p[3].y;
    why = !(fabs(bz[0].p[0].y) <= snap) || !(h1 > snap) ? "need h(0) = 0 < h(1)"
          : h1 < SOR_PROFILE_MIN_HEIGHT                 ? "the profile is less than 1e-6 px high"
                                                        : NULL;
    double r_max = 0.0; /* bounds the curve's radius: it lies in its control points' hull */
    for (int j = 0; j < n && !why; j++)
        for (int k = 0; k < 4 && !why; k++) {
            if (!(bz[j].p[k].x >= -snap))
                why = "r < 0: the profile crosses the axis";
            r_max = fmax(r_max, bz[j].p[k].x);
        }
    if (!why && !(r_max > snap))
        why = "every radius is 0: the profile lies on the axis (no surface to revolve)";
    free(bz);
    return why;
}

/* Scaled Bézier pieces of the profile into s->bez, and the object's extent. */
static int load_profile(sor_t *s, const bspline_t *profile, char *err, size_t errlen)
{
    bezier3_t *bz;
    int n = bspline_to_bezier(profile, &bz);
    if (n <= 0)
        return fail(err, errlen, "out of memory");
    double h1 = bz[n - 1].p[3].y;
    bz[0].p[0].y = 0.0;
    s->scale = s->height / h1;
    s->bez = calloc((size_t)n, sizeof *s->bez);
    if (!s->bez) {
        free(bz);
        return fail(err, errlen, "out of memory");
    }
    s->n_bez = n;
    s->r_max = 0.0, s->h_min = 0.0, s->h_max = s->height;
    for (int j = 0; j < n; j++) {
        sor_piece *pc = &s->bez[j];
        for (int k = 0; k < 4; k++) {
            bz[j].p[k].x = fmax(bz[j].p[k].x, 0.0);
            /* Shared joints stay bit-identical: the same doubles times the same scale. */
            pc->r[k] = bz[j].p[k].x * s->scale;
            pc->h[k] = bz[j].p[k].y * s->scale;
            s->r_max = fmax(s->r_max, pc->r[k]);
            s->h_min = fmin(s->h_min, pc->h[k]);
            s->h_max = fmax(s->h_max, pc->h[k]);
        }
        pc->u0 = bz[j].u0, pc->u1 = bz[j].u1;
        piece_finish(pc);
    }
    s->bez[n - 1].h[3] = s->height;
    piece_finish(&s->bez[n - 1]);
    free(bz);
    s->r_base = s->bez[0].r[0];
    s->r_mouth = s->bez[n - 1].r[3];
    s->size = fmax(s->h_max - s->h_min, 2.0 * s->r_max);
    s->tol = HIT_TOLERANCE * s->size;
    return 0;
}

/* Monotone leaves of all pieces, and the interval each belongs to. */
static int build_leaves(sor_t *s, int **iv_of_leaf)
{
    piece_vec pv = {0};
    for (int j = 0; j < s->n_bez; j++) {
        double roots[4];
        int nr = derivative_roots(s->bez[j].r, roots, 0);
        nr = derivative_roots(s->bez[j].h, roots, nr);
        qsort(roots, (size_t)nr, sizeof *roots, cmp_double);
        sor_piece rest = s->bez[j];
        double done = 0.0;
        for (int k = 0; k < nr; k++) {
            if (roots[k] - done < 1e-9)
                continue;
            sor_piece l, r;
            piece_split(&rest, (roots[k] - done) / (1.0 - done), &l, &r);
            if (push_leaves(&pv, &l, LEAF_FRACTION * s->size, 0) != 0)
                goto oom;
            rest = r;
            done = roots[k];
        }
        if (push_leaves(&pv, &rest, LEAF_FRACTION * s->size, 0) != 0)
            goto oom;
    }
    s->pieces = pv.v;
    s->n_pieces = pv.n;
    *iv_of_leaf = malloc((size_t)pv.n * sizeof **iv_of_leaf);
    if (!*iv_of_leaf)
        return -1;
    int iv = 0, dr_prev = 0, dh_prev = 0;
    for (int k = 0; k < pv.n; k++) {
        const sor_piece *pc = &pv.v[k];
        int dr = sgn(pc->r[3] - pc->r[0]), dh = sgn(pc->h[3] - pc->h[0]);
        if (k > 0 && (dr != dr_prev || dh != dh_prev))
            iv++;
        (*iv_of_leaf)[k] = iv;
        pv.v[k].interval = iv;
        dr_prev = dr, dh_prev = dh;
    }
    s->n_intervals = iv + 1;
    return 0;
oom:
    free(pv.v);
    return -1;
}

/* The Bernstein coefficients of a cubic raised to degree 6. */
static void elevate_cubic_to_6(const double p[4], double out[7])
{
    static const double b3[4] = {1, 3, 3, 1}, b6[7] = {1, 6, 15, 20, 15, 6, 1};
    for (int k = 0; k < 7; k++) {
        double sum = 0.0;
        for (int i = 0; i < 4; i++)
            if (k - i >= 0 && k - i <= 3)
                sum += b3[i] * b3[k - i] * p[i];
        out[k] = sum / b6[k];
    }
}

/* Widens [*lo, *hi] to hold nr R + nh h over the STRIP_PARTS parts of leaf
 * pc: R = r^2 and h, both as degree-6 Bernstein polynomials, lie in the
 * convex hull of their control points. */
static void strip_extend(const sor_piece *pc, double nr, double nh, double *lo, double *hi)
{
    for (int k = 0; k < STRIP_PARTS; k++) {
        /* Part k is [k, k+1] / STRIP_PARTS: cut off the left, then the right. */
        double w0 = (double)k / STRIP_PARTS, w1 = (double)(k + 1) / STRIP_PARTS;
        double r[4], h[4], rest_r[4], rest_h[4], skip[4];
        sor_cubic_split(pc->r, w0, skip, rest_r);
        sor_cubic_split(pc->h, w0, skip, rest_h);
        double w = (w1 - w0) / (1.0 - w0);
        sor_cubic_split(rest_r, w, r, skip);
        sor_cubic_split(rest_h, w, h, skip);
        double R6[7], h6[7];
        sor_bernstein_square3(r, R6);
        elevate_cubic_to_6(h, h6);
        for (int i = 0; i < 7; i++) {
            double g = nr * R6[i] + nh * h6[i];
            *lo = fmin(*lo, g), *hi = fmax(*hi, g);
        }
    }
}

/* The strip of the arc made of leaves [lo, hi): the normal of its chord in
 * the plane (R, size h), the range of the parts' control points along it, and
 * the slack. */
static sor_strip build_strip(const sor_t *s, int lo, int hi)
{
    const sor_piece *first = &s->pieces[lo], *last = &s->pieces[hi - 1];
    double S = s->size;
    double eR = last->r[3] * last->r[3] - first->r[0] * first->r[0], eh = S * (last->h[3] - first->h[0]);
    double len = sqrt(eR * eR + eh * eh);
    sor_strip st = {1.0, 0.0, INFINITY, -INFINITY};
    if (len > 0.0) /* oriented with nr >= 0: the ray's g(s) is then convex */
        st.nr = fabs(eh) / len, st.nh = eh > 0.0 ? -S * eR / len : S * eR / len;
    for (int k = lo; k < hi; k++)
        strip_extend(&s->pieces[k], st.nr, st.nh, &st.d0, &st.d1);
    double slack = STRIP_SLACK * S * S;
    st.d0 -= slack, st.d1 += slack;
    return st;
}

static int build_tree(sor_t *s, const int *iv_of_leaf)
{
    int cap = 2 * s->n_pieces;
    s->nodes = calloc((size_t)cap, sizeof *s->nodes);
    s->pairs = calloc((size_t)cap, sizeof *s->pairs);
    s->strips = calloc((size_t)cap, sizeof *s->strips);
    s->interval_root = malloc((size_t)s->n_intervals * sizeof *s->interval_root);
    tree_build tb = {s, iv_of_leaf, malloc((size_t)cap * sizeof(int)), malloc((size_t)cap * sizeof(int))};
    int ok = s->nodes && s->pairs && s->strips && s->interval_root && tb.range_lo && tb.range_hi;
    if (ok) {
        build_node(&tb, 0, s->n_pieces);
        for (int k = 0; k < s->n_nodes; k++)
            s->strips[k] = build_strip(s, tb.range_lo[k], tb.range_hi[k]);
        for (int k = 0; k < s->n_nodes; k++) {
            if (s->nodes[k].piece >= 0)
                continue;
            int child[2] = {k + 1, s->nodes[k].skip};
            sor_pair *pr = &s->pairs[k];
            for (int j = 0; j < 2; j++) {
                const sor_node *nd = &s->nodes[child[j]];
                const sor_strip *st = &s->strips[child[j]];
                pr->q0[j] = nd->q0, pr->q1[j] = nd->q1, pr->h0[j] = nd->h0, pr->h1[j] = nd->h1;
                pr->nr[j] = st->nr, pr->nh[j] = st->nh, pr->d0[j] = st->d0, pr->d1[j] = st->d1;
            }
            /* Strips are tested only where they decide whether the leaf solver
             * runs: higher up they cost more than they prune (docs/intersector.md). */
            pr->strips = s->nodes[child[0]].piece >= 0 && s->nodes[child[1]].piece >= 0;
        }
        /* Each interval's leaves form one node's range: find the topmost such node. */
        for (int iv = 0; iv < s->n_intervals; iv++)
            s->interval_root[iv] = -1;
        for (int k = 0; k < s->n_nodes; k++) {
            int lo = tb.range_lo[k], hi = tb.range_hi[k], iv = iv_of_leaf[lo];
            if (iv == iv_of_leaf[hi - 1] && (lo == 0 || iv_of_leaf[lo - 1] != iv) &&
                (hi == s->n_pieces || iv_of_leaf[hi] != iv) && s->interval_root[iv] < 0)
                s->interval_root[iv] = k;
        }
    }
    free(tb.range_lo);
    free(tb.range_hi);
    return ok ? 0 : -1;
}

sor_t *sor_create(const bspline_t *profile, double height, unsigned caps, char *err, size_t errlen)
{
    const char *why = sor_profile_check(profile);
    if (why) {
        snprintf(err, errlen, "profile: %s", why);
        return NULL;
    }
    if (!(height > 0.0) || !isfinite(height)) {
        fail(err, errlen, "height must be positive and finite");
        return NULL;
    }
    if (caps & ~(unsigned)SOR_CAPS_ALL) {
        fail(err, errlen, "unknown cap flags");
        return NULL;
    }
    sor_t *s = calloc(1, sizeof *s);
    if (!s) {
        fail(err, errlen, "out of memory");
        return NULL;
    }
    s->height = height, s->inv_height = 1.0 / height;
    s->caps = caps;
    if (load_profile(s, profile, err, errlen) != 0) {
        sor_destroy(s);
        return NULL;
    }
    int *iv_of_leaf = NULL;
    if (build_leaves(s, &iv_of_leaf) != 0 || build_tree(s, iv_of_leaf) != 0) {
        free(iv_of_leaf);
        fail(err, errlen, "out of memory");
        sor_destroy(s);
        return NULL;
    }
    free(iv_of_leaf);
    double slack = BOX_SLACK * s->size, R = s->r_max + slack;
    s->bound = (sor_node){0.0, R * R, s->h_min - slack, s->h_max + slack, -1, -1};
    return s;
}

void sor_destroy(sor_t *s)
{
    if (!s)
        return;
    free(s->pieces);
    free(s->nodes);
    free(s->pairs);
    free(s->strips);
    free(s->interval_root);
    free(s->bez);
    free(s);
}

double sor_profile_scale(const sor_t *s) { return s->scale; }

void sor_bounds(const sor_t *s, vec3 *lo, vec3 *hi)
{
    *lo = v3(-s->r_max, s->h_min, -s->r_max);
    *hi = v3(s->r_max, s->h_max, s->r_max);
}

int sor_prim_count(const sor_t *s)
{
    return s->n_intervals + !!(s->caps & SOR_CAP_BASE) + !!(s->caps & SOR_CAP_MOUTH);
}

/* Which cap a primitive index past the intervals names. */
unsigned sor_prim_cap(const sor_t *s, int prim)
{
    int k = prim - s->n_intervals;
    if (k == 0 && (s->caps & SOR_CAP_BASE))
        return SOR_CAP_BASE;
    return SOR_CAP_MOUTH;
}

void sor_prim_bounds(const sor_t *s, int prim, vec3 *lo, vec3 *hi)
{
    if (prim < s->n_intervals) {
        const sor_node *nd = &s->nodes[s->interval_root[prim]];
        double r = sqrt(nd->q1);
        *lo = v3(-r, nd->h0, -r);
        *hi = v3(r, nd->h1, r);
        return;
    }
    double slack = BOX_SLACK * s->size;
    int base = sor_prim_cap(s, prim) == SOR_CAP_BASE;
    double r = (base ? s->r_base : s->r_mouth) + slack, y = base ? 0.0 : s->height;
    *lo = v3(-r, y - slack, -r);
    *hi = v3(r, y + slack, r);
}
