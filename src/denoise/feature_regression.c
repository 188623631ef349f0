/* The denoiser's filter (denoise/feature_regression.h): per pixel, a
 * weighted first-order regression of the colours of a (2R+1)^2 window on
 * the features; with two half-sample renders, each regressed with the
 * weights of the other (cross-filtering) at several colour bandwidths, the
 * one chosen per pixel whose error the halves estimate least (NFOR,
 * Bitterli et al. 2016). */
#include "denoise/feature_regression.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    RADIUS = 10,     /* the window's half side */
    WINDOW = (2 * RADIUS + 1) * (2 * RADIUS + 1),
    NREG = 11,       /* regressors: 1, dx, dy, albedo (3), normal (3), depth, mirror light */
    SELECT_RADIUS = 3 /* the error estimates are averaged over 7x7 pixels before choosing */
};

/* Rousselle et al.'s NL-means on colour: k sets how many standard
 * deviations of difference still count as alike; EPS keeps noise-free
 * pixels (variance 0) from dividing by zero. One buffer: K_COLOUR; two
 * halves: each of the caller's, chosen per pixel. */
static const double K_COLOUR = 0.45, EPS_COLOUR = 1e-8;
/* The features' scales in the weights: albedo and normal differences, and
 * depth relative to the pixel's own. */
static const double SIGMA_ALBEDO = 0.1, SIGMA_NORMAL = 0.3, SIGMA_DEPTH = 0.1;
/* Ridge on the standardised slopes, relative to the weights' sum: keeps
 * the normal equations solvable; shrinks a slope by 1e-4 of itself. */
static const double RIDGE = 1e-4;
/* A regressor whose weighted spread in the window is below this is left
 * out (constant feature, e.g. one flat wall's normal). */
static const double MIN_SPREAD = 1e-6;
/* What one regression reads: the features (stride: DENOISE_CHANNELS, or
 * FEATURE_STRIDE with the mirror light), the
 * colour whose patches weigh the neighbours (guide) and the colour that is
 * regressed (target), both stride 3, and the variance of the guide's
 * pixels (each channel). */
typedef struct {
    int w, h, stride;
    const float *feat;
    const float *guide, *target;
    const double *var;
} image;

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

static const float *features(const image *im, int x, int y)
{
    return im->feat + ((size_t)y * im->w + x) * im->stride;
}

static int finite_pixel(const float *v, int n)
{
    for (int c = 0; c < n; c++)
        if (!isfinite(v[c]))
            return 0;
    return 1;
}

/* v averaged over each (2r+1)^2 neighbourhood within the image (NULL:
 * out of memory). */
static double *box_mean(int w, int h, const double *v, int r)
{
    double *out = malloc(sizeof *out * (size_t)w * h);
    if (!out)
        return NULL;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            int n = 0;
            for (int yy = clampi(y - r, 0, h - 1); yy <= clampi(y + r, 0, h - 1); yy++)
                for (int xx = clampi(x - r, 0, w - 1); xx <= clampi(x + r, 0, w - 1); xx++)
                    s += v[(size_t)yy * w + xx], n++;
            out[(size_t)y * w + x] = s / n;
        }
    return out;
}

/* The variance channel of in, non-finite or negative values as 0 (NULL:
 * out of memory). */
static double *variance_channel(int w, int h, const float *in)
{
    double *v = malloc(sizeof *v * (size_t)w * h);
    if (!v)
        return NULL;
    for (size_t p = 0; p < (size_t)w * h; p++) {
        float s = in[p * DENOISE_CHANNELS + DENOISE_CH_VARIANCE];
        v[p] = isfinite(s) && s > 0 ? s : 0.0;
    }
    return v;
}

/* The squared distance of the 3x3 patches of the guide around p and q
 * (edges clamped), each term less the pixels' variance and over their
 * summed variance (Rousselle et al. 2012); the NL-means weight for
 * bandwidth k is exp(-max(d, 0) / k^2). */
static double patch_distance(const image *im, int px, int py, int qx, int qy)
{
    double d = 0;
    for (int oy = -1; oy <= 1; oy++)
        for (int ox = -1; ox <= 1; ox++) {
            int ax = clampi(px + ox, 0, im->w - 1), ay = clampi(py + oy, 0, im->h - 1);
            int bx = clampi(qx + ox, 0, im->w - 1), by = clampi(qy + oy, 0, im->h - 1);
            const float *a = im->guide + ((size_t)ay * im->w + ax) * 3, *b = im->guide + ((size_t)by * im->w + bx) * 3;
            double va = im->var[(size_t)ay * im->w + ax], vb = im->var[(size_t)by * im->w + bx];
            double diff = 0;
            for (int c = 0; c < 3; c++) {
                double e = (double)a[c] - b[c];
                diff += e * e;
            }
            d += (diff / 3 - (va + fmin(va, vb))) / (EPS_COLOUR + va + vb);
        }
    return d / 9;
}

