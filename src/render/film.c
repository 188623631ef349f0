#include "celadon/film.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* Channel c of an AOV as the film names it: "name.suffix", a one-channel
 * AOV's suffix Y, a three-channel one's R, G, B unless it names its own. */
static char *aov_channel_name(const film_aov *a, int c)
{
    return dup_name(a->name, a->suffixes ? a->suffixes[c] : a->channels == 1 ? "Y" : rgb_names[c]);
}

int film_format_colour_names(film_pixel_format f, const char **names)
{
    static const char *const xyz_names[3] = {"X", "Y", "Z"};
    int lum = f == FILM_LUMINANCE || f == FILM_LUMINANCE_ALPHA;
    int xyz = f == FILM_XYZ || f == FILM_XYZA, n = lum ? 1 : 3;
    for (int c = 0; c < n; c++)
        names[c] = lum ? "Y" : xyz ? xyz_names[c] : rgb_names[c];
    if (film_format_has_alpha(f))
        names[n++] = "A";
    return n;
}

/* An AOV channel written under the name of a colour channel or of another
 * AOV's channel (depth's Z on an X, Y, Z film) would make an EXR no
 * reader accepts: refused before anything is rendered. The AOVs' names
 * are f->names from `first` on, those of aovs[] in turn. */
static int aov_names_collide(const film_t *f, int first, const film_aov *aovs, char *err, size_t errlen)
{
    const char *colour[4];
    int ncolour = film_format_colour_names(f->format, colour);
    for (int k = first, a = 0, c = 0; k < f->nchannels; k++) {
        int clash = 0;
        for (int j = 0; j < ncolour; j++)
            clash |= !strcmp(f->names[k], colour[j]);
        for (int j = first; j < k; j++)
            clash |= !strcmp(f->names[k], f->names[j]);
        if (clash) {
            snprintf(err, errlen, "the channel '%s' of AOV '%s' is written twice on a %s film", f->names[k],
                     aovs[a].name, film_format_name(f->format));
            return 1;
        }
        if (++c == aovs[a].channels)
            a++, c = 0;
    }
    return 0;
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
    f->samples = calloc((size_t)width * height * 3, sizeof(double));
    f->ids = calloc((size_t)width * height * 2, sizeof(double));
    if (!f->names || !f->sum || !f->weight || !f->samples || !f->ids)
        abort();
    int k = 0;
    for (int c = 0; c < 3; c++)
        f->names[k++] = dup_name("", rgb_names[c]);
    if (alpha)
        f->names[k++] = dup_name("", "A");
    int first = k;
    for (int a = 0; a < naovs; a++)
        for (int c = 0; c < aovs[a].channels; c++)
            f->names[k++] = aov_channel_name(&aovs[a], c);
    if (aov_names_collide(f, first, aovs, err, errlen)) {
        film_free(f);
        return -1;
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
    free(f->samples);
    free(f->ids);
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
    for (size_t i = 0; i < npix * 3; i++)
        dst->samples[i] += src->samples[i];
    for (size_t i = 0; i < npix * 2; i++)
        dst->ids[i] += src->ids[i];
}

void film_sample_range(const film_t *f, double *least, double *most)
{
    size_t npix = (size_t)f->width * f->height;
    *least = npix ? f->samples[0] : 0.0, *most = *least;
    for (size_t p = 1; p < npix; p++) {
        double n = f->samples[3 * p];
        *least = n < *least ? n : *least;
        *most = n > *most ? n : *most;
    }
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

uint8_t film_srgb8(double v) { return (uint8_t)lrint(film_view_encode(FILM_VIEW_STANDARD, v) * 255.0); }

void film_develop_srgb8(const film_t *f, uint8_t *out)
{
    size_t npix = (size_t)f->width * f->height;
    for (size_t p = 0; p < npix; p++) {
        double w = f->weight[p];
        for (int c = 0; c < 3; c++)
            out[p * 3 + c] = film_srgb8(w > 0 ? (float)(f->sum[p * f->nchannels + c] / w) : 0.0);
    }
}
