/* The film written out (film.h: film_write_as): the EXR through OpenEXR's
 * core API (exr_write.c), every other format through OpenImageIO, each
 * with the metadata (film_info.h). */
#include "celadon/film.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "celadon/image.h"
#include "celadon/version.h"
#include "render/film_info.h"

typedef enum { OUT_EXR, OUT_HDR, OUT_TIFF, OUT_PNG, OUT_JPEG, OUT_NONE } out_kind;

static out_kind kind_of(const char *path)
{
    static const struct {
        const char *ext;
        out_kind kind;
    } exts[] = {{"exr", OUT_EXR}, {"hdr", OUT_HDR}, {"tif", OUT_TIFF}, {"tiff", OUT_TIFF},
                {"png", OUT_PNG}, {"jpg", OUT_JPEG}, {"jpeg", OUT_JPEG}};
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/'))
        return OUT_NONE;
    for (size_t i = 0; i < sizeof exts / sizeof exts[0]; i++)
        if (!strcasecmp(dot + 1, exts[i].ext))
            return exts[i].kind;
    return OUT_NONE;
}

/* The bits per channel of kind at the depth asked for (0: its default), or
 * 0 when it cannot be written so. */
static int bits_of(out_kind k, int depth)
{
    switch (k) {
    case OUT_EXR:
    case OUT_HDR: return depth == 0 || depth == 32 ? 32 : 0;
    case OUT_TIFF: return depth == 0 ? 32 : depth == 8 || depth == 16 || depth == 32 ? depth : 0;
    case OUT_PNG: return depth == 0 ? 8 : depth == 8 || depth == 16 ? depth : 0;
    case OUT_JPEG: return depth == 0 || depth == 8 ? 8 : 0;
    default: return 0;
    }
}

int film_output_check(const char *path, int depth, char *err, size_t errlen)
{
    out_kind k = kind_of(path);
    if (k == OUT_NONE)
        snprintf(err, errlen, "output '%s' must end in .exr, .hdr, .tif, .tiff, .png, .jpg or .jpeg", path);
    else if (!bits_of(k, depth))
        snprintf(err, errlen, "'%s' cannot hold %d bits per channel (PNG 8 or 16, TIFF 8, 16 or 32, JPEG 8, "
                              "EXR and HDR 32)", path, depth);
    else
        return 0;
    return -1;
}

/* R, G, B turned into the pixel format's Y or X, Y, Z: Rec. 709 primaries,
 * D65 (Mitsuba's srgb_to_xyz). */
float *film_develop_exr(const film_t *f, int *nch, const char **names)
{
    static const double to_xyz[3][3] = {
        {0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}};
    size_t npix = (size_t)f->width * f->height;
    float *dev = malloc(sizeof(float) * npix * f->nchannels);
    if (!dev)
        abort();
    film_develop(f, dev);
    double least, most;
    film_sample_range(f, &least, &most);
    int spp = (f->extras & FILM_EXTRA_SPP) || least != most, var = (f->extras & FILM_EXTRA_VARIANCE) != 0;
    int ids = (f->extras & FILM_EXTRA_INDEX) ? 2 : 0;
    int lum = f->format == FILM_LUMINANCE || f->format == FILM_LUMINANCE_ALPHA;
    int xyz = f->format == FILM_XYZ || f->format == FILM_XYZA;
    int base = lum ? 1 : 3, film_ch = f->nchannels - 3 + base;
    *nch = film_ch + spp + var + ids;
    for (int c = film_format_colour_names(f->format, names); c < film_ch; c++)
        names[c] = f->names[c + 3 - base];
    if (spp)
        names[film_ch] = "spp.X";
    if (var)
        names[film_ch + spp] = "variance.X";
    if (ids)
        names[film_ch + spp + var] = "IndexOB.X", names[film_ch + spp + var + 1] = "IndexMA.X";
    float *px = malloc(sizeof(float) * npix * *nch);
    if (!px)
        abort();
    for (size_t p = 0; p < npix; p++) {
        const float *in = dev + p * f->nchannels;
        float *out = px + p * *nch;
        for (int c = 0; c < 3 && !lum && !xyz; c++)
            out[c] = in[c];
        if (lum || xyz) {
            double v[3];
            for (int i = 0; i < 3; i++)
                v[i] = to_xyz[i][0] * in[0] + to_xyz[i][1] * in[1] + to_xyz[i][2] * in[2];
            for (int c = 0; c < base; c++)
                out[c] = (float)v[lum ? 1 : c];
        }
        for (int c = base; c < film_ch; c++)
            out[c] = in[c + 3 - base];
        const double *s = f->samples + 3 * p;
        if (spp)
            out[film_ch] = (float)s[0];
        /* The sample variance over the count: the variance of the mean. */
        if (var)
            out[film_ch + spp] = s[0] > 1 ? (float)(fmax(s[2] - s[1] * s[1] / s[0], 0.0) / (s[0] - 1) / s[0]) : 0.0f;
        for (int i = 0; i < ids; i++)
            out[film_ch + spp + var + i] = (float)f->ids[2 * p + i];
    }
    free(dev);
    return px;
}

