/* JPEG-like 8x8 DCT quantisation: see synth_jpeg.h. */
#include "synth_jpeg.h"

#include <math.h>

/* The JPEG standard's example luminance quantisation table (Annex K). */
static const int LUMA_Q[64] = {16, 11, 10, 16, 24,  40,  51,  61,  12, 12, 14, 19, 26,  58,  60,  55,
                               14, 13, 16, 24, 40,  57,  69,  56,  14, 17, 22, 29, 51,  87,  80,  62,
                               18, 22, 37, 56, 68,  109, 103, 77,  24, 35, 55, 64, 81,  104, 113, 92,
                               49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};

/* cos((2x + 1) u π / 16) scaled by the orthonormal DCT-II's c(u) / 2. */
static double basis[8][8];

static void init_basis(void)
{
    for (int u = 0; u < 8; u++)
        for (int x = 0; x < 8; x++)
            basis[u][x] = (u == 0 ? sqrt(0.125) : 0.5) * cos((2 * x + 1) * u * M_PI / 16);
}

/* out = op(a) op(b), op transposing its matrix when the flag is set. */
static void product(const double a[8][8], int ta, const double b[8][8], int tb, double out[8][8])
{
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++) {
            double s = 0;
            for (int k = 0; k < 8; k++)
                s += (ta ? a[k][i] : a[i][k]) * (tb ? b[j][k] : b[k][j]);
            out[i][j] = s;
        }
}

/* One 8x8 block in place: forward DCT (B X Bᵀ), quantise with steps q,
 * inverse (Bᵀ C B). */
static void quantise_block(double blk[8][8], const double q[64])
{
    double tmp[8][8], coef[8][8];
    product(blk, 0, basis, 1, tmp);
    product(basis, 0, tmp, 0, coef);
    for (int k = 0; k < 64; k++)
        coef[k / 8][k % 8] = q[k] * round(coef[k / 8][k % 8] / q[k]);
    product(coef, 0, basis, 0, tmp);
    product(basis, 1, tmp, 0, blk);
}

void synth_jpeg_quantise(image_t *img, int quality)
{
    if (basis[0][0] == 0)
        init_basis();
    quality = quality < 1 ? 1 : quality > 100 ? 100 : quality;
    double scale = quality < 50 ? 5000.0 / quality : 200.0 - 2 * quality, q[64];
    for (int k = 0; k < 64; k++)
        q[k] = fmax(1, floor((LUMA_Q[k] * scale + 50) / 100));
    int W = img->width, H = img->height, C = img->channels;
    double blk[8][8];
    for (int c = 0; c < C; c++)
        for (int by = 0; by < H; by += 8)
            for (int bx = 0; bx < W; bx += 8) {
                for (int y = 0; y < 8; y++)
                    for (int x = 0; x < 8; x++) {
                        int i = bx + x < W ? bx + x : W - 1, j = by + y < H ? by + y : H - 1;
                        blk[y][x] = 255.0 * img->data[((size_t)j * W + i) * C + c] - 128;
                    }
                quantise_block(blk, q);
                for (int y = 0; y < 8 && by + y < H; y++)
                    for (int x = 0; x < 8 && bx + x < W; x++)
                        img->data[((size_t)(by + y) * W + bx + x) * C + c] =
                            (float)fmin(1, fmax(0, (blk[y][x] + 128) / 255.0));
            }
}
