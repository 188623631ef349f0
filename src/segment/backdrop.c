/* recon_backdrop: robust penalised least squares of a cubic B-spline surface.
 * See backdrop.h. */
#include "segment/backdrop.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_statistics_double.h>

#include "segment/robust.h"
#include "core/core.h"

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

void recon_backdrop_basis_x(const recon_backdrop *b, double x, recon_backdrop_basis *out)
{
    basis(x, b->width, b->grid, &out->first, out->wt);
}

void recon_backdrop_basis_y(const recon_backdrop *b, double y, recon_backdrop_basis *out)
{
    basis(y, b->height, b->grid, &out->first, out->wt);
}

/* The surface at a point whose 16 basis weights (wx[i] wy[j] at 4 j + i)
 * start at control point `first` (the others follow: + j g + i), summed in
 * registers, the three channels (and the padding) as one 4-lane vector; the
 * fit's residuals and every evaluation sum in this one order. */
RECON_VECTOR_CLONES static void surface_sum(const recon_backdrop *b, int first, const double phi[16], double out[3])
{
    double s[4] = {0, 0, 0, 0};
#pragma GCC unroll 4
    for (int j = 0; j < 4; j++) {
        const double(*c)[4] = b->coef + first + j * b->grid;
#pragma GCC unroll 4
        for (int i = 0; i < 4; i++) {
            const double p = phi[4 * j + i];
#pragma omp simd
            for (int k = 0; k < 4; k++)
                s[k] += p * c[i][k];
        }
    }
    out[0] = s[0];
    out[1] = s[1];
    out[2] = s[2];
}

void recon_backdrop_at_basis(const recon_backdrop *b, const recon_backdrop_basis *bx, const recon_backdrop_basis *by,
                             double out[3])
{
    double phi[16];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            phi[4 * j + i] = bx->wt[i] * by->wt[j];
    surface_sum(b, by->first * b->grid + bx->first, phi, out);
}

void recon_backdrop_at(const recon_backdrop *b, double x, double y, double out[3])
{
    recon_backdrop_basis bx, by;
    recon_backdrop_basis_x(b, x, &bx);
    recon_backdrop_basis_y(b, y, &by);
    recon_backdrop_at_basis(b, &bx, &by, out);
}

void recon_backdrop_collapse_row(const recon_backdrop *b, const recon_backdrop_basis *by,
                                 double col[RECON_BACKDROP_MAX_GRID][3])
{
    const int g = b->grid;
    for (int i = 0; i < g; i++)
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (int j = 0; j < 4; j++)
                s += by->wt[j] * b->coef[(by->first + j) * g + i][c];
            col[i][c] = s;
        }
}

void recon_backdrop_at_collapsed(const double col[RECON_BACKDROP_MAX_GRID][3], const recon_backdrop_basis *bx,
                                 float out[3])
{
    const double *w = bx->wt;
    const int f = bx->first;
    for (int c = 0; c < 3; c++)
        out[c] = (float)(w[0] * col[f][c] + w[1] * col[f + 1][c] + w[2] * col[f + 2][c] + w[3] * col[f + 3][c]);
}

