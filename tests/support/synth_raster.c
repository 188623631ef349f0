/* Anti-aliased coverage of synthetic shapes: see synth_raster.h. */
#include "synth_raster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int synth_cover_spans(float *cov, int width, int height, int row0, int row1, double y_top, double y_bottom,
                      int subrows, synth_span_fn span, const void *shape)
{
    float *row = malloc((size_t)width * sizeof *row);
    if (!row)
        return -1;
    for (int j = row0 < 0 ? 0 : row0; j <= row1 && j < height; j++) {
        double lo = fmax(j, y_top), hi = fmin(j + 1.0, y_bottom), strip = (hi - lo) / subrows;
        if (!(strip > 0))
            continue;
        memset(row, 0, (size_t)width * sizeof *row);
        for (int k = 0; k < subrows; k++) {
            double xl, xr, y = lo + (k + 0.5) * strip;
            if (!span(shape, y, &xl, &xr) || xr <= 0 || xl >= width)
                continue;
            int i0 = (int)fmax(0, floor(xl)), i1 = (int)fmin(width - 1, floor(xr));
            for (int i = i0; i <= i1; i++)
                row[i] += (float)((fmin(xr, i + 1.0) - fmax(xl, (double)i)) * strip);
        }
        float *dst = cov + (size_t)j * width;
        for (int i = 0; i < width; i++)
            dst[i] = fmaxf(dst[i], fminf(1.0f, row[i]));
    }
    free(row);
    return 0;
}

void synth_cover_sdf(float *cov, int width, int height, int x0, int y0, int x1, int y1, int n, double lipschitz,
                     synth_sdf_fn sdf, const void *shape)
{
    const double half_diagonal = 0.70710678118654752;
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 >= width ? width - 1 : x1, y1 = y1 >= height ? height - 1 : y1;
    for (int j = y0; j <= y1; j++)
        for (int i = x0; i <= x1; i++) {
            double f = sdf(shape, i + 0.5, j + 0.5), c;
            if (f > lipschitz * half_diagonal)
                continue;
            if (f < -lipschitz * half_diagonal)
                c = 1;
            else {
                int in = 0;
                for (int b = 0; b < n; b++)
                    for (int a = 0; a < n; a++)
                        in += sdf(shape, i + (a + 0.5) / n, j + (b + 0.5) / n) < 0;
                c = (double)in / (n * n);
            }
            float *dst = cov + (size_t)j * width + i;
            *dst = fmaxf(*dst, (float)c);
        }
}

void synth_cover_rect(float *cov, int width, int height, double x0, double y0, double x1, double y1)
{
    int i0 = (int)fmax(0, floor(x0)), i1 = (int)fmin(width - 1, ceil(x1) - 1);
    int j0 = (int)fmax(0, floor(y0)), j1 = (int)fmin(height - 1, ceil(y1) - 1);
    for (int j = j0; j <= j1; j++) {
        double cy = fmin(y1, j + 1.0) - fmax(y0, (double)j);
        for (int i = i0; i <= i1; i++) {
            double cx = fmin(x1, i + 1.0) - fmax(x0, (double)i);
            float *dst = cov + (size_t)j * width + i;
            *dst = fmaxf(*dst, (float)(cx * cy));
        }
    }
}
