/* Linear RGB triples and the sRGB transfer function. Header-only.
 * Renderer colours are linear Rec.709/sRGB primaries; images on disk are sRGB-encoded. */
#ifndef CELADON_COLOR_H
#define CELADON_COLOR_H

#include <math.h>

typedef struct { double r, g, b; } rgb;

static inline rgb rgb_make(double r, double g, double b) { return (rgb){r, g, b}; }
static inline rgb rgb_gray(double v) { return (rgb){v, v, v}; }
static inline rgb rgb_add(rgb a, rgb b) { return (rgb){a.r + b.r, a.g + b.g, a.b + b.b}; }
static inline rgb rgb_sub(rgb a, rgb b) { return (rgb){a.r - b.r, a.g - b.g, a.b - b.b}; }
static inline rgb rgb_mul(rgb a, rgb b) { return (rgb){a.r * b.r, a.g * b.g, a.b * b.b}; }
static inline rgb rgb_scale(rgb a, double s) { return (rgb){a.r * s, a.g * s, a.b * s}; }
static inline rgb rgb_lerp(rgb a, rgb b, double t) { return rgb_add(a, rgb_scale(rgb_sub(b, a), t)); }
static inline double rgb_mean(rgb a) { return (a.r + a.g + a.b) / 3.0; }
static inline double rgb_max(rgb a) { return fmax(a.r, fmax(a.g, a.b)); }
static inline int rgb_is_black(rgb a) { return a.r == 0.0 && a.g == 0.0 && a.b == 0.0; }
/* Rec.709 / sRGB luminance of linear RGB. */
static inline double rgb_luminance(rgb a) { return 0.212671 * a.r + 0.715160 * a.g + 0.072169 * a.b; }

/* IEC 61966-2-1 transfer function, one channel. */
static inline double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}
static inline double linear_to_srgb(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
static inline rgb rgb_srgb_to_linear(rgb a)
{
    return (rgb){srgb_to_linear(a.r), srgb_to_linear(a.g), srgb_to_linear(a.b)};
}

#endif
