/* The limb: per row, the outermost pixel on each side that departs from the
 * backdrop beyond it. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>

#include "recon/recon_internal.h"

/* Colour distance between pixels a and b of a row. */
static double dist(const recon_signal *s, int a, int b)
{
    double d2 = 0;
    for (int c = 0; c < s->channels; c++) {
        double t = (double)s->row[(size_t)a * s->channels + c] - s->row[(size_t)b * s->channels + c];
        d2 += t * t;
    }
    return sqrt(d2);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

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
            m = fmax(m, dist(&sig, ext[j] + side * k, far));
        v[n++] = m;
    }
    double q = 0;
    if (n > 0) {
        qsort(v, n, sizeof *v, cmp_double);
        q = v[(size_t)(0.9 * (double)(n - 1))];
    }
    free(v);
    return q;
}

/* The fraction of pixel x that the object covers, x being the outermost
 * pixel departing from the backdrop pixel bg and step pointing inward: its
 * departure over the largest of it and the next two pixels' (1 for a limb
 * one pixel wide; the anti-aliased ramp's fraction at a step edge). */
static double coverage(const recon_signal *s, int x, int step, int bg)
{
    double d = dist(s, x, bg), peak = d;
    for (int k = 1; k <= 2; k++)
        if (x + k * step >= 0 && x + k * step < s->width)
            peak = fmax(peak, dist(s, x + k * step, bg));
    return peak > 0 ? d / peak : 1;
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
        int x = lo + 1;
        while (x < el && dist(&sig, x, lo) <= t)
            x++;
        left[(*nl)++] = v2(x + 1 - coverage(&sig, x, 1, lo), j + 0.5);
        x = hi - 1;
        while (x > er && dist(&sig, x, hi) <= t)
            x--;
        right[(*nr)++] = v2(x + coverage(&sig, x, -1, hi), j + 0.5);
    }
    return 0;
}
