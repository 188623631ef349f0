/* Mitsuba 3's per-pixel z-test of a render against a reference
 * (include/celadon/ztest.h). Arithmetic in float32 where Mitsuba's is, so
 * p-values round as they do there. */
#include "celadon/ztest.h"

#include <math.h>

void ztest_rgb_to_xyz(float rgb[3])
{
    static const float m[3][3] = {{0.412453f, 0.357580f, 0.180423f},
                                  {0.212671f, 0.715160f, 0.072169f},
                                  {0.019334f, 0.119193f, 0.950227f}};
    float r = rgb[0], g = rgb[1], b = rgb[2];
    for (int i = 0; i < 3; i++)
        rgb[i] = m[i][0] * r + m[i][1] * g + m[i][2] * b;
}

/* p = 2 (1 - Phi(z)) with Phi(z) = (1 - erf(-z / sqrt 2)) / 2, each step
 * rounded to float as in Mitsuba's numpy/Dr.Jit float32 arrays. */
static float p_value(float z)
{
    float cdf = (1.0f - erff(-z / sqrtf(2.0f))) * 0.5f;
    return 2.0f * (1.0f - cdf);
}

ztest_result ztest_run(const float *mean, const float *ref, const float *var, int pixel_count, int spp,
                       float *p_out)
{
    ztest_result r = {.pixel_count = pixel_count, .spp = spp, .min_p = INFINITY};
    r.alpha = 1.0 - pow(1.0 - 0.01, 1.0 / pixel_count);
    for (int i = 0; i < pixel_count; i++) {
        float m[3], f[3], v[3];
        for (int c = 0; c < 3; c++)
            m[c] = mean[3 * i + c], f[c] = ref[3 * i + c], v[c] = var[3 * i + c];
        ztest_rgb_to_xyz(m);
        ztest_rgb_to_xyz(f);
        ztest_rgb_to_xyz(v);
        bool pixel_ok = true;
        for (int c = 0; c < 3; c++) {
            float z = fabsf(m[c] - f[c]) * sqrtf((float)spp / fmaxf(v[c], 1e-4f));
            float p = p_value(z);
            if (p_out)
                p_out[3 * i + c] = p;
            if (p < r.min_p)
                r.min_p = p;
            if (p > r.alpha)
                r.passed_channels++;
            else
                pixel_ok = false;
        }
        r.failed_pixels += !pixel_ok;
    }
    r.pass = (double)r.passed_channels / 3.0 >= 0.9975 * pixel_count;
    return r;
}
