/* Dierckx-style smoothing fit (FITPACK curfit/parcur, Dierckx 1993, ch. 5):
 * start from the cubic polynomial (no interior knots), and while the fit is
 * not good enough, add a knot in the interval whose points carry the largest
 * sum of squared residuals, at the middle data point strictly inside it.
 * The spline spaces are nested, so the sum of squared residuals never grows.
 *
 * Differences from FITPACK: one knot per iteration (FITPACK adds a growing
 * number at once, which saves iterations but may overshoot the knot count);
 * the result is the least-squares spline on the final knots (FITPACK then
 * solves for a smoothing parameter p so that the residual equals s exactly,
 * which would only make the curve smoother by leaving more residual); the
 * ends interpolate the first and last point. */
#include "celadon/curve_fit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_distance.h"
#include "fit_lsq.h"

typedef struct {
    int n;
    vec2 *q;   /* distinct consecutive points */
    double *u; /* chord-length parameters, 0 .. 1 */
} fit_data;

static void fit_data_free(fit_data *d)
{
    free(d->q);
    free(d->u);
}

/* Chord-length parametrisation without repeated points. Returns 0 or -1. */
static int parametrise(const vec2 *pts, int n, fit_data *d)
{
    memset(d, 0, sizeof *d);
    if (!pts || n < 4)
        return -1;
    for (int i = 0; i < n; i++)
        if (!isfinite(pts[i].x) || !isfinite(pts[i].y))
            return -1;
    d->q = malloc((size_t)n * sizeof *d->q);
    d->u = malloc((size_t)n * sizeof *d->u);
    if (!d->q || !d->u) {
        fit_data_free(d);
        return -1;
    }
    d->q[0] = pts[0];
    d->u[0] = 0.0;
    int m = 1;
    for (int i = 1; i < n; i++) {
        double len = v2_len(v2_sub(pts[i], d->q[m - 1]));
        if (!(len > 0.0))
            continue;
        if (!isfinite(d->u[m - 1] + len)) {
            fit_data_free(d);
            return -1;
        }
        d->q[m] = pts[i];
        d->u[m] = d->u[m - 1] + len;
        m++;
    }
    double total = d->u[m - 1];
    if (!(total > 0.0)) {
        fit_data_free(d);
        return -1;
    }
    /* Normalise; a step too small to separate two parameters in double
     * precision counts as a repeat too (the knots must stay distinct). The
     * last point stays: it is the rim corner. */
    int k = 1;
    for (int i = 1; i < m; i++) {
        double u = i == m - 1 ? 1.0 : d->u[i] / total;
        if (!(u > d->u[k - 1]))
            continue;
        if (u == 1.0 && i < m - 1)
            continue;
        d->u[k] = u;
        d->q[k++] = d->q[i];
    }
    if (k < 4) {
        fit_data_free(d);
        return -1;
    }
    d->n = k;
    return 0;
}

/* FITPACK's knot placement (fpknot): the interval with the largest sum of
 * squared residuals among those with data strictly inside; the new knot is the
 * middle such data point. A point on a knot counts half on each side.
 * Returns the new knot, or -1 when no interval can take one. */
static double next_knot(const fit_data *d, const double *knots, int n_int, const vec2 *resid)
{
    double best_ssr = -1.0, best_knot = -1.0;
    int i = 0;
    for (int j = 0; j <= n_int; j++) {
        double lo = j == 0 ? 0.0 : knots[j - 1], hi = j == n_int ? 1.0 : knots[j];
        double ssr = 0.0;
        int first_inside = -1, inside = 0;
        while (i < d->n && d->u[i] < lo)
            i++;
        for (int k = i; k < d->n && d->u[k] <= hi; k++) {
            double r2 = v2_dot(resid[k], resid[k]);
            if (d->u[k] == lo || d->u[k] == hi)
                ssr += 0.5 * r2;
            else {
                ssr += r2;
                if (first_inside < 0)
                    first_inside = k;
                inside++;
            }
        }
        if (inside > 0 && ssr > best_ssr) {
            best_ssr = ssr;
            best_knot = d->u[first_inside + (inside - 1) / 2];
        }
    }
    return best_knot;
}

/* Largest distance from a data point to the curve, each measured by Newton
 * from its own parameter; points whose parameter residual is already within
 * tol need no search (the curve point at u_i is at most that far). */
static double max_deviation(const fit_data *d, const bspline_t *c, const vec2 *resid, double tol)
{
    double worst = 0.0;
    for (int i = 0; i < d->n; i++) {
        double r = v2_len(resid[i]);
        if (r > tol)
            r = curve_point_distance_near(c, d->q[i], d->u[i], NULL);
        worst = fmax(worst, r);
    }
    return worst;
}

/* Grows the knot set until ssr <= s, or (when tol > 0) until every point is
 * within tol of the curve. */
static int fit_knot_sequence(const fit_data *d, double s, double tol, bspline_t *out, bspline_fit_info *info)
{
    double *knots = malloc((size_t)d->n * sizeof *knots);
    vec2 *resid = malloc((size_t)d->n * sizeof *resid);
    int n_int = 0, iterations = 0, rc = -1;
    double ssr = INFINITY;
    memset(out, 0, sizeof *out);
    if (!knots || !resid)
        goto done;
    for (;;) {
        if (fit_lsq_spline(d->q, d->u, d->n, knots, n_int, out, resid) != 0)
            goto done;
        iterations++;
        ssr = 0.0;
        for (int i = 0; i < d->n; i++)
            ssr += v2_dot(resid[i], resid[i]);
        int interpolating = n_int + 4 == d->n;
        if (interpolating || (tol > 0.0 ? max_deviation(d, out, resid, tol) <= tol : ssr <= s))
            break;
        if (n_int + 5 == d->n) {
            /* One knot short of the interpolating spline: take FITPACK's
             * interpolation knots (not-a-knot, at the data sites 2..n-3). */
            n_int = d->n - 4;
            memcpy(knots, d->u + 2, (size_t)n_int * sizeof *knots);
            continue;
        }
        double t = next_knot(d, knots, n_int, resid);
        if (t < 0.0)
            break;
        int at = n_int;
        while (at > 0 && knots[at - 1] > t)
            at--;
        memmove(knots + at + 1, knots + at, (size_t)(n_int - at) * sizeof *knots);
        knots[at] = t;
        n_int++;
    }
    rc = 0;
done:
    if (rc != 0)
        bspline_free(out);
    else if (info)
        *info = (bspline_fit_info){tol > 0.0 ? ssr : s, ssr, out->n_ctrl, iterations};
    free(knots);
    free(resid);
    return rc;
}

int bspline_fit_smoothing(const vec2 *pts, int n, double s, bspline_t *out, bspline_fit_info *info)
{
    fit_data d;
    memset(out, 0, sizeof *out);
    if (!(s >= 0.0) || parametrise(pts, n, &d) != 0)
        return -1;
    int rc = fit_knot_sequence(&d, s, 0.0, out, info);
    fit_data_free(&d);
    return rc;
}

int bspline_fit_profile(const vec2 *pts, int n, double max_dev_px, bspline_t *out, bspline_fit_info *info)
{
    fit_data d;
    memset(out, 0, sizeof *out);
    if (!(max_dev_px > 0.0) || !isfinite(max_dev_px) || parametrise(pts, n, &d) != 0)
        return -1;
    int rc = fit_knot_sequence(&d, 0.0, max_dev_px, out, info);
    fit_data_free(&d);
    return rc;
}
