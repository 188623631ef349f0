/* recon_resolve_parts: the profile over rows where the left and right
 * outlines disagree. A surface of revolution has mirror-image outlines;
 * where they disagree over a run of rows something that is not revolved is
 * attached on one side (a handle, a lug, a spout) or the outline is spoiled
 * there. The body itself continues smoothly through the run, so the side
 * that agrees with the smooth continuation of the rows around the run (both
 * sides agree there) is the body's; where neither does, the run is left out
 * and the B-spline bridges it. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit.h>
#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

/* r of the outline o at height h by linear interpolation; NAN past its ends
 * or across a gap of more than 3 px. */
static double r_at(const recon_outline_point *o, int n, double h)
{
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
    return dh <= 1e-9 ? o[lo].r : o[lo].r + (h - o[lo].h) / dh * (o[hi].r - o[lo].r);
}

/* Fits r = c0 + c1 h (+ c2 h^2 with context on both sides of the run) to the
 * context points and returns the coefficients in c. 0, or -1. */
static int fit_context(const double *h, const double *r, int n, int quadratic, double c[3])
{
    c[0] = c[1] = c[2] = 0;
    if (n < 3)
        return -1;
    if (!quadratic) {
        double cov00, cov01, cov11, ss;
        return gsl_fit_linear(h, 1, r, 1, (size_t)n, &c[0], &c[1], &cov00, &cov01, &cov11, &ss) ? -1 : 0;
    }
    gsl_matrix *X = gsl_matrix_alloc((size_t)n, 3), *cov = gsl_matrix_alloc(3, 3);
    gsl_vector *y = gsl_vector_alloc((size_t)n), *cv = gsl_vector_alloc(3);
    gsl_multifit_linear_workspace *ws = gsl_multifit_linear_alloc((size_t)n, 3);
    int rc = -1;
    if (X && cov && y && cv && ws) {
        for (int i = 0; i < n; i++) {
            gsl_matrix_set(X, (size_t)i, 0, 1);
            gsl_matrix_set(X, (size_t)i, 1, h[i]);
            gsl_matrix_set(X, (size_t)i, 2, h[i] * h[i]);
            gsl_vector_set(y, (size_t)i, r[i]);
        }
        double chisq;
        if (gsl_multifit_linear(X, y, cv, cov, &chisq, ws) == 0) {
            for (int k = 0; k < 3; k++)
                c[k] = gsl_vector_get(cv, (size_t)k);
            rc = 0;
        }
    }
    gsl_multifit_linear_free(ws);
    gsl_vector_free(cv);
    gsl_vector_free(y);
    gsl_matrix_free(cov);
    gsl_matrix_free(X);
    return rc;
}

/* Median of |r - prediction| over the run's points of one outline (NAN when
 * that outline has none there). */
static double run_deviation(const double *r, const double *h, int n, const double c[3], double *tmp)
{
    int m = 0;
    for (int i = 0; i < n; i++)
        if (!isnan(r[i]))
            tmp[m++] = fabs(r[i] - (c[0] + c[1] * h[i] + c[2] * h[i] * h[i]));
    return m ? gsl_stats_median(tmp, 1, (size_t)m) : NAN;
}

int recon_resolve_parts(recon_outline_point *main_side, int n, const recon_outline_point *other, int n_other,
                        int main_is_right, double tol, recon_excluded *parts, int max_parts, int *n_parts)
{
    double *ro = malloc((size_t)(n > 0 ? n : 1) * 6 * sizeof *ro);
    uint8_t *bad = calloc((size_t)(n > 0 ? n : 1), 1);
    if (!ro || !bad) {
        free(ro);
        free(bad);
        return -1;
    }
    double *ch = ro + n, *cr = ch + n, *rh = cr + n, *rs = rh + n, *tmp = rs + n;
    for (int i = 0; i < n; i++) {
        ro[i] = r_at(other, n_other, main_side[i].h);
        bad[i] = !isnan(ro[i]) && fabs(main_side[i].r - ro[i]) > tol;
    }
    /* Runs of disagreeing rows, joined across gaps under 4 rows. */
    for (int i = 0; i < n;) {
        if (!bad[i]) {
            i++;
            continue;
        }
        int a = i, b = i;
        for (int j = i + 1; j < n && j <= b + 4; j++)
            if (bad[j])
                b = j;
        i = b + 1;
        /* Context: agreeing rows around the run, as many as the run is long
         * (at least 8) on each side. */
        int want = b - a + 1 > 8 ? b - a + 1 : 8, nc = 0, below = 0, above = 0;
        for (int j = a - 1; j >= 0 && below < want; j--)
            if (!bad[j] && !isnan(ro[j])) {
                ch[nc] = main_side[j].h;
                cr[nc++] = 0.5 * (main_side[j].r + ro[j]);
                below++;
            }
        for (int j = b + 1; j < n && above < want; j++)
            if (!bad[j] && !isnan(ro[j])) {
                ch[nc] = main_side[j].h;
                cr[nc++] = 0.5 * (main_side[j].r + ro[j]);
                above++;
            }
        int m = b - a + 1;
        for (int j = 0; j < m; j++) {
            rh[j] = main_side[a + j].h;
            rs[j] = main_side[a + j].r;
        }
        double c[3], dev_main = NAN, dev_other = NAN;
        /* curvature slack: the continuation is uncertain by about 5% of the
         * run's length */
        double slack = tol + 0.05 * fabs(main_side[b].h - main_side[a].h);
        if (fit_context(ch, cr, nc, below >= 3 && above >= 3, c) == 0) {
            dev_main = run_deviation(rs, rh, m, c, tmp);
            dev_other = run_deviation(ro + a, rh, m, c, tmp);
        }
        int keep = 0; /* 1: main side, 2: the other side, 0: bridge */
        if (dev_main <= slack && !(dev_other < dev_main))
            keep = 1;
        else if (dev_other <= slack)
            keep = 2;
        int gap_main = 0, gap_other = 0;
        for (int j = a; j <= b; j++)
            gap_main |= main_side[j].gap;
        for (int j = 0; j < n_other; j++)
            if (other[j].h >= main_side[a].h && other[j].h <= main_side[b].h)
                gap_other |= other[j].gap;
        for (int j = a; j <= b; j++) {
            if (keep == 2)
                main_side[j].r = isnan(ro[j]) ? NAN : ro[j];
            else if (keep == 0)
                main_side[j].r = NAN;
        }
        if (*n_parts < max_parts) {
            int side_main = main_is_right ? 1 : -1;
            int part_side = keep == 1 ? -side_main : (keep == 2 ? side_main : 0);
            int gap = keep == 1 ? gap_other : (keep == 2 ? gap_main : (gap_main | gap_other));
            double y0 = fmin(main_side[a].y, main_side[b].y), y1 = fmax(main_side[a].y, main_side[b].y);
            parts[(*n_parts)++] = (recon_excluded){
                .what = gap ? RECON_PART_HANDLE : RECON_PART_ASYMMETRY,
                .row0 = (int)floor(y0),
                .row1 = (int)floor(y1),
                .side = part_side,
                .profile = keep == 0 ? RECON_PROFILE_BRIDGED : (keep == 1) == (main_is_right != 0) ? RECON_PROFILE_RIGHT
                                                                                                   : RECON_PROFILE_LEFT,
            };
        }
    }
    free(ro);
    free(bad);
    return 0;
}
