/* Sub-pixel silhouette position on one pixel row from the anti-aliased ramp.
 *
 * Under box-filter anti-aliasing a pixel's colour is c = bg + a (fg - bg), a
 * the fraction of its area covered by the object. Projecting c onto the
 * direction fg - bg gives a = (c - bg).(fg - bg) / |fg - bg|^2 whatever the
 * colours (a glaze as light as the backdrop but of another hue still has a
 * ramp). Over a window of pixels [a0, a1] that the outline crosses, sum a_i
 * is the area of the object inside the window's row strip; for a straight
 * edge that equals the object's length on the row's centre line (the strip is
 * a trapezoid). So the edge on the right is a0 + sum a_i, on the left
 * a1 + 1 - sum a_i, exact up to curvature. fg and bg are the pixels just
 * inside and just outside the window: the nearest pure pixels, which follows
 * shading, texture and backdrop gradients. */
#include <math.h>

#include "recon/recon_internal.h"

static const float *px(const recon_signal *s, int i) { return s->row + (size_t)i * s->channels; }

static double dist(const recon_signal *s, const float *a, const float *b)
{
    double d2 = 0;
    for (int c = 0; c < s->channels; c++)
        d2 += ((double)a[c] - b[c]) * ((double)a[c] - b[c]);
    return sqrt(d2);
}

/* Object length inside [a0, a1] measured from its inner end, and the contrast
 * |fg - bg|. A glossy glaze at grazing angles reflects its surroundings, i.e.
 * the backdrop: its colour drifts toward the backdrop's over the last pixels
 * before the outline, so the nearest pure pixel lags behind the colour under
 * the edge. When the two pixels inside trend toward bg, fg is extrapolated one
 * pixel along that trend (by at most half the contrast). */
static int ramp(const recon_signal *s, int a0, int a1, int side, double *len, double *contrast)
{
    const int w = s->width, ch = s->channels;
    if (a0 < 2 || a1 > w - 3 || a1 < a0)
        return 0;
    const float *pfg = px(s, side > 0 ? a0 - 1 : a1 + 1), *pbg = px(s, side > 0 ? a1 + 1 : a0 - 1);
    const float *pfg2 = px(s, side > 0 ? a0 - 2 : a1 + 2);
    double fg[3], bg[3], d[3], dd = 0, ext_along = 0, ext_len2 = 0;
    for (int c = 0; c < ch; c++) {
        fg[c] = pfg[c];
        bg[c] = pbg[c];
        double e = pfg[c] - pfg2[c]; /* the extrapolation step fg - fg2 */
        ext_along += e * (bg[c] - fg[c]);
        ext_len2 += e * e;
        dd += (bg[c] - fg[c]) * (bg[c] - fg[c]);
    }
    /* extrapolate when the step points toward bg and is under half the contrast */
    if (ext_along > 0 && ext_len2 < 0.25 * dd)
        for (int c = 0; c < ch; c++)
            fg[c] += pfg[c] - pfg2[c];
    double n2 = 0;
    for (int c = 0; c < ch; c++) {
        d[c] = fg[c] - bg[c];
        n2 += d[c] * d[c];
    }
    *contrast = sqrt(n2);
    if (*contrast < 1e-4)
        return 0;
    double sum = 0;
    for (int i = a0; i <= a1; i++) {
        const float *p = px(s, i);
        double t = 0;
        for (int c = 0; c < ch; c++)
            t += (p[c] - bg[c]) * d[c];
        sum += t / n2;
    }
    *len = sum;
    return 1;
}

recon_edge recon_subpixel_edge(const recon_signal *s, int i0, int side, double slope, double delta)
{
    recon_edge out = {NAN, 0, 0};
    const int w = s->width;
    if (i0 < 0 || i0 >= w)
        return out;
    double half = 0.5 * fabs(slope);
    int span = (int)ceil(fabs(slope));
    /* Pass 1: from the background well outside the mask, inward to the first
     * pixel that differs from it by more than delta: the outermost pixel the
     * object touches (the mask may miss a light rim or decoration). */
    int far = i0 + side * (span + 12);
    far = far < 1 ? 1 : (far > w - 2 ? w - 2 : far);
    if ((far - i0) * side < span + 2)
        return out;
    const float *bgv = px(s, far);
    int p = far - side, stop = i0 - side * (span + 3);
    while (p != stop && dist(s, px(s, p), bgv) <= delta)
        p -= side;
    if (p == stop)
        return out;
    int a0 = side > 0 ? p - span : p, a1 = side > 0 ? p : p + span;
    double len, contrast;
    if (!ramp(s, a0, a1, side, &len, &contrast))
        return out;
    double e = side > 0 ? a0 + len : a1 + 1 - len;
    /* Pass 2: only the pixels the edge can cross, so fg and bg come from the
     * pixels nearest to it. */
    a0 = (int)floor(e - half - 0.25);
    a1 = (int)floor(e + half + 0.25);
    if (!ramp(s, a0, a1, side, &len, &contrast))
        return out;
    out.x = side > 0 ? a0 + len : a1 + 1 - len;
    out.contrast = contrast;
    out.ok = isfinite(out.x) && fabs(out.x - (i0 + 0.5 + 0.5 * side)) < span + 12;
    return out;
}
