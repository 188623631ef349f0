/* Gaussian mixtures of colours, fitted as GrabCut fits them: Orchard–Bouman
 * splitting for the start, then a few rounds of hard assignment and refit. */
#include "segment/gmm.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>

/* Every covariance gets this variance added on its diagonal: colours are
 * quantised to 1/255 and a component of equal pixels (a flat black-and-white
 * photo) would otherwise be singular. (2/255)^2. */
#define GMM_VARIANCE_FLOOR (4.0 / (255.0 * 255.0))

/* sq holds the upper triangle (i <= j at 3 i + j): the products commute
 * exactly, so the lower one would be the same sums. */
typedef struct {
    double n, sum[3], sq[9];
} moments;

static void moments_add(moments *m, const float *c)
{
    const double c0 = c[0], c1 = c[1], c2 = c[2];
    m->n += 1;
    m->sum[0] += c0;
    m->sum[1] += c1;
    m->sum[2] += c2;
    m->sq[0] += c0 * c0;
    m->sq[1] += c0 * c1;
    m->sq[2] += c0 * c2;
    m->sq[4] += c1 * c1;
    m->sq[5] += c1 * c2;
    m->sq[8] += c2 * c2;
}

/* Mean and covariance (with the variance floor) of the moments. */
static void moments_stats(const moments *m, double mu[3], double cov[9])
{
    for (int i = 0; i < 3; i++)
        mu[i] = m->sum[i] / m->n;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cov[3 * i + j] = m->sq[i <= j ? 3 * i + j : 3 * j + i] / m->n - mu[i] * mu[j] + (i == j ? GMM_VARIANCE_FLOOR : 0);
}

int recon_invert_sym3(const double a[9], double inv[9], double *logdet)
{
    double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
    double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
    if (!(det > 0))
        return -1;
    double id = 1 / det;
    inv[0] = c00 * id;
    inv[1] = inv[3] = c01 * id;
    inv[2] = inv[6] = c02 * id;
    inv[4] = (a[0] * a[8] - a[2] * a[6]) * id;
    inv[5] = inv[7] = (a[2] * a[3] - a[0] * a[5]) * id;
    inv[8] = (a[0] * a[4] - a[1] * a[3]) * id;
    *logdet = log(det);
    return 0;
}

/* Sets component k from its moments; 0, or -1 when it has too few pixels. */
static int set_component(recon_gmm *g, int k, const moments *m, double total)
{
    if (m->n < 2)
        return -1;
    double cov[9], logdet;
    moments_stats(m, g->mean[k], cov);
    if (recon_invert_sym3(cov, g->icov[k], &logdet) != 0)
        return -1;
    /* log(weight) - log((2 pi)^(3/2) sqrt(det)) */
    g->lognorm[k] = log(m->n / total) - 1.5 * log(2 * M_PI) - 0.5 * logdet;
    return 0;
}

static double mahalanobis2(const recon_gmm *g, int k, const float *c)
{
    double d[3] = {c[0] - g->mean[k][0], c[1] - g->mean[k][1], c[2] - g->mean[k][2]};
    return recon_quad3(g->icov[k], d);
}

/* The component that explains c best (hard assignment). */
static int best_component(const recon_gmm *g, const float *c)
{
    int best = 0;
    double bl = -INFINITY;
    for (int k = 0; k < g->k; k++) {
        double l = g->lognorm[k] - 0.5 * mahalanobis2(g, k, c);
        if (l > bl) {
            bl = l;
            best = k;
        }
    }
    return best;
}

double recon_gmm_log_density(const recon_gmm *g, const float *c)
{
    double l[RECON_GMM_MAX_K], m = -INFINITY;
    for (int k = 0; k < g->k; k++) {
        l[k] = g->lognorm[k] - 0.5 * mahalanobis2(g, k, c);
        m = l[k] > m ? l[k] : m;
    }
    /* exp(0) of the largest term is 1, without the call */
    double s = 0;
    for (int k = 0; k < g->k; k++)
        s += l[k] - m == 0 ? 1.0 : exp(l[k] - m);
    return m + log(s);
}

