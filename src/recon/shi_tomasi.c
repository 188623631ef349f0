/* 7x7 Gaussian smoothing and the Shi–Tomasi corner response (J. Shi,
 * C. Tomasi, "Good features to track", CVPR 1994): the smaller eigenvalue of
 * the gradient structure tensor. */
#include <math.h>

#include "recon/recon_internal.h"

static inline int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

void recon_gaussian7(float *img, float *tmp, int w, int h)
{
    const double sigma = 1.4;
    float k[7];
    double sum = 0;
    for (int i = 0; i < 7; i++)
        sum += k[i] = (float)exp(-(i - 3) * (i - 3) / (2 * sigma * sigma));
    for (int i = 0; i < 7; i++)
        k[i] = (float)(k[i] / sum);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float s = 0;
            for (int i = 0; i < 7; i++)
                s += k[i] * img[(size_t)y * w + clampi(x + i - 3, 0, w - 1)];
            tmp[(size_t)y * w + x] = s;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float s = 0;
            for (int i = 0; i < 7; i++)
                s += k[i] * tmp[(size_t)clampi(y + i - 3, 0, h - 1) * w + x];
            img[(size_t)y * w + x] = s;
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

void recon_shi_tomasi(const float *img, int w, int h, float *response)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            response[(size_t)y * w + x] = recon_shi_tomasi_at(img, w, h, x, y);
}
