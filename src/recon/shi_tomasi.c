/* 7x7 Gaussian smoothing and the Shi–Tomasi corner response (J. Shi,
 * C. Tomasi, "Good features to track", CVPR 1994): the smaller eigenvalue of
 * the gradient structure tensor.
 *
 * The whole-image filters run row by row over a few rows of float scratch
 * (a ring of the rows the vertical part needs), each loop over a row with
 * `omp simd` so that it vectorises at -O2 too; the borders are replicated by
 * padding the rows, so the inner loops have no clamping. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE__
#include <xmmintrin.h>
#endif

#include "recon/recon_internal.h"

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* Copies src[0..n) to dst[pad .. pad+n) and replicates its end values into
 * the pad cells on either side. */
static void pad_row(float *dst, const float *src, int n, int pad)
{
    memcpy(dst + pad, src, (size_t)n * sizeof *dst);
    for (int i = 0; i < pad; i++) {
        dst[i] = src[0];
        dst[pad + n + i] = src[n - 1];
    }
}

/* The normalised 7-tap kernel, sigma 1.4; k[3] is the centre. */
static void gaussian7_kernel(float k[7])
{
    const double sigma = 1.4;
    double e[7], sum = 0;
    for (int i = 0; i < 7; i++)
        sum += e[i] = exp(-(i - 3) * (i - 3) / (2 * sigma * sigma));
    for (int i = 0; i < 7; i++)
        k[i] = (float)(e[i] / sum);
}

RECON_VECTOR_CLONES void recon_gaussian7(float *img, float *tmp, int w, int h)
{
    if (w <= 0 || h <= 0)
        return;
    float k[7];
    gaussian7_kernel(k);
    const float k0 = k[0], k1 = k[1], k2 = k[2], k3 = k[3];
    /* tmp: R = min(7, h) horizontally filtered rows (row r in slot r % R),
     * then one padded input row. A slot is overwritten only after the last
     * output row that needs it, and each input row is read before its own
     * output row is written, so the result can go back into img. */
    const int R = h < 7 ? h : 7;
    float *ring = tmp, *padded = tmp + (size_t)R * w;
    int done = 0; /* rows [0, done) are filtered horizontally */
    for (int y = 0; y < h; y++) {
        for (; done < h && done <= y + 3; done++) {
            pad_row(padded, img + (size_t)done * w, w, 3);
            float *restrict o = ring + (size_t)(done % R) * w;
            const float *restrict p = padded;
#pragma omp simd
            for (int x = 0; x < w; x++)
                o[x] = k0 * (p[x] + p[x + 6]) + k1 * (p[x + 1] + p[x + 5]) + k2 * (p[x + 2] + p[x + 4]) +
                       k3 * p[x + 3];
        }
        const float *r[7];
        for (int i = 0; i < 7; i++)
            r[i] = ring + (size_t)(clampi(y + i - 3, 0, h - 1) % R) * w;
        const float *restrict r0 = r[0], *restrict r1 = r[1], *restrict r2 = r[2], *restrict r3 = r[3];
        const float *restrict r4 = r[4], *restrict r5 = r[5], *restrict r6 = r[6];
        float *restrict o = img + (size_t)y * w;
#pragma omp simd
        for (int x = 0; x < w; x++)
            o[x] = k0 * (r0[x] + r6[x]) + k1 * (r1[x] + r5[x]) + k2 * (r2[x] + r4[x]) + k3 * r3[x];
    }
}

float recon_shi_tomasi_at(const float *img, int w, int h, int x, int y)
{
#define AT(x, y) img[(size_t)clampi(y, 0, h - 1) * w + clampi(x, 0, w - 1)]
    double a = 0, b = 0, c = 0;
    for (int v = y - 1; v <= y + 1; v++)
        for (int u = x - 1; u <= x + 1; u++) {
            /* 3x3 Sobel */
            double gx = (AT(u + 1, v - 1) + 2 * AT(u + 1, v) + AT(u + 1, v + 1)) -
                        (AT(u - 1, v - 1) + 2 * AT(u - 1, v) + AT(u - 1, v + 1));
            double gy = (AT(u - 1, v + 1) + 2 * AT(u, v + 1) + AT(u + 1, v + 1)) -
                        (AT(u - 1, v - 1) + 2 * AT(u, v - 1) + AT(u + 1, v - 1));
            a += gx * gx;
            b += gx * gy;
            c += gy * gy;
        }
#undef AT
    return (float)(0.5 * (a + c) - sqrt(0.25 * (a - c) * (a - c) + b * b));
}