static int write_exr(const film_t *f, const char *path, const film_info *info, char *err, size_t errlen)
{
    const char **names = malloc(sizeof *names * (size_t)(f->nchannels + FILM_EXR_EXTRA_MAX));
    if (!names)
        abort();
    int nch;
    float *px = film_develop_exr(f, &nch, names);
    film_attr attrs[FILM_INFO_MAX + 1];
    int n = 0;
    if (info->summary[0])
        attrs[n++] = (film_attr){"comments", info->summary};
    for (int i = 0; i < info->n; i++)
        attrs[n++] = info->attr[i];
    int rc = exr_write_float_attrs(path, f->width, f->height, nch, names, px, &f->meta, attrs, n, err, errlen);
    free(px);
    free(names);
    return rc;
}

/* The RGB averages, through the exposure and view for display-referred
 * bits (8, 16), as they are for float. */
static void *develop_rgb(const film_t *f, int bits, const film_output *o)
{
    size_t npix = (size_t)f->width * f->height, size = bits == 8 ? 1 : bits == 16 ? 2 : 4;
    unsigned char *out = malloc(npix * 3 * size);
    if (!out)
        abort();
    double gain = exp2(o->exposure), top = bits == 8 ? 255.0 : 65535.0;
    for (size_t p = 0; p < npix; p++) {
        double w = f->weight[p];
        for (int c = 0; c < 3; c++) {
            double v = w > 0 ? (float)(f->sum[p * f->nchannels + c] / w) : 0.0;
            size_t i = p * 3 + c;
            if (bits == 32)
                ((float *)out)[i] = (float)v;
            else if (bits == 16)
                ((uint16_t *)out)[i] = (uint16_t)lrint(film_view_encode(o->view, gain * v) * top);
            else
                out[i] = (uint8_t)lrint(film_view_encode(o->view, gain * v) * top);
        }
    }
    return out;
}

/* The metadata as text: a PNG's text chunks; a JPEG's one comment, or a
 * TIFF's (or Radiance's) description, holds every line. */
static int text_of(const film_info *info, out_kind k, image_text *text, char *all, size_t alllen, char *date,
                   size_t datelen)
{
    time_t now = time(NULL);
    struct tm tm;
    localtime_r(&now, &tm);
    strftime(date, datelen, "%Y:%m:%d %H:%M:%S", &tm);
    int n = 0;
    text[n++] = (image_text){"Software", "celadon " CELADON_VERSION};
    text[n++] = (image_text){"DateTime", date};
    if (!info->summary[0])
        return n;
    if (k == OUT_PNG) {
        text[n++] = (image_text){"ImageDescription", info->summary};
        for (int i = 0; i < info->n; i++)
            text[n++] = (image_text){info->attr[i].name, info->attr[i].value};
        return n;
    }
    size_t len = (size_t)snprintf(all, alllen, "%s", info->summary);
    for (int i = 0; i < info->n && len < alllen; i++)
        len += (size_t)snprintf(all + len, alllen - len, "\n%s: %s", info->attr[i].name, info->attr[i].value);
    text[n++] = (image_text){"ImageDescription", all};
    return n;
}

int film_write_as(const film_t *f, const char *path, const film_output *o, char *err, size_t errlen)
{
    if (film_output_check(path, o->depth, err, errlen) != 0)
        return -1;
    out_kind k = kind_of(path);
    film_info *info = malloc(sizeof *info);
    if (!info)
        abort();
    film_info_collect(f, info);
    int rc;
    if (k == OUT_EXR) {
        rc = write_exr(f, path, info, err, errlen);
    } else {
        int bits = bits_of(k, o->depth);
        void *px = develop_rgb(f, bits, o);
        image_text text[FILM_INFO_MAX + 3];
        char all[8192], date[32], why[512];
        int ntext = text_of(info, k, text, all, sizeof all, date, sizeof date);
        rc = image_write_with_text(path, f->width, f->height, 3,
                                   bits == 8 ? IMAGE_U8 : bits == 16 ? IMAGE_U16 : IMAGE_F32, px, text, ntext, why,
                                   sizeof why);
        if (rc != 0)
            snprintf(err, errlen, "%s: cannot write: %s", path, why);
        free(px);
    }
    free(info);
    return rc;
}

int film_write(const film_t *f, const char *path, char *err, size_t errlen)
{
    film_output o = {0.0, FILM_VIEW_STANDARD, 0};
    return film_write_as(f, path, &o, err, errlen);
}
