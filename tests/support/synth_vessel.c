/* Synthetic vessel photographs: see synth_vessel.h. */
#include "synth_vessel.h"

#include "synth_body.h"
#include "synth_raster.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The vessel as a level-camera body (synth_body.h). */
static synth_body body_of(const synth_params *p)
{
    return (synth_body){(synth_profile)p->shape, p->height_px, 1.0, p->base_center, p->tilt_deg, 0.0};
}

synth_params synth_defaults(synth_shape shape, int width, int height)
{
    synth_params p;
    memset(&p, 0, sizeof p);
    p.shape = shape;
    p.width = width;
    p.height = height;
    p.height_px = fmin(0.7 * height, 0.75 * width / (2 * synth_profile_max_radius((synth_profile)shape)));
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
    synth_body b = body_of(p);
    return synth_body_radius(&b, h);
}

synth_truth synth_truth_of(const synth_params *p)
{
    synth_body b = body_of(p);
    synth_truth t;
    t.axis_origin = p->base_center;
    t.axis_direction = synth_body_axis(&b);
    synth_body_corners(&b, t.corners);
    t.height_px = p->height_px;
    t.tilt_deg = p->tilt_deg;
    return t;
}

int synth_silhouette_x(const synth_params *p, double y, double *x_left, double *x_right)
{
    synth_body b = body_of(p);
    return synth_body_outline_x(&b, y, x_left, x_right);
}

static int body_span(const void *body, double y, double *x_left, double *x_right)
{
    return synth_body_outline_x(body, y, x_left, x_right);
}

/* Meridian stripes of 45° centred on multiples of 45°, so the silhouette
 * (phi = ±90°) lies mid-stripe, as on a decorated vessel whose pattern does
 * not change within a pixel or two of its outline; ten height bands. */
static float pattern_colour_mix(const synth_body *b, vec2 q)
{
    double h, phi;
    synth_body_surface(b, q, &h, &phi);
    int stripe = (int)floor(phi / (3.14159265358979323846 / 4) + 0.5);
    int band = (int)floor(h / (b->height_px / 10));
    return (float)((stripe + band) & 1);
}

int synth_draw(const synth_params *p, image_t *img)
{
    memset(img, 0, sizeof *img);
    if (p->width < 1 || p->height < 1 || p->height_px <= 0 || (double)p->width * p->height > 1e8)
        return -1;
    int ch = p->rgba ? 4 : 3, W = p->width, Hi = p->height;
    synth_body b = body_of(p);
    float *cov = calloc((size_t)W * Hi, sizeof *cov);
    *img = image_alloc(W, Hi, ch);
    int sub = p->subrows > 0 ? p->subrows : 16;
    if (!cov || !img->data || synth_cover_spans(cov, W, Hi, 0, Hi - 1, -INFINITY, INFINITY, sub, body_span, &b)) {
        free(cov);
        image_free(img);
        return -1;
    }
    img->has_alpha = p->rgba;
    for (int j = 0; j < Hi; j++)
        for (int i = 0; i < W; i++) {
            float c = cov[(size_t)j * W + i];
            float *px = img->data + ((size_t)j * W + i) * ch;
            float m = p->textured && c > 0 ? pattern_colour_mix(&b, v2(i + 0.5, j + 0.5)) : 0.0f;
            for (int q = 0; q < 3; q++) {
                float f = p->fg[q] + m * (p->fg2[q] - p->fg[q]);
                px[q] = p->rgba ? (c > 0 ? f : p->bg[q]) : c * f + (1 - c) * p->bg[q];
            }
            if (p->rgba)
                px[3] = c;
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
