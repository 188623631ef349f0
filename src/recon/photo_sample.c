/* Bilinear samples of a photo (recon/recon.h). */
#include "recon/recon.h"

#include <math.h>
#include <stddef.h>

void recon_sample_rgb(const image_t *img, vec2 p, float out[3])
{
    double fx = p.x - 0.5, fy = p.y - 0.5;
    fx = fmin(fmax(fx, 0.0), img->width - 1.0);
    fy = fmin(fmax(fy, 0.0), img->height - 1.0);
    int x0 = (int)fx, y0 = (int)fy;
    int x1 = x0 + 1 < img->width ? x0 + 1 : x0, y1 = y0 + 1 < img->height ? y0 + 1 : y0;
    float tx = (float)(fx - x0), ty = (float)(fy - y0);
    int C = img->channels;
    const float *p00 = img->data + ((size_t)y0 * img->width + x0) * C, *p10 = img->data + ((size_t)y0 * img->width + x1) * C;
    const float *p01 = img->data + ((size_t)y1 * img->width + x0) * C, *p11 = img->data + ((size_t)y1 * img->width + x1) * C;
    for (int k = 0; k < 3; k++) {
        int c = C >= 3 ? k : 0;
        float top = p00[c] + tx * (p10[c] - p00[c]), bottom = p01[c] + tx * (p11[c] - p01[c]);
        out[k] = top + ty * (bottom - top);
    }
}
