/* The denoiser (celadon/denoise.h): per pixel, a weighted first-order
 * regression of the colours of a (2R+1)^2 window on the features. */
#include "celadon/denoise.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const denoise_channel_names[DENOISE_CHANNELS] = {
    "R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z", "variance.X"};

enum {
    RADIUS = 8,      /* the window's half side */
    WINDOW = (2 * RADIUS + 1) * (2 * RADIUS + 1),
    NREG = 10,       /* regressors: 1, dx, dy, albedo (3), normal (3), depth */
    CH_ALBEDO = 3, CH_NORMAL = 6, CH_DEPTH = 9, CH_VARIANCE = 10
};

/* Rousselle et al.'s NL-means on colour: k sets how many standard
 * deviations of difference still count as alike; EPS keeps noise-free
 * pixels (variance 0) from dividing by zero. */
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

typedef struct {
    int w, h;
    const float *in;
    const double *var; /* the variance channel, 3x3 box-filtered */
} image;

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

static const float *pixel(const image *im, int x, int y) { return im->in + ((size_t)y * im->w + x) * DENOISE_CHANNELS; }

static int finite_pixel(const float *v)
{
    for (int c = 0; c < DENOISE_CHANNELS; c++)
        if (!isfinite(v[c]))
            return 0;
    return 1;
}

/* The variance averaged over each 3x3 neighbourhood (a 16-spp estimate of
 * it is itself noisy); non-finite values count as 0. */
static double *smoothed_variance(int w, int h, const float *in)
{
    double *v = malloc(sizeof *v * (size_t)w * h);
    if (!v)
        abort();
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h)
                        continue;
                    float s1 = in[((size_t)yy * w + xx) * DENOISE_CHANNELS + CH_VARIANCE];
                    s += isfinite(s1) && s1 > 0 ? s1 : 0.0;
                    n++;
                }
            v[(size_t)y * w + x] = s / n;
        }
    return v;
}

/* The NL-means weight of q for p: the variance-cancelled squared colour
 * distance of their 3x3 patches (edges clamped), each term over the
 * pixels' summed variance. */
static double colour_weight(const image *im, int px, int py, int qx, int qy)
{
    double d = 0;
    for (int oy = -1; oy <= 1; oy++)
        for (int ox = -1; ox <= 1; ox++) {
            int ax = clampi(px + ox, 0, im->w - 1), ay = clampi(py + oy, 0, im->h - 1);
            int bx = clampi(qx + ox, 0, im->w - 1), by = clampi(qy + oy, 0, im->h - 1);
            const float *a = pixel(im, ax, ay), *b = pixel(im, bx, by);
            double va = im->var[(size_t)ay * im->w + ax], vb = im->var[(size_t)by * im->w + bx];
            double diff = 0;
            for (int c = 0; c < 3; c++) {
                double e = (double)a[c] - b[c];
                diff += e * e;
            }
            d += (diff / 3 - (va + fmin(va, vb))) / (EPS_COLOUR + K_COLOUR * K_COLOUR * (va + vb));
        }
    d /= 9;
    return d > 0 ? exp(-d) : 1.0;
}

static double feature_weight(const float *p, const float *q)
{
    double da = 0, dn = 0;
    for (int c = 0; c < 3; c++) {
        double a = (double)p[CH_ALBEDO + c] - q[CH_ALBEDO + c], n = (double)p[CH_NORMAL + c] - q[CH_NORMAL + c];
        da += a * a, dn += n * n;
    }
    double zs = SIGMA_DEPTH * fmax(fmax(fabs(p[CH_DEPTH]), fabs(q[CH_DEPTH])), 1e-6);
    double dz = ((double)p[CH_DEPTH] - q[CH_DEPTH]) / zs;
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
 * relative to p's depth. */
static void regressors(const float *p, const float *q, int dx, int dy, double *x)
{
    x[0] = 1.0;
    x[1] = (double)dx / RADIUS, x[2] = (double)dy / RADIUS;
    for (int c = 0; c < 3; c++) {
        x[3 + c] = (double)q[CH_ALBEDO + c] - p[CH_ALBEDO + c];
        x[6 + c] = (double)q[CH_NORMAL + c] - p[CH_NORMAL + c];
    }
    x[9] = ((double)q[CH_DEPTH] - p[CH_DEPTH]) / fmax(fabs(p[CH_DEPTH]), 1e-6);
}

/* The denoised colour of pixel (px, py): the intercept (the value at p's
 * own features) of the weighted least-squares fit over the window. */
static void denoise_pixel(const image *im, int px, int py, float *out)
{
    const float *p = pixel(im, px, py);
    double w[WINDOW], x[WINDOW][NREG], y[WINDOW][3];
    int n = 0;
    for (int qy = py - RADIUS; qy <= py + RADIUS; qy++)
        for (int qx = px - RADIUS; qx <= px + RADIUS; qx++) {
            if (qx < 0 || qy < 0 || qx >= im->w || qy >= im->h)
                continue;
            const float *q = pixel(im, qx, qy);
            if (!finite_pixel(q))
                continue;
            double wq = colour_weight(im, px, py, qx, qy) * feature_weight(p, q) * variance_weight(im, px, py, qx, qy);
            if (!(wq > 1e-6))
                continue;
            w[n] = wq;
            regressors(p, q, qx - px, qy - py, x[n]);
            for (int c = 0; c < 3; c++)
                y[n][c] = q[c];
            n++;
        }
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
        for (int c = 0; c < 3; c++)
            out[c] = p[c];
        return;
    }
    for (int c = 0; c < 3; c++)
        out[c] = (float)b[0][c];
}

void denoise_image(int width, int height, const float *in, float *out)
{
    image im = {width, height, in, smoothed_variance(width, height, in)};
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const float *p = pixel(&im, x, y);
            float *o = out + ((size_t)y * width + x) * 3;
            if (finite_pixel(p))
                denoise_pixel(&im, x, y, o);
            else
                memcpy(o, p, 3 * sizeof *o);
        }
    free((void *)im.var);
}