/* Orchard–Bouman: start from one cluster and split, k-1 times, the cluster
 * whose covariance has the largest eigenvalue, along that eigenvector at the
 * cluster's mean. Writes each sample's cluster to lab. */
static int split_clusters(const float *rgb, const int *idx, int n, int k, uint8_t *lab)
{
    memset(lab, 0, (size_t)n);
    gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(3);
    gsl_matrix *a = gsl_matrix_alloc(3, 3), *ev = gsl_matrix_alloc(3, 3);
    gsl_vector *eval = gsl_vector_alloc(3);
    int ok = ws && a && ev && eval;
    for (int have = 1; ok && have < k; have++) {
        moments m[RECON_GMM_MAX_K];
        memset(m, 0, sizeof m);
        for (int i = 0; i < n; i++)
            moments_add(&m[lab[i]], rgb + 3 * (size_t)idx[i]);
        int split = -1;
        double best = 0, axis[3] = {0, 0, 0}, mu_s[3] = {0, 0, 0};
        for (int c = 0; c < have; c++) {
            if (m[c].n < 2)
                continue;
            double mu[3], cov[9];
            moments_stats(&m[c], mu, cov);
            for (int i = 0; i < 9; i++)
                a->data[i] = cov[i];
            gsl_eigen_symmv(a, eval, ev, ws);
            gsl_eigen_symmv_sort(eval, ev, GSL_EIGEN_SORT_VAL_DESC);
            double lam = gsl_vector_get(eval, 0) * m[c].n; /* spread times size: split the cluster that costs most */
            if (lam > best) {
                best = lam;
                split = c;
                for (int i = 0; i < 3; i++) {
                    axis[i] = gsl_matrix_get(ev, i, 0);
                    mu_s[i] = mu[i];
                }
            }
        }
        if (split < 0)
            break;
        for (int i = 0; i < n; i++) {
            if (lab[i] != split)
                continue;
            const float *c = rgb + 3 * (size_t)idx[i];
            double t = (c[0] - mu_s[0]) * axis[0] + (c[1] - mu_s[1]) * axis[1] + (c[2] - mu_s[2]) * axis[2];
            if (t > 0)
                lab[i] = (uint8_t)have;
        }
    }
    gsl_vector_free(eval);
    gsl_matrix_free(ev);
    gsl_matrix_free(a);
    gsl_eigen_symmv_free(ws);
    return ok ? 0 : -1;
}

/* Components from the clusters in lab; empty or degenerate ones are dropped. */
static int components_from_labels(recon_gmm *g, const float *rgb, const int *idx, int n, const uint8_t *lab, int k)
{
    moments m[RECON_GMM_MAX_K];
    memset(m, 0, sizeof m);
    for (int i = 0; i < n; i++)
        moments_add(&m[lab[i]], rgb + 3 * (size_t)idx[i]);
    g->k = 0;
    for (int c = 0; c < k; c++)
        if (set_component(g, g->k, &m[c], n) == 0)
            g->k++;
    return g->k > 0 ? 0 : -1;
}

int recon_gmm_fit(recon_gmm *g, const float *rgb, const int *idx, int n, int k, int rounds)
{
    if (k < 1 || k > RECON_GMM_MAX_K || n < 2 * k)
        return -1;
    uint8_t *lab = malloc((size_t)n);
    if (!lab)
        return -1;
    int rc = split_clusters(rgb, idx, n, k, lab);
    if (rc == 0)
        rc = components_from_labels(g, rgb, idx, n, lab, k);
    for (int r = 0; rc == 0 && r < rounds; r++) {
        int kk = g->k;
        for (int i = 0; i < n; i++)
            lab[i] = (uint8_t)best_component(g, rgb + 3 * (size_t)idx[i]);
        rc = components_from_labels(g, rgb, idx, n, lab, kk);
    }
    free(lab);
    return rc;
}
