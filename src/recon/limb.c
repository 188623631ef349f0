/* The limb: per row, the outermost pixel on each side that departs from the
 * backdrop beyond it (recon_internal.h; algorithms-recon.md section 5). */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

/* How far the backdrop beside a clean edge strays from the backdrop further
 * out: JPEG ringing, the anti-aliasing a pixel beyond the mask still
 * carries. Per row of the clean side, the largest distance of the pixels
 * 2-8 px outside its outermost object pixel from the one 16 px outside; the
 * 90th percentile of that over the rows (a row where the mask stops short of
 * the edge is not the backdrop's: a few may). */
static double ringing(const image_t *img, const float *gray, int alpha, const int *ext, int side, float *buf)
{
    enum { NEAR0 = 3, NEAR1 = 9, FAR = 16 };
    const int w = img->width, h = img->height;
    double *v = malloc((size_t)h * sizeof *v);
    if (!v)
        return NAN;
    size_t n = 0;
    for (int j = 0; j < h; j++) {
        int far = ext[j] + side * FAR;
        if (ext[j] < 0 || far < 0 || far >= w)
            continue;
        recon_signal sig = recon_signal_row(img, gray, alpha, j, buf);
        double m = 0;
        for (int k = NEAR0; k <= NEAR1; k++)
            m = fmax(m, recon_signal_distance(&sig, ext[j] + side * k, far));
        v[n++] = m;
    }
    double q = n > 0 ? gsl_stats_select(v, 1, n, (size_t)(0.9 * (double)(n - 1))) : 0;
    free(v);
    return q;
}

/* Where a row first departs from its backdrop: from the backdrop pixel bg
 * inward (step +1 from the left, -1 from the right) to the first pixel
 * differing from it by more than t, at the latest stop. *edge: the outline's
 * sub-pixel position there, the pixel's covered fraction being its
 * departure over the largest of it and the next two pixels' (1 for a limb
 * one pixel wide, the anti-aliased ramp's fraction at a step edge). Returns
 * 1 when the departure is sharp, as an outline is (within a pixel, blurred a
 * little): the pixels 4-5 further in depart at most 1.5 times as much as the
 * first three; a highlight's soft inner boundary, still rising there, is no
 * outline. */
static int departure(const recon_signal *s, int bg, int stop, int step, double t, double *edge)
{
    int x = bg + step;
    while (x != stop && recon_signal_distance(s, x, bg) <= t)
        x += step;
    double d = recon_signal_distance(s, x, bg), peak = d, later = 0;
    for (int k = 1; k <= 5; k++) {
        int i = x + k * step;
        if (i < 0 || i >= s->width)
            break;
        if (k <= 2)
            peak = fmax(peak, recon_signal_distance(s, i, bg));
        else if (k >= 4)
            later = fmax(later, recon_signal_distance(s, i, bg));
    }
    double covered = peak > 0 ? d / peak : 1;
    *edge = step > 0 ? x + 1 - covered : x + covered;
    return later <= 1.5 * peak;
}

int recon_limb_points(const image_t *img, const float *gray, int alpha, const int *ext, vec2 origin, vec2 dir,
                      int washed, double delta, float *buf, vec2 *left, int *nl, vec2 *right, int *nr)
{
    enum { MARGIN = 12 };
    const int w = img->width, h = img->height;
    *nl = *nr = 0;
    const int clean = washed > 0 ? 1 : 0;
    double ring = ringing(img, gray, alpha, ext + (size_t)clean * h, clean ? 1 : -1, buf);
    if (isnan(ring))
        return -1;
    /* Twice what the backdrop shows beside a clean edge, at least the noise:
     * the same threshold on both sides, so that what remains of the edge's
     * blur biases both alike. */
    const double t = fmax(delta, 2 * ring);
    for (int j = 0; j < h; j++) {
        const int el = ext[j], er = ext[h + j];
        if (el < 0 || er < 0)
            continue;
        /* the axis crosses row j at x = origin.x + (j + 0.5 - origin.y) dx/dy */
        double xc = origin.x + (j + 0.5 - origin.y) * dir.x / dir.y;
        /* Search from beyond the farther of the side's own extent and the
         * other side's mirror image (a washed-out side's mask lies inside). */
        const int margin = MARGIN + (int)(0.1 * (er - el));
        int lo = (int)floor(fmin(el, 2 * xc - er - 1)) - margin, hi = (int)ceil(fmax(er, 2 * xc - el + 1)) + margin;
        if (lo < 0 || hi >= w)
            continue;
        recon_signal sig = recon_signal_row(img, gray, alpha, j, buf);
        double xl, xr;
        /* the washed-out side's soft departures are not its outline */
        if (departure(&sig, lo, el, 1, t, &xl) || washed < 0)
            left[(*nl)++] = v2(xl, j + 0.5);
        if (departure(&sig, hi, er, -1, t, &xr) || washed > 0)
            right[(*nr)++] = v2(xr, j + 0.5);
    }
    return 0;
}
