/* celadon denoise: a render's EXR denoised into another (denoise.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/denoise.h"
#include "render/exr_read.h"

/* "has no channel A, B (render with --aov ...)" for the channels the
 * denoiser needs that e lacks, or "" when it has them all. */
static void missing_channels(const exr_in *e, char *out, size_t outlen)
{
    size_t n = 0;
    out[0] = '\0';
    for (int k = 0; k < DENOISE_HALF_CHANNELS && n < outlen; k++)
        if (!exr_in_has_channel(e, denoise_channel_names[k]))
            n += (size_t)snprintf(out + n, outlen - n, "%s%s", n ? ", " : "has no channel ", denoise_channel_names[k]);
    if (n && n < outlen)
        snprintf(out + n, outlen - n, " (denoising needs R, G, B and render --aov denoising,half,specular,variance)");
}

int denoise_exr(const char *in_path, const char *out_path, char *err, size_t errlen)
{
    exr_in *e = exr_in_open(in_path, err, errlen);
    if (!e)
        return -2;
    char missing[512];
    missing_channels(e, missing, sizeof missing);
    if (missing[0]) {
        snprintf(err, errlen, "%s: %s", in_path, missing);
        exr_in_close(e);
        return -2;
    }
    int w, h, nch = exr_in_channel_count(e);
    exr_in_size(e, &w, &h);
    size_t npix = (size_t)w * h;
    const char **names = malloc(sizeof *names * (size_t)nch);
    float *all = malloc(sizeof *all * npix * nch), *in = malloc(sizeof *in * npix * DENOISE_HALF_CHANNELS),
          *out = malloc(sizeof *out * npix * 3);
    int rc = -2;
    if (!names || !all || !in || !out) {
        snprintf(err, errlen, "%s: %dx%d pixels: out of memory", in_path, w, h);
        goto done;
    }
    for (int c = 0; c < nch; c++)
        names[c] = exr_in_channel_name(e, c);
    if (exr_in_read(e, nch, names, all, err, errlen) == 0 &&
        exr_in_read(e, DENOISE_HALF_CHANNELS, denoise_channel_names, in, err, errlen) == 0) {
        if (denoise_image_halves(w, h, in, out) != 0) {
            snprintf(err, errlen, "%s: %dx%d pixels: out of memory for the denoiser", in_path, w, h);
            goto done;
        }
        for (int c = 0; c < nch; c++)
            for (int k = 0; k < 3; k++)
                if (!strcmp(names[c], denoise_channel_names[k]))
                    for (size_t p = 0; p < npix; p++)
                        all[p * nch + c] = out[p * 3 + k];
        film_attr denoised = {"celadon/denoised", DENOISE_DESCRIPTION};
        rc = exr_write_float_like(out_path, w, h, nch, names, all, e, &denoised, 1, err, errlen) == 0 ? 0 : -1;
    }
done:
    exr_in_close(e);
    free(names);
    free(all);
    free(in);
    free(out);
    return rc;
}
