/* One-sided Hausdorff distances between the profile curve and a polyline.
 *
 * Each side is sampled with spacing <= SPACING px (the curve per knot span,
 * by the length of the span's control polygon, which bounds the arc length).
 * Distances to the other side come from a segment tree; polyline points measure
 * to the curve through the nearest chord of the dense curve samples and then a
 * Newton foot point on the curve itself. A distance function is 1-Lipschitz
 * along either side, so the true maximum lies near a sampled local maximum
 * within SPACING of the sampled maximum; each such candidate is polished by
 * golden-section search between its neighbouring samples. */
#include "celadon/curve_distance.h"

#include <math.h>
#include <stdlib.h>

#include "segment_tree.h"

#define SPACING 0.25
/* Samples per side at most: beyond it (curves thousands of times larger than
 * a photograph) the spacing grows instead. */
#define MAX_SAMPLES 65536.0
#define MAX_COORD 1e100

typedef struct {
    const bspline_t *c;
    const segment_tree *poly_index;  /* the polyline */
    const segment_tree *curve_index; /* chords of the dense curve samples */
    const double *cu;               /* parameters of the dense curve samples */
    vec2 a, b;                      /* the polyline segment being scanned */
} context;

/* Distance from the curve point at u to the polyline. */
static double curve_side(const context *x, double u)
{
    return segment_tree_nearest(x->poly_index, bspline_eval(x->c, u), NULL, NULL);
}

/* Distance from the point at t on segment a b to the curve. */
static double polyline_side(const context *x, double t)
{
    vec2 q = v2_lerp(x->a, x->b, t);
    int s;
    double ts;
    segment_tree_nearest(x->curve_index, q, &s, &ts);
    double guess = x->cu[s] + ts * (x->cu[s + 1] - x->cu[s]);
    return curve_point_distance_near(x->c, q, guess, NULL);
}

typedef double (*side_fn)(const context *, double);

/* Golden-section search for the maximum of f on [lo, hi] (to 1e-13 in the
 * parameter; the distance is then exact to far below a micro-pixel). */
static double golden_max(side_fn f, const context *x, double lo, double hi, double f_known)
{
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
    double fc = f(x, c), fd = f(x, d), best = fmax(f_known, fmax(fc, fd));
    for (int it = 0; it < 50 && b - a > 1e-13 * (1.0 + fabs(a)); it++) {
        if (fc > fd) {
            b = d, d = c, fd = fc;
            c = b - g * (b - a), fc = f(x, c);
        } else {
            a = c, c = d, fc = fd;
            d = a + g * (b - a), fd = f(x, d);
        }
        best = fmax(best, fmax(fc, fd));
    }
    return best;
}

/* The maximum of f over samples s[0..n-1] (values v, h[i] the length of
 * the side between samples i and i+1), polished around local maxima. f is
 * 1-Lipschitz in length, so on [s[i], s[i+1]] it stays below
 * (v[i] + v[i+1] + h[i]) / 2: a local maximum whose neighbouring intervals
 * cannot beat the best value so far (or known, found elsewhere) is skipped. */
static double polished_max(side_fn f, const context *x, const double *s, const double *v, const double *h, int n,
                           double known)
{
    double best = known;
    for (int i = 0; i < n; i++)
        best = fmax(best, v[i]);
    for (int i = 0; i < n; i++) {
        if ((i > 0 && v[i - 1] > v[i]) || (i + 1 < n && v[i + 1] > v[i]))
            continue;
        double bound = v[i];
        if (i > 0)
            bound = fmax(bound, 0.5 * (v[i - 1] + v[i] + h[i - 1]));
        if (i + 1 < n)
            bound = fmax(bound, 0.5 * (v[i] + v[i + 1] + h[i]));
        if (bound > best + 1e-12)
            best = fmax(best, golden_max(f, x, s[i > 0 ? i - 1 : i], s[i + 1 < n ? i + 1 : i], v[i]));
    }
    return best;
}

/* Dense samples of the curve: parameters and points. Returns the count or -1. */
static int sample_curve(const bspline_t *c, double **pu, vec2 **pp)
{
    int p = c->degree, nk = bspline_n_knots(c), total = 1;
    double *len = malloc((size_t)nk * sizeof *len), sum = 0.0;
    int *per_span = malloc((size_t)nk * sizeof *per_span);
    if (!len || !per_span) {
        free(len);
        free(per_span);
        return -1;
    }
    for (int k = p; k < c->n_ctrl; k++) {
        len[k] = 0.0;
        if (c->knots[k + 1] > c->knots[k])
            for (int j = k - p; j < k; j++)
                len[k] += v2_len(v2_sub(c->ctrl[j + 1], c->ctrl[j]));
        sum += len[k];
    }
    double spacing = fmax(SPACING, sum / MAX_SAMPLES);
    if (!isfinite(spacing)) { /* control points so far apart their distance overflows */
        free(len);
        free(per_span);
        return -1;
    }
    for (int k = p; k < c->n_ctrl; k++) {
        per_span[k] = c->knots[k + 1] > c->knots[k] ? 2 + (int)ceil(len[k] / spacing) : 0;
        total += per_span[k];
    }
    free(len);
    double *u = malloc((size_t)total * sizeof *u);
    vec2 *pt = malloc((size_t)total * sizeof *pt);
    if (!u || !pt) {
        free(per_span);
        free(u);
        free(pt);
        return -1;
    }
    int m = 0;
    u[m++] = c->knots[p];
    for (int k = p; k < c->n_ctrl; k++)
        for (int i = 1; i <= per_span[k]; i++)
            u[m++] = c->knots[k] + (c->knots[k + 1] - c->knots[k]) * i / per_span[k];
    for (int i = 0; i < m; i++)
        pt[i] = bspline_eval(c, u[i]);
    free(per_span);
    *pu = u;
    *pp = pt;
    return m;
}