void recon_backdrop_row(const recon_backdrop *b, int y, float *out)
{
    recon_backdrop_basis by, bx;
    double col[RECON_BACKDROP_MAX_GRID][3];
    recon_backdrop_basis_y(b, y + 0.5, &by);
    recon_backdrop_collapse_row(b, &by, col);
    for (int x = 0; x < b->width; x++) {
        recon_backdrop_basis_x(b, x + 0.5, &bx);
        recon_backdrop_at_collapsed(col, &bx, out + 3 * x);
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

/* A sample's 16 basis weights (wx[i] wy[j] at 4 j + i) and the index of its
 * first control point (the others follow: + j g + i). */
typedef struct {
    double phi[16];
    int first;
} sample_basis;

static void sample_basis_at(const recon_backdrop *b, double x, double y, sample_basis *sb)
{
    int fx, fy;
    double wx[4], wy[4];
    basis(x, b->width, b->grid, &fx, wx);
    basis(y, b->height, b->grid, &fy, wy);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            sb->phi[4 * j + i] = wx[i] * wy[j];
    sb->first = fy * b->grid + fx;
}

/* Adds a sample of weight w to its span cell's block of the normal
 * equations: the 16x16 products of its basis weights (blk, dense) and its
 * colour's (rhs, 16x4, the fourth column unused). The samples of one cell
 * share their 16 control points, so the block is summed contiguously and
 * goes into the whole system once. Only the lower triangle is read (the
 * Cholesky factorisation reads no other): row a is summed up to the end of
 * its group of four, a vector at a time. */
RECON_VECTOR_CLONES static void add_sample(double *restrict blk, double *restrict rhs, const double *restrict phi,
                                           const float *c, double w)
{
    const double c4[4] = {c[0], c[1], c[2], 0};
#pragma GCC unroll 16
    for (int a = 0; a < 16; a++) {
        double wa = w * phi[a], *row = blk + 16 * a, *r = rhs + 4 * a;
#pragma GCC unroll 4
        for (int q0 = 0; q0 <= a; q0 += 4)
#pragma omp simd
            for (int q = q0; q < q0 + 4; q++)
                row[q] += wa * phi[q];
#pragma omp simd
        for (int k = 0; k < 4; k++)
            r[k] += wa * c4[k];
    }
}

/* One weighted solve: coef from the samples (basis, colour, weight). The
 * normal equations are summed per span cell (add_sample) and solved by
 * Cholesky. */
static int solve(recon_backdrop *b, const sample_basis *sb, const float *col, const double *wt, int n)
{
    const int g = b->grid, m = g * g, spans = g - 3;
    double *ata = calloc((size_t)m * (m + 3), sizeof *ata), *atb = ata ? ata + (size_t)m * m : NULL;
    double *blk = calloc((size_t)spans * spans * (256 + 64), sizeof *blk);
    gsl_vector *x = gsl_vector_alloc(m), *bv = gsl_vector_alloc(m);
    int rc = -1;
    if (!ata || !blk || !x || !bv)
        goto out;
    double wsum = 0;
    for (int s = 0; s < n; s++) {
        if (wt[s] <= 0)
            continue;
        int cell = sb[s].first / g * spans + sb[s].first % g;
        double *cb = blk + (size_t)cell * (256 + 64);
        add_sample(cb, cb + 256, sb[s].phi, col + 3 * s, wt[s]);
        wsum += wt[s];
    }
    for (int cell = 0; cell < spans * spans; cell++) {
        const double *cb = blk + (size_t)cell * (256 + 64);
        int first = cell / spans * g + cell % spans; /* control point a = 4 j + i is at first + j g + i */
        for (int a = 0; a < 16; a++) {
            int ia = first + a / 4 * g + a % 4;
            for (int q = 0; q <= a; q++) /* ia >= iq: the lower triangle */
                ata[(size_t)ia * m + first + q / 4 * g + q % 4] += cb[16 * a + q];
            for (int k = 0; k < 3; k++)
                atb[3 * ia + k] += cb[256 + 4 * a + k];
        }
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
    free(blk);
    free(ata);
    return rc;
}

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
    sample_basis *sb = malloc((size_t)cap * sizeof *sb);
    double *wt = malloc((size_t)cap * 2 * sizeof *wt);
    float *col = malloc((size_t)cap * 3 * sizeof *col);
    int rc = -1, n = 0;
    if (!sb || !wt || !col)
        goto out;
    for (int y = step / 2; y < h; y += step)
        for (int x = step / 2; x < w; x += step) {
            size_t p = (size_t)y * w + x;
            if (!use[p])
                continue;
            sample_basis_at(b, x + 0.5, y + 0.5, &sb[n]);
            memcpy(col + 3 * n, rgb + 3 * p, 3 * sizeof *col);
            wt[n++] = 1;
        }
    if (n < grid * grid)
        goto out;
    double *res = wt + cap;
    for (int r = 0;; r++) {
        if (solve(b, sb, col, wt, n) != 0)
            goto out;
        for (int s = 0; s < n; s++) {
            double m[3];
            surface_sum(b, sb[s].first, sb[s].phi, m);
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
                surface_sum(b, sb[k].first, sb[k].phi, m);
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
    free(sb);
    free(wt);
    free(col);
    return rc;
}
