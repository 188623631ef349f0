#include "celadon/film.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/color.h"
#include "celadon/image.h"

/* "prefix.suffix", or whichever of the two is not empty. */
static char *dup_name(const char *prefix, const char *suffix)
{
    size_t n = strlen(prefix) + strlen(suffix) + 2;
    char *s = malloc(n);
    if (!s)
        abort();
    snprintf(s, n, "%s%s%s", prefix, *prefix && *suffix ? "." : "", suffix);
    return s;
}

static const char *const rgb_names[3] = {"R", "G", "B"};

/* In the order of film_pixel_format. */
static const char *const format_names[] = {"rgb", "rgba", "luminance", "luminance_alpha", "xyz", "xyza"};

const char *film_format_name(film_pixel_format f) { return format_names[f]; }

int film_format_parse(const char *name, film_pixel_format *f)
{
    for (int i = 0; i < (int)(sizeof format_names / sizeof format_names[0]); i++)
        if (strcmp(name, format_names[i]) == 0) {
            *f = (film_pixel_format)i;
            return 0;
        }
    return -1;
}

int film_init_format(film_t *f, int width, int height, film_pixel_format format, const film_aov *aovs, int naovs,
                     char *err, size_t errlen)
{
    memset(f, 0, sizeof *f);
    if (width <= 0 || height <= 0 || width > FILM_MAX_SIDE || height > FILM_MAX_SIDE || (double)width * height > FILM_MAX_PIXELS) {
        snprintf(err, errlen, "film size %dx%d is out of range", width, height);
        return -1;
    }
    int alpha = film_format_has_alpha(format), n = 3 + alpha;
    for (int a = 0; a < naovs; a++) {
        int ok = aovs[a].suffixes ? aovs[a].channels >= 1 && aovs[a].channels <= 4
                                  : aovs[a].channels == 1 || aovs[a].channels == 3;
        if (!ok) {
            snprintf(err, errlen, "AOV '%s' has %d channels (1 or 3 supported)", aovs[a].name, aovs[a].channels);
            return -1;
        }
        n += aovs[a].channels;
    }
    f->width = width;
    f->height = height;
    f->nchannels = n;
    f->format = format;
    f->names = calloc((size_t)n, sizeof(char *));
    f->sum = calloc((size_t)width * height * n, sizeof(double));
    f->weight = calloc((size_t)width * height, sizeof(double));
    if (!f->names || !f->sum || !f->weight)
        abort();
    int k = 0;
    for (int c = 0; c < 3; c++)
        f->names[k++] = dup_name("", rgb_names[c]);
    if (alpha)
        f->names[k++] = dup_name("", "A");
    for (int a = 0; a < naovs; a++)
        for (int c = 0; c < aovs[a].channels; c++) {
            const char *suffix = aovs[a].suffixes ? aovs[a].suffixes[c] : aovs[a].channels == 1 ? "Y" : rgb_names[c];
            f->names[k++] = dup_name(aovs[a].name, suffix);
        }
    return 0;
}

int film_init(film_t *f, int width, int height, const film_aov *aovs, int naovs, char *err, size_t errlen)
{
    return film_init_format(f, width, height, FILM_RGB, aovs, naovs, err, errlen);
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

/* R, G, B turned into the pixel format's Y or X, Y, Z: Rec. 709 primaries,
 * D65 (Mitsuba's srgb_to_xyz). */
float *film_develop_exr(const film_t *f, int *nch, const char **names)
{
    static const double to_xyz[3][3] = {
        {0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}};
    static const char *const xyz_names[3] = {"X", "Y", "Z"};
    size_t npix = (size_t)f->width * f->height;
    float *dev = malloc(sizeof(float) * npix * f->nchannels);
    if (!dev)
        abort();
    film_develop(f, dev);
    int lum = f->format == FILM_LUMINANCE || f->format == FILM_LUMINANCE_ALPHA;
    int xyz = f->format == FILM_XYZ || f->format == FILM_XYZA;
    if (!lum && !xyz) {
        *nch = f->nchannels;
        for (int c = 0; c < *nch; c++)
            names[c] = f->names[c];
        return dev;
    }
    int base = lum ? 1 : 3;
    *nch = f->nchannels - 3 + base;
    for (int c = 0; c < *nch; c++)
        names[c] = c >= base ? f->names[c + 3 - base] : lum ? "Y" : xyz_names[c];
    float *px = malloc(sizeof(float) * npix * *nch);
    if (!px)
        abort();
    for (size_t p = 0; p < npix; p++) {
        const float *in = dev + p * f->nchannels;
        float *out = px + p * *nch;
        double v[3];
        for (int i = 0; i < 3; i++)
            v[i] = to_xyz[i][0] * in[0] + to_xyz[i][1] * in[1] + to_xyz[i][2] * in[2];
        for (int c = 0; c < base; c++)
            out[c] = (float)v[lum ? 1 : c];
        for (int c = base; c < *nch; c++)
            out[c] = in[c + 3 - base];
    }
    free(dev);
    return px;
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
        const char **names = malloc(sizeof *names * (size_t)f->nchannels);
        if (!names)
            abort();
        int nch;
        float *px = film_develop_exr(f, &nch, names);
        rc = exr_write_float(path, f->width, f->height, nch, names, px, &f->meta, err, errlen);
        free(px);
        free(names);
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
