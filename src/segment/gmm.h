/* Gaussian mixture models of colours (3 channels), full covariance: the
 * object's colour model of the segmentation (segment.c). */
#ifndef CELADON_SEGMENT_GMM_H
#define CELADON_SEGMENT_GMM_H

#include <stdint.h>

enum { RECON_GMM_MAX_K = 8 };

typedef struct {
    int k;                          /* components in use */
    double mean[RECON_GMM_MAX_K][3];
    double icov[RECON_GMM_MAX_K][9]; /* inverse covariance, row-major */
    double lognorm[RECON_GMM_MAX_K]; /* log(weight) - log((2 pi)^1.5 sqrt(det cov)) */
} recon_gmm;

/* Fits up to k components (1..RECON_GMM_MAX_K) to the colours rgb[3 idx[i]]
 * (i < n): Orchard–Bouman splitting, then `rounds` rounds of hard assignment
 * and refit, as GrabCut does. Covariances get (2/255)^2 on the diagonal.
 * Components left with fewer than 2 colours are dropped. Returns 0, or -1
 * when n < 2k or out of memory. */
int recon_gmm_fit(recon_gmm *g, const float *rgb, const int *idx, int n, int k, int rounds);

/* log p(c) of the mixture (a density over colours in [0,1]^3). */
double recon_gmm_log_density(const recon_gmm *g, const float *c);

/* Inverse and log-determinant of a symmetric positive definite 3x3 matrix
 * (row-major; both triangles of inv set). Returns 0, or -1 when it is not
 * positive definite. The segmentation's single Gaussians use it too. */
int recon_invert_sym3(const double a[9], double inv[9], double *logdet);

/* d^T q d for a symmetric 3x3 q (only its upper triangle is read). */
static inline double recon_quad3(const double q[9], const double d[3])
{
    return d[0] * (q[0] * d[0] + 2 * q[1] * d[1] + 2 * q[2] * d[2]) + d[1] * (q[4] * d[1] + 2 * q[5] * d[2]) +
           d[2] * q[8] * d[2];
}

#endif
