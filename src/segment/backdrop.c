/* recon_backdrop: robust penalised least squares of a cubic B-spline surface.
 * See backdrop.h. */
#include "segment/backdrop.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_statistics_double.h>

/* Uniform cubic B-spline with g control points on [0, len]: the g-3 spans
 * share the length; writes the first control index and the 4 weights. */
static void basis(double x, double len, int g, int *first, double wt[4])
{
    int spans = g - 3;
    double u = x / len * spans;
    int s = (int)floor(u);
    s = s < 0 ? 0 : (s >= spans ? spans - 1 : s);
    double t = u - s, it = 1 - t;
    wt[0] = it * it * it / 6;
    wt[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    wt[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    wt[3] = t * t * t / 6;
    *first = s;
}

void recon_backdrop_at(const recon_backdrop *b, double x, double y, double out[3])
{
    int fx, fy;
    double wx[4], wy[4];
    basis(x, b->width, b->grid, &fx, wx);
    basis(y, b->height, b->grid, &fy, wy);
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            const double *c = b->coef[(fy + j) * b->grid + fx + i];
            double wgt = wx[i] * wy[j];
            out[0] += wgt * c[0];
            out[1] += wgt * c[1];
            out[2] += wgt * c[2];
        }
}

void recon_backdrop_row(const recon_backdrop *b, int y, float *out)
{
    const int g = b->grid;
    int fy;
    double wy[4], col[RECON_BACKDROP_MAX_GRID][3];
    basis(y + 0.5, b->height, g, &fy, wy);
    for (int i = 0; i < g; i++)
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (int j = 0; j < 4; j++)
                s += wy[j] * b->coef[(fy + j) * g + i][c];
            col[i][c] = s;
        }
    for (int x = 0; x < b->width; x++) {
        int fx;
        double wx[4];
        basis(x + 0.5, b->width, g, &fx, wx);
        for (int c = 0; c < 3; c++)
            out[3 * x + c] = (float)(wx[0] * col[fx][c] + wx[1] * col[fx + 1][c] + wx[2] * col[fx + 2][c] +
                                     wx[3] * col[fx + 3][c]);
    }
}

/* Adds lambda * D^T D for the second differences along x and y of the grid. */
static void add_bending_penalty(gsl_matrix *A, int g, double lambda)
{
    for (int dir = 0; dir < 2; dir++)
        for (int j = 0; j < g; j++)
            for (int i = 0; i + 2 < g; i++) {
                int id[3];
                for (int k = 0; k < 3; k++)
                    id[k] = dir ? (i + k) * g + j : j * g + i + k;
                static const double d[3] = {1, -2, 1};
                for (int a = 0; a < 3; a++)
                    for (int c = 0; c < 3; c++)
                        *gsl_matrix_ptr(A, id[a], id[c]) += lambda * d[a] * d[c];
            }
}

/* One weighted solve: coef from the samples (x, y, colour, weight). The
 * normal equations are summed in plain arrays (a sample touches 16 control
 * points) and solved by Cholesky. */
static int solve(recon_backdrop *b, const double *xy, const float *col, const double *wt, int n)
{
    const int g = b->grid, m = g * g;
    double *ata = calloc((size_t)m * (m + 3), sizeof *ata), *atb = ata + (size_t)m * m;
    gsl_vector *x = gsl_vector_alloc(m), *bv = gsl_vector_alloc(m);
    int rc = -1;
    if (!ata || !x || !bv)
        goto out;
    double wsum = 0;
    for (int s = 0; s < n; s++) {
        if (wt[s] <= 0)
            continue;
        int fx, fy;
        double wx[4], wy[4], phi[16];
        int id[16];
        basis(xy[2 * s], b->width, g, &fx, wx);
        basis(xy[2 * s + 1], b->height, g, &fy, wy);
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) {
                phi[4 * j + i] = wx[i] * wy[j];
                id[4 * j + i] = (fy + j) * g + fx + i;
            }
        for (int a = 0; a < 16; a++) {
            double wa = wt[s] * phi[a];
            double *row = ata + (size_t)id[a] * m;
            for (int c = 0; c < 16; c++)
                row[id[c]] += wa * phi[c];
            for (int c = 0; c < 3; c++)
                atb[3 * id[a] + c] += wa * col[3 * s + c];
        }
        wsum += wt[s];
    }
    gsl_matrix_view A = gsl_matrix_view_array(ata, m, m);
    /* The penalty is small next to the data of a control point's support
     * (about wsum / m), so where there are pixels they decide; where there
     * are none it interpolates linearly. */
    add_bending_penalty(&A.matrix, g, 1e-3 * wsum / m + 1e-9);
    for (int i = 0; i < m; i++) /* a ridge: the bending penalty alone leaves planes free */
        ata[(size_t)i * m + i] += 1e-9 * (wsum / m + 1);
    if (gsl_linalg_cholesky_decomp1(&A.matrix) != 0)
        goto out;
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < m; i++)
            gsl_vector_set(bv, i, atb[3 * i + c]);
        if (gsl_linalg_cholesky_solve(&A.matrix, bv, x) != 0)
            goto out;
        for (int i = 0; i < m; i++)
            b->coef[i][c] = gsl_vector_get(x, i);
    }
    rc = 0;