/* Row v (-1 <= v <= h) of the 3-wide horizontal sums of gx², gx·gy and gy²
 * into sxx, sxy, syy [0, w). The Sobel gradients are those of the image
 * extended by replication, at u = -1 .. w: gx = s(u+1) - s(u-1) and
 * gy = d(u-1) + 2 d(u) + d(u+1), with s and d the vertical [1 2 1] sum and
 * [-1 0 1] difference of the columns. scratch: 5 (w + 4) floats. */
RECON_VECTOR_CLONES static void structure_row(const float *img, int w, int h, int v, float *scratch, float *restrict sxx,
                          float *restrict sxy, float *restrict syy)
{
    const int W = w + 4; /* columns -2 .. w+1 */
    float *restrict s = scratch, *restrict d = s + W, *restrict xx = d + W, *restrict xy = xx + W,
                    *restrict yy = xy + W;
    const float *restrict up = img + (size_t)clampi(v - 1, 0, h - 1) * w;
    const float *restrict mid = img + (size_t)clampi(v, 0, h - 1) * w;
    const float *restrict dn = img + (size_t)clampi(v + 1, 0, h - 1) * w;
#pragma omp simd
    for (int x = 0; x < w; x++) {
        s[x + 2] = up[x] + 2 * mid[x] + dn[x];
        d[x + 2] = dn[x] - up[x];
    }
    s[0] = s[1] = s[2];
    d[0] = d[1] = d[2];
    s[w + 2] = s[w + 3] = s[w + 1];
    d[w + 2] = d[w + 3] = d[w + 1];
    /* Products at u = -1 .. w, i.e. index u + 1 in xx, xy, yy. */
#pragma omp simd
    for (int i = 0; i < w + 2; i++) {
        float gx = s[i + 2] - s[i], gy = d[i] + 2 * d[i + 1] + d[i + 2];
        xx[i] = gx * gx;
        xy[i] = gx * gy;
        yy[i] = gy * gy;
    }
#pragma omp simd
    for (int x = 0; x < w; x++) {
        sxx[x] = xx[x] + xx[x + 1] + xx[x + 2];
        sxy[x] = xy[x] + xy[x + 1] + xy[x + 2];
        syy[x] = yy[x] + yy[x + 1] + yy[x + 2];
    }
}

/* v[i] = sqrt(v[i]) for v >= 0. The packed square root where there is one:
 * sqrtf may set errno, which keeps compilers from vectorising it. */
RECON_VECTOR_CLONES static void sqrt_row(float *v, int n)
{
    int i = 0;
#ifdef __SSE__
    for (; i + 4 <= n; i += 4)
        _mm_storeu_ps(v + i, _mm_sqrt_ps(_mm_loadu_ps(v + i)));
#endif
    for (; i < n; i++)
        v[i] = sqrtf(v[i]);
}

RECON_VECTOR_CLONES int recon_shi_tomasi(const float *img, int w, int h, float *response)
{
    /* Ring of three rows of horizontal sums (gradient rows v-1, v, v+1 for
     * output row v), each row xx | xy | yy, then structure_row's scratch,
     * which also holds the half traces of an output row. */
    if (w <= 0 || h <= 0)
        return 0;
    float *buf = malloc(((size_t)9 * w + 5 * ((size_t)w + 4)) * sizeof *buf);
    if (!buf)
        return -1;
    float *scratch = buf + (size_t)9 * w, *restrict half = scratch;
#define RING(v) (buf + (size_t)(((v) + 3) % 3) * 3 * w)
    for (int v = -1; v <= 0; v++)
        structure_row(img, w, h, v, scratch, RING(v), RING(v) + w, RING(v) + 2 * w);
    for (int y = 0; y < h; y++) {
        float *nx = RING(y + 1);
        structure_row(img, w, h, y + 1, scratch, nx, nx + w, nx + 2 * w);
        const float *restrict p = RING(y - 1), *restrict c = RING(y), *restrict q = RING(y + 1);
        float *restrict o = response + (size_t)y * w;
#pragma omp simd
        for (int x = 0; x < w; x++) {
            float a = p[x] + c[x] + q[x];
            float b = p[x + w] + c[x + w] + q[x + w];
            float cc = p[x + 2 * w] + c[x + 2 * w] + q[x + 2 * w];
            float hd = 0.5f * (a - cc);
            half[x] = 0.5f * (a + cc);
            o[x] = hd * hd + b * b;
        }
        sqrt_row(o, w);
#pragma omp simd
        for (int x = 0; x < w; x++)
            o[x] = half[x] - o[x];
    }
#undef RING
    free(buf);
    return 0;
}