static double feature_weight(const float *p, const float *q)
{
    double da = 0, dn = 0;
    for (int c = 0; c < 3; c++) {
        double a = (double)p[DENOISE_CH_ALBEDO + c] - q[DENOISE_CH_ALBEDO + c];
        double n = (double)p[DENOISE_CH_NORMAL + c] - q[DENOISE_CH_NORMAL + c];
        da += a * a, dn += n * n;
    }
    double zs = SIGMA_DEPTH * fmax(fmax(fabs(p[DENOISE_CH_DEPTH]), fabs(q[DENOISE_CH_DEPTH])), 1e-6);
    double dz = ((double)p[DENOISE_CH_DEPTH] - q[DENOISE_CH_DEPTH]) / zs;
    return exp(-0.5 * (da / (SIGMA_ALBEDO * SIGMA_ALBEDO) + dn / (SIGMA_NORMAL * SIGMA_NORMAL) + dz * dz));
}

/* Weighted least squares with noise of unequal variance weighs each
 * sample by the inverse of its variance: a neighbour noisier than p (a
 * firefly, a caustic) counts for p's variance over its own. */
static double variance_weight(const image *im, int px, int py, int qx, int qy)
{
    double vp = im->var[(size_t)py * im->w + px], vq = im->var[(size_t)qy * im->w + qx];
    return vq > vp ? (vp + 1e-12) / (vq + 1e-12) : 1.0;
}

/* Solves the symmetric positive definite a (n x n) x = b for 3 right-hand
 * sides in place (Cholesky); -1 when a is not positive definite. */
static int cholesky_solve(double a[NREG][NREG], double b[NREG][3], int n)
{
    for (int j = 0; j < n; j++) {
        double d = a[j][j];
        for (int k = 0; k < j; k++)
            d -= a[j][k] * a[j][k];
        if (!(d > 0))
            return -1;
        a[j][j] = sqrt(d);
        for (int i = j + 1; i < n; i++) {
            double s = a[i][j];
            for (int k = 0; k < j; k++)
                s -= a[i][k] * a[j][k];
            a[i][j] = s / a[j][j];
        }
    }
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < n; i++) {
            double s = b[i][c];
            for (int k = 0; k < i; k++)
                s -= a[i][k] * b[k][c];
            b[i][c] = s / a[i][i];
        }
        for (int i = n - 1; i >= 0; i--) {
            double s = b[i][c];
            for (int k = i + 1; k < n; k++)
                s -= a[k][i] * b[k][c];
            b[i][c] = s / a[i][i];
        }
    }
    return 0;
}

/* The regressors of q relative to p: 1, the screen offset over the
 * radius, the albedo and normal differences, the depth difference
 * relative to p's depth, the mirror light's difference (0 without it: a
 * regressor with no spread is left out). */
static void regressors(const float *p, const float *q, int stride, int dx, int dy, double *x)
{
    x[0] = 1.0;
    x[1] = (double)dx / RADIUS, x[2] = (double)dy / RADIUS;
    for (int c = 0; c < 3; c++) {
        x[3 + c] = (double)q[DENOISE_CH_ALBEDO + c] - p[DENOISE_CH_ALBEDO + c];
        x[6 + c] = (double)q[DENOISE_CH_NORMAL + c] - p[DENOISE_CH_NORMAL + c];
    }
    x[9] = ((double)q[DENOISE_CH_DEPTH] - p[DENOISE_CH_DEPTH]) / fmax(fabs(p[DENOISE_CH_DEPTH]), 1e-6);
    x[10] = stride > FEATURE_MIRROR ? (double)q[FEATURE_MIRROR] - p[FEATURE_MIRROR] : 0.0;
}

/* The intercept (the value at p's own features) of the least-squares fit
 * of y on x with weights w over n neighbours, into out; p's own colour
 * when the fit fails. */
