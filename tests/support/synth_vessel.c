/* Synthetic vessel photographs: see synth_vessel.h. */
#include "synth_vessel.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Profile radius in units of H at t = h/H. */
static double unit_radius(synth_shape shape, double t)
{
    switch (shape) {
    case SYNTH_VASE:
        return 0.17 + 0.09 * sin(2 * PI * (0.85 * t + 0.08));
    case SYNTH_BOWL:
        return 0.50 + 0.70 * t - 0.25 * t * t;
    case SYNTH_BOTTLE:
        return 0.08 + 0.17 * 0.5 * (1 - tanh((t - 0.6) / 0.07));
    case SYNTH_JAR:
    default:
        return 0.32 + 0.04 * sin(PI * t) - 0.02 * t;
    }
}

static double max_unit_radius(synth_shape shape)
{
    double m = 0;
    for (int k = 0; k <= 400; k++)
        m = fmax(m, unit_radius(shape, k / 400.0));
    return m;
}

synth_params synth_defaults(synth_shape shape, int width, int height)
{
    synth_params p;
    memset(&p, 0, sizeof p);
    p.shape = shape;
    p.width = width;
    p.height = height;
    p.height_px = fmin(0.7 * height, 0.75 * width / (2 * max_unit_radius(shape)));
    p.base_center = v2(0.5 * width, 0.5 * height + 0.5 * p.height_px);
    const float fg[3] = {0.25f, 0.42f, 0.33f}, fg2[3] = {0.68f, 0.70f, 0.60f}, bg[3] = {0.94f, 0.94f, 0.93f};
    memcpy(p.fg, fg, sizeof fg);
    memcpy(p.fg2, fg2, sizeof fg2);
    memcpy(p.bg, bg, sizeof bg);
    p.subrows = 16;
    return p;
}

double synth_radius(const synth_params *p, double h)
{
    return p->height_px * unit_radius(p->shape, h / p->height_px);
}

static vec2 axis_dir(const synth_params *p)
{
    double t = p->tilt_deg * PI / 180;
    return v2(sin(t), -cos(t));
}

synth_truth synth_truth_of(const synth_params *p)
{
    synth_truth t;
    vec2 d = axis_dir(p), n = v2(-d.y, d.x);
    double H = p->height_px, rb = synth_radius(p, 0), rr = synth_radius(p, H);
    vec2 top = v2_add(p->base_center, v2_scale(d, H));
    t.axis_origin = p->base_center;
    t.axis_direction = d;
    t.corners[CORNER_RIM_LEFT] = v2_sub(top, v2_scale(n, rr));
    t.corners[CORNER_RIM_RIGHT] = v2_add(top, v2_scale(n, rr));
    t.corners[CORNER_BASE_LEFT] = v2_sub(p->base_center, v2_scale(n, rb));
    t.corners[CORNER_BASE_RIGHT] = v2_add(p->base_center, v2_scale(n, rb));
    t.height_px = H;
    t.tilt_deg = p->tilt_deg;
    return t;
}

/* Signed inside-ness of an image point: positive inside the vessel, zero on its
 * outline, continuous (the minimum of the three constraints). */
static double inside(const synth_params *p, vec2 d, vec2 q)
{
    vec2 n = v2(-d.y, d.x), rel = v2_sub(q, p->base_center);
    double s = v2_dot(rel, n), h = v2_dot(rel, d), H = p->height_px;
    double hc = fmin(fmax(h, 0), H);
    return fmin(synth_radius(p, hc) - fabs(s), fmin(h, H - h));
}

/* Bisection between an inside x (a) and an outside x (b) on line y. */
static double polish(const synth_params *p, vec2 d, double y, double a, double b)
{
    for (int k = 0; k < 60 && fabs(b - a) > 1e-10; k++) {
        double m = 0.5 * (a + b);
        if (inside(p, d, v2(m, y)) > 0)
            a = m;
        else
            b = m;
    }
    return 0.5 * (a + b);
}

