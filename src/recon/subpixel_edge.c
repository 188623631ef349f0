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

/* The object's length in the window when its k-th pixel from the inner end,
 * j, is the object's colour at the edge: j and the pixels inside it are
 * covered, the ones outside it are fractions of |p_j - bg| (n the window's
 * last index; *contrast = |p_j - bg|). */
static double covered_to(const recon_signal *s, int n, int in, int inner, int j, const double *bg, double *contrast)
{
    const float *pj = px(s, inner - j * in);
    double d[3], n2 = 0, sum = j + 1;
    for (int c = 0; c < s->channels; c++) {
        d[c] = pj[c] - bg[c];
        n2 += d[c] * d[c];
    }
    for (int k = j + 1; k <= n; k++) {
        const float *p = px(s, inner - k * in);
        double t = 0;
        for (int c = 0; c < s->channels; c++)
            t += (p[c] - bg[c]) * d[c];
        sum += t / n2;
    }
    *contrast = sqrt(n2);
    return sum;
}

/* Object length inside [a0, a1] measured from its inner end, and the contrast
 * |fg - bg| at that end. A glossy glaze at grazing angles reflects its
 * surroundings, i.e. the backdrop (Fresnel): its colour drifts toward the
 * backdrop's over the last pixels before the outline, faster and faster, so
 * the nearest pure pixel lags behind the colour under the edge and the
 * object's fraction of each window pixel comes out short (0.3-0.5 px inward
 * on synth-dev's melon vase). When glaze is set and the three pixels inside
 * trend toward bg, the glaze's colour at the window's k-th pixel from its
 * inner end is extrapolated along that trend, m = min(k + 1, 2) steps, and
 * along its acceleration when that too points toward bg and is no larger
 * than the step (a second-order step, m (m + 1) / 2 times the change of the
 * step; JPEG noise makes larger ones), by at most half the contrast.
 * A window pixel p farther from bg than the pixel inside, fg as seen (by
 * more than the noise delta), with fg nearer to bg than to p (|fg - bg| <
 * |fg - p|, i.e. |p - bg|^2 > 2 (p - bg).(fg - bg)), says fg is not the
 * colour that p mixes with the backdrop (a dark limb with a band painted
 * just inside it as light as the backdrop, or lighter): the farthest such p
 * is the object's colour under the edge, and the length is counted from it
 * (covered_to). A highlight beside a dark glaze is not such a case (both
 * are far from the backdrop), nor is fg's extrapolation toward bg: p is
 * compared with the pixel, not with the guess. */
static int ramp(const recon_signal *s, int a0, int a1, int side, int glaze, double delta, double *len,
                double *contrast)
{
    const int w = s->width, ch = s->channels;
    if (a0 < 2 || a1 > w - 3 || a1 < a0)
        return 0;
    const int in = side > 0 ? -1 : 1, inner = side > 0 ? a0 : a1; /* toward the object; the window's inner end */
    const int third = inner + 3 * in >= 0 && inner + 3 * in < w ? inner + 3 * in : inner + 2 * in;
    const float *pfg = px(s, inner + in), *pfg2 = px(s, inner + 2 * in), *pfg3 = px(s, third);
    const float *pbg = px(s, side > 0 ? a1 + 1 : a0 - 1);
    double bg[3], step[3], acc[3], dd = 0, along = 0, acc_along = 0, s2 = 0, a2 = 0;
    for (int c = 0; c < ch; c++) {
        bg[c] = pbg[c];
        step[c] = pfg[c] - pfg2[c];
        acc[c] = step[c] - (pfg2[c] - pfg3[c]);
        along += step[c] * (bg[c] - pfg[c]);
        acc_along += acc[c] * (bg[c] - pfg[c]);
        dd += (bg[c] - pfg[c]) * (bg[c] - pfg[c]);
        s2 += step[c] * step[c];
        a2 += acc[c] * acc[c];
    }
    const int trend = glaze && along > 0, accelerates = trend && acc_along > 0 && a2 <= s2;
    double sum = 0, far = 0;
    int j = -1; /* the window pixel that is the object's colour, when fg is not */
    *contrast = 0;
    for (int k = 0; k <= a1 - a0; k++) {
        const float *p = px(s, inner - k * in);
        double m = fmin(k + 1, 2), q = accelerates ? 0.5 * m * (m + 1) : 0, x[3], x2 = 0;
        for (int c = 0; c < ch; c++) {
            x[c] = trend ? m * step[c] + q * acc[c] : 0;
            x2 += x[c] * x[c];
        }
        double lim = x2 > 0.25 * dd ? sqrt(0.25 * dd / x2) : 1, n2 = 0, t = 0, q2 = 0, t0 = 0;
        for (int c = 0; c < ch; c++) {
            double d = pfg[c] + lim * x[c] - bg[c];
            n2 += d * d;
            t += (p[c] - bg[c]) * d;
            q2 += (p[c] - bg[c]) * (p[c] - bg[c]);
            t0 += (p[c] - bg[c]) * (pfg[c] - bg[c]);
        }
        if (k == 0)
            *contrast = sqrt(n2);
        if (n2 < 1e-8)
            return 0;
        sum += t / n2;
        if (sqrt(q2) > far && sqrt(q2) > sqrt(dd) + delta && q2 > 2 * t0) {
            far = sqrt(q2);
            j = k;
        }
    }
    if (j >= 0)
        sum = covered_to(s, a1 - a0, in, inner, j, bg, contrast);
    *len = sum;
    return 1;
}

static recon_edge edge_at(const recon_signal *s, int i0, int side, double slope, double delta, int glaze)
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
    int p = far - side, stop = i0 - side * (span + 3);
    while (p != stop && recon_signal_distance(s, p, far) <= delta)
        p -= side;
    if (p == stop)
        return out;
    int a0 = side > 0 ? p - span : p, a1 = side > 0 ? p : p + span;
    double len, contrast;
    if (!ramp(s, a0, a1, side, glaze, delta, &len, &contrast))
        return out;
    double e = side > 0 ? a0 + len : a1 + 1 - len;
    /* Pass 2: only the pixels the edge can cross, so fg and bg come from the
     * pixels nearest to it. */
    a0 = (int)floor(e - half - 0.25);
    a1 = (int)floor(e + half + 0.25);
    if (!ramp(s, a0, a1, side, glaze, delta, &len, &contrast))
        return out;
    out.x = side > 0 ? a0 + len : a1 + 1 - len;
    out.contrast = contrast;
    out.ok = isfinite(out.x) && fabs(out.x - (i0 + 0.5 + 0.5 * side)) < span + 12;
    return out;
}

recon_edge recon_subpixel_edge(const recon_signal *s, int i0, int side, double slope, double delta)
{
    return edge_at(s, i0, side, slope, delta, 1);
}

recon_edge recon_subpixel_edge_flat(const recon_signal *s, int i0, int side, double slope, double delta)
{
    return edge_at(s, i0, side, slope, delta, 0);
}
