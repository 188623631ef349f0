/* recon_resolve_parts: the body's profile from the two one-sided outlines.
 *
 * A surface of revolution has mirror-image outlines. Where the two agree
 * (within tol) the rows are the body's, whatever their shape: a foot ring or
 * a lip is symmetric. Where they disagree, or next to a window (background
 * seen between a handle and the body), something that is not revolved may
 * cover the body on one side or both. The body is smooth there, so a robust
 * smoothing spline (a P-spline: cubic B-splines on uniform knots with a
 * second-difference penalty, Eilers & Marx 1996) is fitted to every
 * observation, the agreeing rows and the windows' rows held as inliers, the
 * others kept while they lie within tol of it (next to a window, unless they
 * lie outside it by more: a handle's attachment only adds to the outline). Each row's radius is then the mean of
 * its inlying sides; one inlying side is moved by its offset from the mean in
 * the nearest rows where both sides lie in; none leaves the row to the
 * B-spline's bridge. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "recon/recon_internal.h"

/* Knots of the P-spline every 1.5% of the profile's height (at least 4 px):
 * it follows a foot ring or a shoulder but not a handle's attachment. */
#define KNOT_SPACING_FRACTION 0.015
#define KNOT_SPACING_MIN_PX 4.0
/* The penalty on second differences of the coefficients, per unit of data
 * weight: light, so the agreeing rows decide the shape where they are. */
#define PENALTY 0.1
/* rows either side of an excluded run that belong to its fillet */
#define ATTACH_ROWS 3
enum { IRLS_ROUNDS = 8 };

typedef struct {
    double h0, dh; /* first knot and spacing */
    int m;         /* coefficients */
    double *c;
} pspline;

/* Cubic uniform B-spline basis at h: first coefficient index and 4 weights. */
static int pspline_basis(const pspline *p, double h, double w[4])
{
    double u = (h - p->h0) / p->dh;
    int s = (int)floor(u);
    s = s < 0 ? 0 : (s > p->m - 4 ? p->m - 4 : s);
    double t = u - s, it = 1 - t;
    w[0] = it * it * it / 6;
    w[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    w[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    w[3] = t * t * t / 6;
    return s;
}

static double pspline_eval(const pspline *p, double h)
{
    double w[4];
    int s = pspline_basis(p, h, w);
    return w[0] * p->c[s] + w[1] * p->c[s + 1] + w[2] * p->c[s + 2] + w[3] * p->c[s + 3];
}

/* Weighted penalised least squares over the observations (h, r, weight). */
static int pspline_fit(pspline *p, const double *h, const double *r, const double *wt, int n, double *A)
{
    const int m = p->m;
    double *b = A + (size_t)m * m, wsum = 0;
    memset(A, 0, (size_t)m * (m + 1) * sizeof *A);
    for (int i = 0; i < n; i++) {
        if (!(wt[i] > 0) || isnan(r[i]))
            continue;
        double w[4];
        int s = pspline_basis(p, h[i], w);
        for (int a = 0; a < 4; a++) {
            for (int c = 0; c < 4; c++)
                A[(size_t)(s + a) * m + s + c] += wt[i] * w[a] * w[c];
            b[s + a] += wt[i] * w[a] * r[i];
        }
        wsum += wt[i];
    }
    double lambda = PENALTY * (wsum / m + 1);
    for (int j = 0; j + 2 < m; j++) {
        static const double d[3] = {1, -2, 1};
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                A[(size_t)(j + a) * m + j + c] += lambda * d[a] * d[c];
    }
    for (int j = 0; j < m; j++)
        A[(size_t)j * m + j] += 1e-9 * (wsum / m + 1); /* the penalty leaves lines free */
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)m, (size_t)m);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)m), cv = gsl_vector_view_array(p->c, (size_t)m);
    if (gsl_linalg_cholesky_decomp1(&Av.matrix) != 0)
        return -1;
    return gsl_linalg_cholesky_solve(&Av.matrix, &bv.vector, &cv.vector) ? -1 : 0;
}

/* r of the outline o at height h by linear interpolation; NAN past its ends
 * or across a gap of more than 3 px. *gap: the window flag of the nearer point. */
