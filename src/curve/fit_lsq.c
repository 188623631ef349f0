/* Least squares for a cubic spline with fixed knots, through GSL: the basis
 * values come from gsl_bspline, the normal equations are banded (each data
 * row touches 4 consecutive control points) and go to GSL's banded Cholesky.
 * The two end control points equal the end data points (clamped ends
 * interpolate), so they move to the right-hand side.
 *
 * A tiny penalty on consecutive control point differences (relative weight
 * 1e-10) keeps the system positive definite when a knot interval holds too
 * few data for the Schoenberg-Whitney condition; it changes a well-posed fit
 * by far less than a pixel's millionth. */
#include "fit_lsq.h"

#include <gsl/gsl_bspline.h>
#include <gsl/gsl_linalg.h>
#include <stdlib.h>

enum { ORDER = 4 };

int fit_lsq_spline(const vec2 *q, const double *u, int n, const double *interior, int n_int, bspline_t *out,
                   vec2 *resid)
{
    int m = n_int + ORDER, nu = m - 2; /* control points, unknowns (1..m-2) */
    if (n_int < 0 || m > n)
        return -1;
    /* Band columns: the diagonal and up to 3 subdiagonals, no more than the
     * matrix has (GSL's error handler aborts on a mismatch). */
    size_t ncol = nu < ORDER ? (size_t)nu : ORDER;
    bspline_free(out);
    if (bspline_init(out, 3, m) != 0)
        return -1;
    gsl_bspline_workspace *w = gsl_bspline_alloc(ORDER, (size_t)n_int + 2);
    gsl_vector *brk = gsl_vector_alloc((size_t)n_int + 2), *bv = gsl_vector_alloc(ORDER);
    gsl_matrix *ab = gsl_matrix_calloc((size_t)nu, ncol), *rhs = gsl_matrix_calloc((size_t)nu, 2);
    gsl_matrix *x = gsl_matrix_alloc((size_t)nu, 2);
    double *basis = malloc((size_t)n * ORDER * sizeof *basis);
    int *first = malloc((size_t)n * sizeof *first), rc = -1;
    if (!w || !brk || !bv || !ab || !rhs || !x || !basis || !first)
        goto done;

    gsl_vector_set(brk, 0, 0.0);
    for (int j = 0; j < n_int; j++)
        gsl_vector_set(brk, (size_t)j + 1, interior[j]);
    gsl_vector_set(brk, (size_t)n_int + 1, 1.0);
    gsl_bspline_knots(brk, w);

    const vec2 p0 = q[0], p1 = q[n - 1];
    for (int i = 0; i < n; i++) {
        size_t is, ie;
        gsl_bspline_eval_nonzero(u[i], bv, &is, &ie, w);
        first[i] = (int)is;
        double *N = basis + ORDER * i;
        vec2 t = q[i]; /* the data minus the fixed end control points' share */
        for (int a = 0; a < ORDER; a++) {
            N[a] = gsl_vector_get(bv, (size_t)a);
            int j = (int)is + a;
            if (j == 0)
                t = v2_sub(t, v2_scale(p0, N[a]));
            else if (j == m - 1)
                t = v2_sub(t, v2_scale(p1, N[a]));
        }
        for (int a = 0; a < ORDER; a++) {
            int ja = (int)is + a - 1; /* unknown index */
            if (ja < 0 || ja >= nu || N[a] == 0.0)
                continue;
            *gsl_matrix_ptr(rhs, (size_t)ja, 0) += N[a] * t.x;
            *gsl_matrix_ptr(rhs, (size_t)ja, 1) += N[a] * t.y;
            for (int b = a; b < ORDER; b++) {
                int jb = (int)is + b - 1;
                if (jb < nu)
                    *gsl_matrix_ptr(ab, (size_t)ja, (size_t)(jb - ja)) += N[a] * N[b];
            }
        }
    }

    double dmax = 0.0;
    for (int j = 0; j < nu; j++)
        dmax = fmax(dmax, gsl_matrix_get(ab, (size_t)j, 0));
    double lambda = 1e-10 * (dmax > 0.0 ? dmax : 1.0);
    /* lambda |P[c+1] - P[c]|^2; control point c is unknown c - 1 unless it is an end. */
    for (int c = 0; c + 1 < m; c++) {
        int ka = c - 1, kb = c; /* unknown indices of P[c], P[c+1] */
        int fa = ka >= 0, fb = kb < nu;
        if (fa)
            *gsl_matrix_ptr(ab, (size_t)ka, 0) += lambda;
        if (fb)
            *gsl_matrix_ptr(ab, (size_t)kb, 0) += lambda;
        if (fa && fb)
            *gsl_matrix_ptr(ab, (size_t)ka, 1) -= lambda;
        else if (fa || fb) {
            int k = fa ? ka : kb;
            vec2 fixed = fa ? p1 : p0;
            *gsl_matrix_ptr(rhs, (size_t)k, 0) += lambda * fixed.x;
            *gsl_matrix_ptr(rhs, (size_t)k, 1) += lambda * fixed.y;
        }
    }
    if (gsl_linalg_cholesky_band_decomp(ab) != 0 || gsl_linalg_cholesky_band_solvem(ab, rhs, x) != 0)
        goto done;

    for (int k = 0; k < m + ORDER; k++)
        out->knots[k] = k < ORDER ? 0.0 : (k >= m ? 1.0 : interior[k - ORDER]);
    out->ctrl[0] = p0;
    out->ctrl[m - 1] = p1;
    for (int j = 0; j < nu; j++) {
        out->ctrl[j + 1] = v2(gsl_matrix_get(x, (size_t)j, 0), gsl_matrix_get(x, (size_t)j, 1));
        if (!isfinite(out->ctrl[j + 1].x) || !isfinite(out->ctrl[j + 1].y))
            goto done;
    }
    for (int i = 0; i < n; i++) {
        vec2 c = {0.0, 0.0};
        for (int a = 0; a < ORDER; a++)
            c = v2_add(c, v2_scale(out->ctrl[first[i] + a], basis[ORDER * i + a]));
        resid[i] = v2_sub(c, q[i]);
    }
    rc = 0;
done:
    if (w)
        gsl_bspline_free(w);
    gsl_vector_free(brk);
    gsl_vector_free(bv);
    gsl_matrix_free(ab);
    gsl_matrix_free(rhs);
    gsl_matrix_free(x);
    free(basis);
    free(first);
    return rc;
}
