/* render --denoise: the film's colour through the denoiser (denoise.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/denoise.h"

/* The index of the channel called name among n names, or -1. */
static int channel_index(const char *const *names, int n, const char *name)
{
    for (int c = 0; c < n; c++)
        if (!strcmp(names[c], name))
            return c;
    return -1;
}

int denoise_film(film_t *f, char *err, size_t errlen)
{
    if (!(f->extras & FILM_EXTRA_VARIANCE)) {
        snprintf(err, errlen, "denoising needs the variance of the pixels (--aov variance)");
        return -1;
    }
    /* R, G, B and the AOVs are the film's own channels (whatever its pixel
     * format), the variance is what its EXR holds. */
    int src[DENOISE_HALF_CHANNELS];
    for (int k = 0; k < DENOISE_HALF_CHANNELS; k++)
        if (k != DENOISE_CHANNELS - 1 &&
            (src[k] = channel_index((const char *const *)f->names, f->nchannels, denoise_channel_names[k])) < 0) {
            snprintf(err, errlen, "denoising needs the channel %s (--aov denoising,half,specular)", denoise_channel_names[k]);
            return -1;
        }
    size_t npix = (size_t)f->width * f->height;
    const char **names = malloc(sizeof *names * (size_t)(f->nchannels + FILM_EXR_EXTRA_MAX));
    float *dev = malloc(sizeof *dev * npix * f->nchannels), *in = malloc(sizeof *in * npix * DENOISE_HALF_CHANNELS),
          *out = malloc(sizeof *out * npix * 3);
    int nexr, rc = -1;
    float *exr = names && dev && in && out ? film_develop_exr(f, &nexr, names) : NULL;
    if (!exr) {
        snprintf(err, errlen, "%dx%d pixels: out of memory for the denoiser", f->width, f->height);
        goto done;
    }
    int var = channel_index(names, nexr, "variance.X");
    film_develop(f, dev);
    for (size_t p = 0; p < npix; p++)
        for (int k = 0; k < DENOISE_HALF_CHANNELS; k++)
            in[p * DENOISE_HALF_CHANNELS + k] =
                k == DENOISE_CHANNELS - 1 ? exr[p * nexr + var] : dev[p * f->nchannels + src[k]];
    if (denoise_image_halves(f->width, f->height, in, out) != 0) {
        snprintf(err, errlen, "%dx%d pixels: out of memory for the denoiser", f->width, f->height);
        goto done;
    }
    for (size_t p = 0; p < npix; p++)
        for (int c = 0; c < 3; c++)
            f->sum[p * f->nchannels + c] = f->weight[p] > 0 ? out[p * 3 + c] * f->weight[p] : 0.0;
    snprintf(f->meta.denoised, sizeof f->meta.denoised, "%s", DENOISE_DESCRIPTION);
    rc = 0;
done:
    free(exr);
    free(names);
    free(dev);
    free(in);
    free(out);
    return rc;
}