static double r_at(const recon_outline_point *o, int n, double h, int *gap)
{
    *gap = 0;
    if (n < 2 || h < o[0].h || h > o[n - 1].h)
        return NAN;
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (o[mid].h <= h)
            lo = mid;
        else
            hi = mid;
    }
    double dh = o[hi].h - o[lo].h;
    if (dh > 3)
        return NAN;
    *gap = (h - o[lo].h <= o[hi].h - h ? o[lo] : o[hi]).gap;
    return dh <= 1e-9 ? o[lo].r : o[lo].r + (h - o[lo].h) / dh * (o[hi].r - o[lo].r);
}

/* The last row of a window's attachment, walking from row k0 away from the
 * window by step (+1 or -1) for at most reach rows: the handle's edge bulges
 * out of the body there and comes back onto it, so the attachment ends at
 * the outline's narrowest row after its widest, once the outline widens
 * again by more than tol (the body beyond: a flaring neck, a belly). An
 * outline that never widens again is all attachment within reach. */
static int attachment_end(const double *r, int n, int k0, int step, int reach, double tol)
{
    int last = k0 - step, narrowest = -1;
    double widest = -INFINITY, low = INFINITY;
    for (int k = k0, m = 0; k >= 0 && k < n && m < reach; k += step, m++) {
        last = k;
        if (isnan(r[k]))
            continue;
        if (narrowest < 0 && r[k] >= widest - tol) {
            widest = fmax(widest, r[k]);
        } else if (narrowest < 0 || r[k] < low) {
            low = r[k];
            narrowest = k;
        } else if (r[k] > low + tol) {
            return narrowest;
        }
    }
    return last;
}

/* Marks the zone of each window run on one side (gap, r: its rows): the
 * rows a handle may be attached on, from the window out to the end of each
 * attachment (attachment_end, within the window's run length, at least 10
 * rows, of it) and ATTACH_ROWS beyond for its fillet. */
static void window_zone(const uint8_t *gap, const double *r, int n, double tol, uint8_t *zone)
{
    memset(zone, 0, (size_t)n);
    for (int i = 0; i < n;) {
        if (!gap[i]) {
            i++;
            continue;
        }
        int a = i;
        while (i < n && gap[i])
            i++;
        int reach = i - a > 10 ? i - a : 10;
        int lo = attachment_end(r, n, a - 1, -1, reach, tol) - ATTACH_ROWS;
        int hi = attachment_end(r, n, i, 1, reach, tol) + ATTACH_ROWS;
        for (int j = lo < 0 ? 0 : lo; j < n && j <= hi; j++)
            zone[j] = 1;
    }
}

/* Clears ATTACH_ROWS flags at each end of every run of set flags. */
static void trim_runs(uint8_t *flag, int n)
{
    for (int i = 0; i < n;) {
        if (!flag[i]) {
            i++;
            continue;
        }
        int a = i;
        while (i < n && flag[i])
            i++;
        for (int j = a; j < i; j++)
            if (j < a + ATTACH_ROWS || j >= i - ATTACH_ROWS)
                flag[j] = 0;
    }
}

/* The offset of one side from the two sides' mean in the nearest rows (up
 * to 8 on each side of [a, b)) where both lie in. */
static double local_offset(const double *r_side, const double *r_other, const uint8_t *both, int n, int a, int b)
{
    double s = 0;
    int cnt = 0;
    for (int j = a - 1, k = 0; j >= 0 && k < 8; j--)
        if (both[j]) {
            s += 0.5 * (r_side[j] - r_other[j]);
            cnt++, k++;
        }
    for (int j = b, k = 0; j < n && k < 8; j++)
        if (both[j]) {
            s += 0.5 * (r_side[j] - r_other[j]);
            cnt++, k++;
        }
    return cnt ? s / cnt : 0;
}

