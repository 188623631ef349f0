#include "celadon/film.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/color.h"
#include "celadon/image.h"

static char *dup_name(const char *prefix, const char *suffix)
{
    size_t n = strlen(prefix) + strlen(suffix) + 2;
    char *s = malloc(n);
    if (!s)
        abort();
    snprintf(s, n, "%s%s%s", prefix, *prefix ? "." : "", suffix);
    return s;
}

int film_init(film_t *f, int width, int height, const film_aov *aovs, int naovs, char *err, size_t errlen)
{
    memset(f, 0, sizeof *f);
    if (width <= 0 || height <= 0 || (double)width * height > 1e9) {
        snprintf(err, errlen, "film size %dx%d is out of range", width, height);
        return -1;
    }
    int n = 3;
    for (int a = 0; a < naovs; a++) {
        if (aovs[a].channels != 1 && aovs[a].channels != 3) {
            snprintf(err, errlen, "AOV '%s' has %d channels (1 or 3 supported)", aovs[a].name, aovs[a].channels);
            return -1;
        }
        n += aovs[a].channels;
    }
    f->width = width;
    f->height = height;
    f->nchannels = n;
    f->names = calloc((size_t)n, sizeof(char *));
    f->sum = calloc((size_t)width * height * n, sizeof(double));
    f->weight = calloc((size_t)width * height, sizeof(double));
    if (!f->names || !f->sum || !f->weight)
        abort();
    static const char *const rgb_names[3] = {"R", "G", "B"};
    int k = 0;
    for (int c = 0; c < 3; c++)
        f->names[k++] = dup_name("", rgb_names[c]);
    for (int a = 0; a < naovs; a++)
        for (int c = 0; c < aovs[a].channels; c++) {
            const char *suffix = aovs[a].suffixes ? aovs[a].suffixes[c] : aovs[a].channels == 1 ? "Y" : rgb_names[c];
            f->names[k++] = dup_name(aovs[a].name, suffix);
        }
    return 0;
}

void film_free(film_t *f)
{
    for (int c = 0; c < f->nchannels && f->names; c++)
        free(f->names[c]);
    free(f->names);
    free(f->sum);
    free(f->weight);
    memset(f, 0, sizeof *f);
}

void film_add(film_t *f, int x, int y, const double *values, double weight)
{
    size_t p = (size_t)y * f->width + x;
    double *s = f->sum + p * f->nchannels;
    for (int c = 0; c < f->nchannels; c++)
        s[c] += weight * values[c];
    f->weight[p] += weight;
}

void film_merge(film_t *dst, const film_t *src)
{
    size_t npix = (size_t)dst->width * dst->height;
    for (size_t i = 0; i < npix * dst->nchannels; i++)
        dst->sum[i] += src->sum[i];
    for (size_t p = 0; p < npix; p++)
        dst->weight[p] += src->weight[p];
}

void film_develop(const film_t *f, float *out)
{
    size_t npix = (size_t)f->width * f->height;
    for (size_t p = 0; p < npix; p++) {
        double w = f->weight[p];
        for (int c = 0; c < f->nchannels; c++)
            out[p * f->nchannels + c] = w > 0 ? (float)(f->sum[p * f->nchannels + c] / w) : 0.0f;
    }
}

uint8_t film_srgb8(double v)
{
    if (!(v > 0)) /* also NaN */
        return 0;
    if (v >= 1)
        return 255;
    return (uint8_t)lrint(linear_to_srgb(v) * 255.0);
}

void film_develop_srgb8(const film_t *f, uint8_t *out)
{
    size_t npix = (size_t)f->width * f->height;
    for (size_t p = 0; p < npix; p++) {
        double w = f->weight[p];
        for (int c = 0; c < 3; c++)
            out[p * 3 + c] = film_srgb8(w > 0 ? (float)(f->sum[p * f->nchannels + c] / w) : 0.0);
    }
}

static int has_ext(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    return dot && !strchr(dot, '/') && strcasecmp(dot + 1, ext) == 0;
}

int film_write(const film_t *f, const char *path, char *err, size_t errlen)
{
    int exr = has_ext(path, "exr");
    int ldr = has_ext(path, "png") || has_ext(path, "jpg") || has_ext(path, "jpeg");
    if (!exr && !ldr) {
        snprintf(err, errlen, "%s: unsupported output format (use .exr, .png or .jpg)", path);
        return -1;
    }
    size_t npix = (size_t)f->width * f->height;
    int rc;
    if (exr) {
        float *px = malloc(sizeof(float) * npix * f->nchannels);
        if (!px)
            abort();
        film_develop(f, px);
        rc = exr_write_float(path, f->width, f->height, f->nchannels, (const char *const *)f->names, px, err, errlen);
        free(px);
    } else {
        uint8_t *rgb8 = malloc(npix * 3);
        if (!rgb8)
            abort();
        film_develop_srgb8(f, rgb8);
        char why[512];
        rc = image_write_u8(path, f->width, f->height, 3, rgb8, why, sizeof why);
        if (rc != 0)
            snprintf(err, errlen, "%s: cannot write: %s", path, why);
        free(rgb8);
    }
    return rc;
}
