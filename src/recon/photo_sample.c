/* Samples of a photo: bilinear colours, and the rows the outline is measured
 * on (recon/recon.h). */
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

recon_signal recon_signal_row(const image_t *img, const float *gray, int alpha, int j, float *buf)
{
    const int w = img->width, c = img->channels;
    if (alpha || c < 3)
        return (recon_signal){gray + (size_t)j * w, w, 1};
    const float *p = img->data + (size_t)j * w * c;
    if (!buf)
        return (recon_signal){p, w, 3};
    for (int i = 0; i < w; i++)
        for (int k = 0; k < 3; k++) {
            float v = p[(size_t)i * c + k];
            buf[3 * i + k] = v > 0 ? (v < 1 ? v : 1) : 0;
        }
    return (recon_signal){buf, w, 3};
}