int synth_silhouette_x(const synth_params *p, double y, double *x_left, double *x_right)
{
    vec2 d = axis_dir(p);
    /* The vessel lies within rmax of the axis segment: scan that x-range. */
    double rmax = p->height_px * max_unit_radius(p->shape) + 1;
    vec2 top = v2_add(p->base_center, v2_scale(d, p->height_px));
    double x0 = floor(fmin(p->base_center.x, top.x) - rmax - 2), x1 = ceil(fmax(p->base_center.x, top.x) + rmax + 2);
    const double step = 0.5;
    double first = NAN, last = NAN;
    for (double x = x0; x <= x1; x += step)
        if (inside(p, d, v2(x, y)) > 0) {
            if (isnan(first))
                first = x;
            last = x;
        }
    if (isnan(first))
        return 0;
    *x_left = polish(p, d, y, first, first - step);
    *x_right = polish(p, d, y, last, last + step);
    return 1;
}

static float pattern_colour_mix(const synth_params *p, vec2 d, vec2 q)
{
    vec2 n = v2(-d.y, d.x), rel = v2_sub(q, p->base_center);
    double H = p->height_px;
    double h = fmin(fmax(v2_dot(rel, d), 0), H);
    double r = synth_radius(p, h), s = v2_dot(rel, n);
    double phi = asin(fmax(-1.0, fmin(1.0, s / r)));
    /* Meridian stripes of 45° centred on multiples of 45°, so the silhouette
     * (phi = ±90°) lies mid-stripe, as on a decorated vessel whose pattern
     * does not change within a pixel or two of its outline; ten height bands. */
    int stripe = (int)floor(phi / (PI / 4) + 0.5);
    int band = (int)floor(h / (H / 10));
    return (float)((stripe + band) & 1);
}

int synth_draw(const synth_params *p, image_t *img)
{
    memset(img, 0, sizeof *img);
    if (p->width < 1 || p->height < 1 || p->height_px <= 0 || (double)p->width * p->height > 1e8)
        return -1;
    int ch = p->rgba ? 4 : 3, W = p->width, Hi = p->height;
    int sub = p->subrows > 0 ? p->subrows : 16;
    *img = image_alloc(W, Hi, ch);
    if (!img->data)
        return -1;
    img->has_alpha = p->rgba;
    float *cov = calloc((size_t)W, sizeof *cov);
    if (!cov) {
        image_free(img);
        return -1;
    }
    vec2 d = axis_dir(p);
    for (int j = 0; j < Hi; j++) {
        memset(cov, 0, (size_t)W * sizeof *cov);
        for (int k = 0; k < sub; k++) {
            double xl, xr, y = j + (k + 0.5) / sub;
            if (!synth_silhouette_x(p, y, &xl, &xr))
                continue;
            int i0 = (int)fmax(0, floor(xl)), i1 = (int)fmin(W - 1, floor(xr));
            for (int i = i0; i <= i1; i++)
                cov[i] += (float)((fmin(xr, i + 1.0) - fmax(xl, (double)i)) / sub);
        }
        for (int i = 0; i < W; i++) {
            float c = fminf(1.0f, fmaxf(0.0f, cov[i]));
            float *px = img->data + ((size_t)j * W + i) * ch;
            float m = p->textured && c > 0 ? pattern_colour_mix(p, d, v2(i + 0.5, j + 0.5)) : 0.0f;
            for (int q = 0; q < 3; q++) {
                float f = p->fg[q] + m * (p->fg2[q] - p->fg[q]);
                px[q] = p->rgba ? (c > 0 ? f : p->bg[q]) : c * f + (1 - c) * p->bg[q];
            }
            if (p->rgba)
                px[3] = c;
        }
    }
    free(cov);
    return 0;
}

int synth_write(const char *path, const image_t *img, int bits, char *err, size_t errlen)
{
    size_t n = (size_t)img->width * img->height * img->channels;
    double maxv = bits == 16 ? 65535.0 : 255.0;
    void *buf = malloc(n * (bits == 16 ? 2 : 1));
    if (!buf)
        return -1;
    for (size_t i = 0; i < n; i++) {
        double v = floor(fmin(1.0, fmax(0.0, img->data[i])) * maxv + 0.5);
        if (bits == 16)
            ((uint16_t *)buf)[i] = (uint16_t)v;
        else
            ((uint8_t *)buf)[i] = (uint8_t)v;
    }
    int rc = bits == 16 ? image_write_u16(path, img->width, img->height, img->channels, buf, err, errlen)
                        : image_write_u8(path, img->width, img->height, img->channels, buf, err, errlen);
    free(buf);
    return rc;
}