int recon_resolve_parts(recon_outline_point *main_side, int n, const recon_outline_point *other, int n_other,
                        int main_is_right, double tol, recon_excluded *parts, int max_parts, int *n_parts,
                        double *lr_disagreement, double *excluded_fraction)
{
    *lr_disagreement = 0;
    *excluded_fraction = 0;
    if (n < 4)
        return 0;
    const double height = main_side[n - 1].h - main_side[0].h;
    pspline ps = {main_side[0].h, fmax(KNOT_SPACING_MIN_PX, KNOT_SPACING_FRACTION * height), 0, NULL};
    ps.m = (int)ceil(height / ps.dh) + 3;
    ps.h0 -= ps.dh; /* a knot span of margin at each end */
    ps.m += 2;
    size_t nn = (size_t)n;
    double *h = malloc(nn * 2 * sizeof *h), *r = malloc(nn * 2 * sizeof *r), *wt = malloc(nn * 2 * sizeof *wt);
    double *stretch = malloc(nn * sizeof *stretch);
    double *A = malloc((size_t)ps.m * (ps.m + 1) * sizeof *A);
    uint8_t *flags = malloc(nn * 8);
    ps.c = malloc((size_t)ps.m * sizeof *ps.c);
    int rc = -1;
    if (!h || !r || !wt || !stretch || !A || !flags || !ps.c)
        goto out;
    /* Observations: [0, n) the main side's rows, [n, 2n) the other side at
     * the same heights. */
    uint8_t *gap = flags, *zone = gap + 2 * nn, *forced = zone + 2 * nn, *in = forced + nn, *both = in + 2 * nn;
    for (int i = 0; i < n; i++) {
        int g;
        h[i] = h[n + i] = main_side[i].h;
        r[i] = main_side[i].r;
        gap[i] = (uint8_t)main_side[i].gap;
        r[n + i] = r_at(other, n_other, main_side[i].h, &g);
        gap[n + i] = (uint8_t)g;
    }
    window_zone(gap, r, n, tol, zone);
    window_zone(gap + n, r + n, n, tol, zone + n);
    /* The body seen through a window is held in, but not in the window's
     * first and last rows: there the hole closes along the attachment's
     * fillet, outside the body. */
    trim_runs(gap, n);
    trim_runs(gap + n, n);
    /* Distances to the outline are measured across it, not along the row:
     * where the outline runs at slope s = |dr/dh| a horizontal difference
     * is sqrt(1 + s^2) times the normal one (a shoulder turning flat into a
     * neck moves many pixels per row). s from the main side's neighbours two
     * rows away. */
    for (int i = 0; i < n; i++) {
        int a = i - 2 < 0 ? 0 : i - 2, b = i + 2 >= n ? n - 1 : i + 2;
        double sl = b > a && main_side[b].h > main_side[a].h ? (main_side[b].r - main_side[a].r) / (main_side[b].h - main_side[a].h) : 0;
        stretch[i] = sqrt(1 + sl * sl);
    }
    int n_forced = 0;
    for (int i = 0; i < 2 * n; i++) {
        int row = i % n;
        /* held in: rows where the sides agree, and rows only the main side
         * has (nothing tells a part there); not next to a window */
        int alone = isnan(r[n + row]);
        int agree = !zone[row] && !zone[n + row] && (alone || fabs(r[row] - r[n + row]) <= tol * stretch[row]);
        forced[row] = (uint8_t)agree;
        wt[i] = isnan(r[i]) ? 0 : (agree || gap[i] ? 1 : 0);
        n_forced += wt[i] > 0;
    }
    if (n_forced < 8)
        for (int i = 0; i < 2 * n; i++)
            wt[i] = !isnan(r[i]);
    /* IRLS: a free observation is in while it lies within tol of the fit.
     * Next to a window only the side outside the fit falls out: a handle's
     * attachment adds to the outline there, and a lid or a neck narrower
     * than the spline can bend to is the body's. There the first fit (on
     * the rows held in and the body seen through the window) admits rows
     * once and later rounds only drop them: readmitting rows at the edge of
     * an attachment as the fit moves out would creep up its fillet. */
    for (int it = 0; it < IRLS_ROUNDS; it++) {
        if (pspline_fit(&ps, h, r, wt, 2 * n, A) != 0)
            goto out;
        for (int i = 0; i < 2 * n; i++)
            if (!isnan(r[i]) && !forced[i % n] && !gap[i] && (it == 0 || !zone[i] || wt[i] > 0)) {
                double e = (r[i] - pspline_eval(&ps, h[i])) / stretch[i % n];
                wt[i] = e <= tol && (zone[i] || e >= -tol);
            }
    }
    for (int i = 0; i < 2 * n; i++)
        in[i] = !isnan(r[i]) && wt[i] > 0;
    /* A part joins the body through a fillet that bends the outline a few
     * rows before it leaves the fit: rows within ATTACH_ROWS of a side's
     * excluded run are dropped from that side too where the other side holds
     * the row clear of any run of its own, and by a window in any case (two
     * handles, or a handle where the other side is not seen: bridged). */
    uint8_t *near_out[2] = {forced, both}; /* scratch: both are free here */
    for (int s = 0; s < 2; s++)
        for (int i = 0; i < n; i++) {
            near_out[s][i] = 0;
            for (int j = i - ATTACH_ROWS; j <= i + ATTACH_ROWS; j++)
                if (j >= 0 && j < n && !isnan(r[s * n + j]) && !in[s * n + j])
                    near_out[s][i] = 1;
        }
    for (int i = 0; i < n; i++) {
        for (int s = 0; s < 2; s++)
            if (near_out[s][i] && ((in[(1 - s) * n + i] && !near_out[1 - s][i]) || zone[s * n + i]))
                in[s * n + i] = 0;
    }
    /* Figures on the outlines as measured. */
    double sum = 0, rmax = 0;
    int both_n = 0, one_sided = 0;
    for (int i = 0; i < n; i++) {
        both[i] = in[i] && in[n + i];
        if (both[i]) {
            sum += fabs(r[i] - r[n + i]);
            rmax = fmax(rmax, fmax(r[i], r[n + i]));
            both_n++;
        } else if (!isnan(r[n + i]) || !in[i]) {
            one_sided++;
        }
    }
    *lr_disagreement = both_n && rmax > 0 ? sum / both_n / rmax : 0;
    *excluded_fraction = (double)one_sided / n;

    /* The profile, and the runs of rows that are not on both sides. */
    const int side_main = main_is_right ? 1 : -1;
    const recon_profile_source src_main = main_is_right ? RECON_PROFILE_RIGHT : RECON_PROFILE_LEFT;
    const recon_profile_source src_other = main_is_right ? RECON_PROFILE_LEFT : RECON_PROFILE_RIGHT;
    double *out_r = wt; /* reused */
    for (int i = 0; i < n;) {
        if (both[i]) {
            out_r[i] = 0.5 * (r[i] + r[n + i]);
            i++;
            continue;
        }
        if (in[i] && isnan(r[n + i])) { /* the other side has no row here: the main side as is */
            out_r[i] = r[i];
            i++;
            continue;
        }
        /* a run of one state: main only (1), other only (2), neither (0) */
        int state = in[i] ? 1 : (in[n + i] ? 2 : 0), a = i;
        while (i < n && !both[i] && !(in[i] && isnan(r[n + i])) && (in[i] ? 1 : (in[n + i] ? 2 : 0)) == state)
            i++;
        int window = 0; /* a handle: the run lies by a window */
        for (int j = a; j < i; j++)
            window |= zone[j] || zone[n + j];
        double off = state == 1   ? local_offset(r, r + n, both, n, a, i)
                     : state == 2 ? local_offset(r + n, r, both, n, a, i)
                                  : 0;
        for (int j = a; j < i; j++)
            out_r[j] = state == 1 ? r[j] - off : (state == 2 ? r[n + j] - off : NAN);
        if (*n_parts < max_parts) {
            double y0 = fmin(main_side[a].y, main_side[i - 1].y), y1 = fmax(main_side[a].y, main_side[i - 1].y);
            parts[(*n_parts)++] = (recon_excluded){
                .what = window ? RECON_PART_HANDLE : RECON_PART_ASYMMETRY,
                .row0 = (int)floor(y0),
                .row1 = (int)floor(y1),
                .side = state == 1 ? -side_main : (state == 2 ? side_main : 0),
                .profile = state == 1 ? src_main : (state == 2 ? src_other : RECON_PROFILE_BRIDGED),
            };
        }
    }
    for (int i = 0; i < n; i++)
        main_side[i].r = out_r[i];
    rc = 0;
out:
    free(h);
    free(r);
    free(wt);
    free(stretch);
    free(A);
    free(flags);
    free(ps.c);
    return rc;
}