static void fit_intercept(int n, const double *w, double x[][NREG], double y[][3], const float *own, float *out)
{
    /* Standardise each slope regressor by its weighted root mean square
     * about p (0 leaves it out), so that one ridge fits every feature. */
    double total = 0, scale[NREG] = {1.0};
    for (int i = 0; i < n; i++)
        total += w[i];
    for (int j = 1; j < NREG; j++) {
        double m = 0;
        for (int i = 0; i < n; i++)
            m += w[i] * x[i][j] * x[i][j];
        m = sqrt(m / total);
        scale[j] = m > MIN_SPREAD ? 1.0 / m : 0.0;
    }
    double a[NREG][NREG], b[NREG][3];
    memset(a, 0, sizeof a);
    memset(b, 0, sizeof b);
    for (int i = 0; i < n; i++) {
        if (w[i] == 0.0)
            continue;
        double xs[NREG];
        for (int j = 0; j < NREG; j++)
            xs[j] = x[i][j] * scale[j];
        for (int j = 0; j < NREG; j++) {
            double wx = w[i] * xs[j];
            for (int k = 0; k <= j; k++)
                a[j][k] += wx * xs[k];
            for (int c = 0; c < 3; c++)
                b[j][c] += wx * y[i][c];
        }
    }
    for (int j = 1; j < NREG; j++)
        a[j][j] += scale[j] > 0 ? RIDGE * total : total;
    if (cholesky_solve(a, b, NREG) != 0) {
        memcpy(out, own, 3 * sizeof *out);
        return;
    }
    for (int c = 0; c < 3; c++)
        out[c] = (float)b[0][c];
}

/* The target's colour at (px, py) denoised at each of the nk bandwidths
 * ks, into out[k * 3 ...]. */
static void denoise_pixel(const image *im, int px, int py, const double *ks, int nk, float *out)
{
    const float *p = features(im, px, py);
    double d[WINDOW], wf[WINDOW], w[WINDOW], x[WINDOW][NREG], y[WINDOW][3];
    int n = 0;
    for (int qy = py - RADIUS; qy <= py + RADIUS; qy++)
        for (int qx = px - RADIUS; qx <= px + RADIUS; qx++) {
            if (qx < 0 || qy < 0 || qx >= im->w || qy >= im->h)
                continue;
            const float *q = features(im, qx, qy), *t = im->target + ((size_t)qy * im->w + qx) * 3;
            if (!finite_pixel(q, im->stride) || !finite_pixel(t, 3) ||
                !finite_pixel(im->guide + ((size_t)qy * im->w + qx) * 3, 3))
                continue;
            wf[n] = feature_weight(p, q) * variance_weight(im, px, py, qx, qy);
            if (!(wf[n] > 1e-6))
                continue;
            d[n] = fmax(patch_distance(im, px, py, qx, qy), 0.0);
            regressors(p, q, im->stride, qx - px, qy - py, x[n]);
            for (int c = 0; c < 3; c++)
                y[n][c] = t[c];
            n++;
        }
    const float *own = im->target + ((size_t)py * im->w + px) * 3;
    for (int k = 0; k < nk; k++) {
        for (int i = 0; i < n; i++) {
            w[i] = wf[i] * exp(-d[i] / (ks[k] * ks[k]));
            w[i] = w[i] > 1e-6 ? w[i] : 0.0;
        }
        fit_intercept(n, w, x, y, own, out + 3 * k);
    }
}

/* Every pixel of im denoised at the nk bandwidths ks: out holds, per
 * pixel, nk colours. Non-finite pixels are taken as they are. */
static void denoise_all(const image *im, const double *ks, int nk, float *out)
{
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            float *o = out + ((size_t)y * im->w + x) * 3 * nk;
            const float *t = im->target + ((size_t)y * im->w + x) * 3;
            if (finite_pixel(features(im, x, y), im->stride) && finite_pixel(t, 3))
                denoise_pixel(im, x, y, ks, nk, o);
            else
                for (int k = 0; k < nk; k++)
                    memcpy(o + 3 * k, t, 3 * sizeof *o);
        }
}

/* The RGB of in (stride DENOISE_CHANNELS), stride 3 (NULL: out of
 * memory). */
static float *colour_of(int w, int h, const float *in)
{
    float *c = malloc(sizeof *c * (size_t)w * h * 3);
    if (!c)
        return NULL;
    for (size_t p = 0; p < (size_t)w * h; p++)
        memcpy(c + 3 * p, in + p * DENOISE_CHANNELS, 3 * sizeof *c);
    return c;
}

int denoise_image(int width, int height, const float *in, float *out)
{
    double *raw = variance_channel(width, height, in);
    /* The variance averaged over each 3x3 neighbourhood (a 16-spp estimate
     * of it is itself noisy). */
    double *var = raw ? box_mean(width, height, raw, 1) : NULL;
    float *colour = colour_of(width, height, in);
    int rc = -1;
    if (var && colour) {
        image im = {width, height, DENOISE_CHANNELS, in, colour, colour, var};
        denoise_all(&im, &K_COLOUR, 1, out);
        rc = 0;
    }
    free(raw), free(var), free(colour);
    return rc;
}