out:
    gsl_vector_free(bv);
    gsl_vector_free(x);
    free(ata);
    return rc;
}

/* Tukey's biweight constant (95% efficiency for normal residuals). */
#define TUKEY_C 4.685
/* MAD to sigma for a normal distribution. */
#define MAD_TO_SIGMA 1.4826

int recon_backdrop_fit(recon_backdrop *b, const float *rgb, int w, int h, const uint8_t *use, int step, int grid,
                       int rounds)
{
    if (grid < 4 || grid > RECON_BACKDROP_MAX_GRID || step < 1)
        return -1;
    memset(b, 0, sizeof *b);
    b->grid = grid;
    b->width = w;
    b->height = h;
    int cap = ((w + step - 1) / step) * ((h + step - 1) / step);
    double *xy = malloc((size_t)cap * 2 * sizeof *xy), *wt = malloc((size_t)cap * 2 * sizeof *wt);
    float *col = malloc((size_t)cap * 3 * sizeof *col);
    int rc = -1, n = 0;
    if (!xy || !wt || !col)
        goto out;
    for (int y = step / 2; y < h; y += step)
        for (int x = step / 2; x < w; x += step) {
            size_t p = (size_t)y * w + x;
            if (!use[p])
                continue;
            xy[2 * n] = x + 0.5;
            xy[2 * n + 1] = y + 0.5;
            memcpy(col + 3 * n, rgb + 3 * p, 3 * sizeof *col);
            wt[n++] = 1;
        }
    if (n < grid * grid)
        goto out;
    double *res = wt + cap;
    for (int r = 0;; r++) {
        if (solve(b, xy, col, wt, n) != 0)
            goto out;
        for (int s = 0; s < n; s++) {
            double m[3];
            recon_backdrop_at(b, xy[2 * s], xy[2 * s + 1], m);
            double d0 = col[3 * s] - m[0], d1 = col[3 * s + 1] - m[1], d2 = col[3 * s + 2] - m[2];
            res[s] = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        }
        double *tmp = malloc((size_t)n * sizeof *tmp);
        if (!tmp)
            goto out;
        memcpy(tmp, res, (size_t)n * sizeof *tmp);
        double sigma = MAD_TO_SIGMA * gsl_stats_select(tmp, 1, (size_t)n, (size_t)n / 2) + 1e-4;
        free(tmp);
        double cut = TUKEY_C * sigma;
        if (r == rounds) {
            /* The residual covariance of the inliers (pixels the last fit
             * gave weight): what a backdrop pixel varies by. */
            double s = 0, c[9] = {0};
            for (int k = 0; k < n; k++) {
                if (res[k] >= cut)
                    continue;
                double m[3], d[3];
                recon_backdrop_at(b, xy[2 * k], xy[2 * k + 1], m);
                for (int i = 0; i < 3; i++)
                    d[i] = col[3 * k + i] - m[i];
                for (int i = 0; i < 9; i++)
                    c[i] += d[i / 3] * d[i % 3];
                s += 1;
            }
            for (int i = 0; i < 9; i++)
                b->cov[i] = c[i] / s + (i % 4 == 0 ? 1.0 / (255.0 * 255.0) : 0);
            break;
        }
        for (int s = 0; s < n; s++) {
            double u = res[s] / cut;
            wt[s] = u < 1 ? (1 - u * u) * (1 - u * u) : 0;
        }
    }
    rc = 0;
out:
    free(xy);
    free(wt);
    free(col);
    return rc;
}
