/* Sub-pixel silhouette position on one pixel row from the anti-aliased ramp.
 *
 * Under box-filter anti-aliasing a pixel's value is v = bg + a (fg - bg), a the
 * fraction of its area covered by the object. Over a window of pixels [a0, a1]
 * that the outline crosses, sum a_i is the area of the object inside the
 * window's row strip; for a straight edge that equals the object's length on
 * the row's centre line (the strip is a trapezoid). So the edge on the right
 * is a0 + sum a_i, on the left a1 + 1 - sum a_i, exact up to curvature. fg and
 * bg are the pixels just inside and just outside the window: the nearest pure
 * pixels, which follows shading, texture and backdrop gradients. */
#include <math.h>

#include "recon/recon_internal.h"

/* Object length inside [a0, a1] measured from its inner end, and the contrast.
 * A glossy glaze at grazing angles reflects its surroundings, i.e. the
 * backdrop: its level drifts toward the backdrop's over the last pixels
 * before the outline, so the nearest pure pixel lags behind the level under
 * the edge. When the two pixels inside trend toward bg, fg is extrapolated one
 * pixel along that trend (by at most half the contrast). */
static int ramp(const float *row, int w, int a0, int a1, int side, int glaze, double *len, double *contrast)
{
    if (a0 < 2 || a1 > w - 3 || a1 < a0)
        return 0;
    double fg = side > 0 ? row[a0 - 1] : row[a1 + 1], bg = side > 0 ? row[a1 + 1] : row[a0 - 1];
    double fg2 = side > 0 ? row[a0 - 2] : row[a1 + 2], ext = 2 * fg - fg2;
    if (glaze && (ext - fg) * (bg - fg) > 0 && fabs(ext - fg) < 0.5 * fabs(bg - fg))
        fg = ext;
    *contrast = fabs(fg - bg);
    if (*contrast < 1e-4)
        return 0;
    double s = 0;
    for (int i = a0; i <= a1; i++)
        s += (row[i] - bg) / (fg - bg);
    *len = s;
    return 1;
}

static recon_edge edge_at(const float *gray, int w, int h, int j, int i0, int side, double slope, double delta,
                          int glaze)
{
    recon_edge out = {NAN, 0, 0};
    if (j < 0 || j >= h || i0 < 0 || i0 >= w)
        return out;
    const float *row = gray + (size_t)j * w;
    double half = 0.5 * fabs(slope);
    int span = (int)ceil(fabs(slope));
    /* Pass 1: from the background well outside the mask, inward to
     * the first pixel that differs from it by more than delta: the outermost
     * pixel the object touches (the mask may miss a light rim or decoration). */
    int far = i0 + side * (span + 12);
    far = far < 1 ? 1 : (far > w - 2 ? w - 2 : far);
    if ((far - i0) * side < span + 2)
        return out;
    double bgv = row[far];
    int p = far - side, stop = i0 - side * (span + 3);
    while (p != stop && fabs(row[p] - bgv) <= delta)
        p -= side;
    if (p == stop)
        return out;
    int a0 = side > 0 ? p - span : p, a1 = side > 0 ? p : p + span;
    double len, contrast;
    if (!ramp(row, w, a0, a1, side, glaze, &len, &contrast))
        return out;
    double e = side > 0 ? a0 + len : a1 + 1 - len;
    /* Pass 2: only the pixels the edge can cross, so fg and bg come from the
     * pixels nearest to it. */
    a0 = (int)floor(e - half - 0.25);
    a1 = (int)floor(e + half + 0.25);
    if (!ramp(row, w, a0, a1, side, glaze, &len, &contrast))
        return out;
    out.x = side > 0 ? a0 + len : a1 + 1 - len;
    out.contrast = contrast;
    out.ok = isfinite(out.x) && fabs(out.x - (i0 + 0.5 + 0.5 * side)) < span + 12;
    return out;
}

recon_edge recon_subpixel_edge(const float *gray, int w, int h, int j, int i0, int side, double slope, double delta)
{
    return edge_at(gray, w, h, j, i0, side, slope, delta, 1);
}

recon_edge recon_subpixel_edge_flat(const float *gray, int w, int h, int j, int i0, int side, double slope,
                                    double delta)
{
    return edge_at(gray, w, h, j, i0, side, slope, delta, 0);
}