/* Coordinates whose squared distances cannot overflow (|x| <= MAX_COORD). */
static int within_range(const vec2 *p, int n)
{
    for (int i = 0; i < n; i++)
        if (!(fabs(p[i].x) <= MAX_COORD) || !(fabs(p[i].y) <= MAX_COORD))
            return 0;
    return 1;
}

/* Grows the three scratch arrays to hold n values. Returns 0 or -1. */
static int reserve(double **a, double **b, double **c, int *cap, int n)
{
    if (n <= *cap)
        return 0;
    *cap = 2 * n;
    free(*a), free(*b), free(*c);
    *a = malloc((size_t)*cap * sizeof **a);
    *b = malloc((size_t)*cap * sizeof **b);
    *c = malloc((size_t)*cap * sizeof **c);
    return *a && *b && *c ? 0 : -1;
}

void curve_polyline_hausdorff(const bspline_t *c, const vec2 *poly, int n, double *curve_to_polyline,
                              double *polyline_to_curve)
{
    curve_range_polyline_hausdorff(c, -INFINITY, INFINITY, poly, n, curve_to_polyline, polyline_to_curve);
}

void curve_range_polyline_hausdorff(const bspline_t *c, double u_lo, double u_hi, const vec2 *poly, int n,
                                    double *curve_to_polyline, double *polyline_to_curve)
{
    *curve_to_polyline = *polyline_to_curve = NAN;
    double *cu = NULL, *val = NULL, *par = NULL, *step = NULL;
    vec2 *cp = NULL;
    int cap = 0;
    segment_tree pg = {0}, cg = {0};
    if (n < 1 || bspline_validate(c) || !within_range(poly, n) || !within_range(c->ctrl, c->n_ctrl))
        return;
    int m = sample_curve(c, &cu, &cp);
    if (m < 2 || segment_tree_build(&pg, poly, n) != 0 || segment_tree_build(&cg, cp, m) != 0 ||
        reserve(&val, &par, &step, &cap, m) != 0)
        goto done;
    context x = {c, &pg, &cg, cu, {0, 0}, {0, 0}};

    /* Curve side, over the samples in [u_lo, u_hi]. The arc between dense
     * samples exceeds its chord by far less than the 1% margin given to the
     * Lipschitz bound. */
    int i0 = 0, i1 = m;
    while (i0 < m && cu[i0] < u_lo)
        i0++;
    while (i1 > i0 && cu[i1 - 1] > u_hi)
        i1--;
    for (int i = i0; i < i1; i++) {
        val[i] = segment_tree_nearest(&pg, cp[i], NULL, NULL);
        step[i] = i + 1 < i1 ? 1.01 * v2_len(v2_sub(cp[i + 1], cp[i])) : 0.0;
    }
    double c2p = i1 > i0 ? polished_max(curve_side, &x, cu + i0, val + i0, step + i0, i1 - i0, 0.0) : 0.0;

    /* Polyline side, one segment at a time (a lone point is a segment of length 0). */
    double p2c = 0.0, poly_len = 0.0;
    for (int s = 0; s + 1 < n; s++)
        poly_len += v2_len(v2_sub(poly[s + 1], poly[s]));
    double spacing = fmax(SPACING, poly_len / MAX_SAMPLES);
    if (!isfinite(spacing))
        goto done;
    for (int s = 0; s < (n > 1 ? n - 1 : 1); s++) {
        x.a = poly[s];
        x.b = poly[n > 1 ? s + 1 : s];
        double len = v2_len(v2_sub(x.b, x.a));
        int k = 1 + (int)ceil(len / spacing);
        if (reserve(&val, &par, &step, &cap, k + 1) != 0)
            goto done;
        for (int i = 0; i <= k; i++) {
            par[i] = (double)i / k;
            val[i] = polyline_side(&x, par[i]);
            step[i] = len / k;
        }
        p2c = polished_max(polyline_side, &x, par, val, step, k + 1, p2c);
    }
    *curve_to_polyline = c2p;
    *polyline_to_curve = p2c;
done:
    segment_tree_free(&pg);
    segment_tree_free(&cg);
    free(cu);
    free(cp);
    free(val);
    free(par);
    free(step);
}