/* The variance of a half's pixels (each channel): the sample variance
 * (3x3-averaged), rescaled by how far the halves actually differ around
 * the pixel, since with quasi-random samplers the sample variance
 * overstates the error of the mean several times (Rousselle et al. 2012
 * use the halves' difference alike). Where the sample variance is 0 the
 * halves' difference alone, averaged. NULL: out of memory. */
static double *half_variance(int w, int h, const double *raw, const float *a, const float *b)
{
    size_t n = (size_t)w * h;
    double *diff = malloc(sizeof *diff * n);
    if (!diff)
        return NULL;
    for (size_t p = 0; p < n; p++) {
        double s = 0;
        for (int c = 0; c < 3; c++) {
            double e = (double)a[3 * p + c] - b[3 * p + c];
            s += isfinite(e) ? e * e : 0.0;
        }
        diff[p] = s / 6; /* E[(a - b)^2] = 2 var(half) */
    }
    double *sample = box_mean(w, h, raw, 1), *sample_wide = box_mean(w, h, raw, 4),
           *diff_wide = box_mean(w, h, diff, 4), *var = malloc(sizeof *var * n);
    /* A half holds half the samples: its variance is twice the whole's
     * (the sample variance's), so 2 sample[p] rescaled by diff_wide / (2
     * sample_wide). */
    if (sample && sample_wide && diff_wide && var)
        for (size_t p = 0; p < n; p++)
            var[p] = sample_wide[p] > 0 ? sample[p] * diff_wide[p] / sample_wide[p] : diff_wide[p];
    else
        free(var), var = NULL;
    free(diff), free(sample), free(sample_wide), free(diff_wide);
    return var;
}

/* Each bandwidth's error at each pixel, estimated from the halves: the
 * filtered a (fa) against b (independent of a; E[(fa - b)^2] = MSE(fa) +
 * var(b)) and vice versa, less what averaging fa and fb removes of their
 * variance, (fa - fb)^2 / 4; then averaged over SELECT_RADIUS. Into err
 * (nk per pixel); -1: out of memory. */
static int bandwidth_errors(int w, int h, const float *a, const float *b, const float *fa, const float *fb,
                            const double *var, int nk, double *err)
{
    size_t n = (size_t)w * h;
    double *e = malloc(sizeof *e * n);
    if (!e)
        return -1;
    for (int k = 0; k < nk; k++) {
        for (size_t p = 0; p < n; p++) {
            double s = 0;
            for (int c = 0; c < 3; c++) {
                double xa = fa[(p * nk + k) * 3 + c], xb = fb[(p * nk + k) * 3 + c];
                double ea = xa - b[3 * p + c], eb = xb - a[3 * p + c], dab = xa - xb;
                s += 0.5 * (ea * ea + eb * eb) - 0.25 * dab * dab;
            }
            e[p] = isfinite(s) ? s / 3 - var[p] : INFINITY;
        }
        double *smooth = box_mean(w, h, e, SELECT_RADIUS);
        if (!smooth) {
            free(e);
            return -1;
        }
        for (size_t p = 0; p < n; p++)
            err[p * nk + k] = isfinite(smooth[p]) ? smooth[p] : INFINITY;
        free(smooth);
    }
    free(e);
    return 0;
}

int feature_regression_halves(int width, int height, const float *feat, const float *a, const float *b,
                              const double *sample_variance, const double *ks, int nk, float *out)
{
    size_t n = (size_t)width * height, NK = (size_t)nk;
    float *fa = malloc(sizeof *fa * n * 3 * NK), *fb = malloc(sizeof *fb * n * 3 * NK);
    double *err = malloc(sizeof *err * n * NK), *var = half_variance(width, height, sample_variance, a, b);
    int rc = -1;
    if (fa && fb && err && var) {
        /* Cross-filtering: each half regressed with the weights of the
         * other, so that a half's noise does not choose its own weights. */
        image ia = {width, height, FEATURE_STRIDE, feat, b, a, var}, ib = {width, height, FEATURE_STRIDE, feat, a, b, var};
        denoise_all(&ia, ks, nk, fa);
        denoise_all(&ib, ks, nk, fb);
        rc = bandwidth_errors(width, height, a, b, fa, fb, var, nk, err);
    }
    if (rc == 0)
        for (size_t p = 0; p < n; p++) {
            size_t best = 0;
            for (size_t k = 1; k < NK; k++)
                best = err[p * NK + k] < err[p * NK + best] ? k : best;
            for (int c = 0; c < 3; c++)
                out[3 * p + c] = 0.5f * (fa[(p * NK + best) * 3 + c] + fb[(p * NK + best) * 3 + c]);
        }
    free(fa), free(fb), free(err), free(var);
    return rc;
}
