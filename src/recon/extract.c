/* recon_extract: photo -> vessel mask -> contour -> axis -> sub-pixel
 * outlines -> caps -> parts -> profile polyline. See include/celadon/recon.h
 * and docs/algorithms-recon.md. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "core/core.h"
#include "recon/recon_internal.h"

/* The largest lean of a vessel's axis from the image's vertical. */
#define MAX_TILT_DEG 30.0

static recon_status fail(recon_status st, char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return st;
}

vec2 recon_profile_to_image(vec2 axis_origin, vec2 axis_direction, double r, double h, int side_sign)
{
    vec2 right = v2(-axis_direction.y, axis_direction.x);
    return v2_add(axis_origin, v2_add(v2_scale(right, side_sign * r), v2_scale(axis_direction, h)));
}

const char *recon_part_name(recon_part_kind k)
{
    static const char *names[RECON_PART_KIND_COUNT] = {"shadow", "stand", "handle", "asymmetry"};
    return k >= 0 && k < RECON_PART_KIND_COUNT ? names[k] : "unknown";
}

const char *recon_profile_source_name(recon_profile_source s)
{
    static const char *names[] = {"none", "left", "right", "bridged"};
    return s >= RECON_PROFILE_NONE && s <= RECON_PROFILE_BRIDGED ? names[s] : "unknown";
}

/* Frees the arrays and clears their pointers and counts; scalars stay. */
static void free_arrays(recon_result *res)
{
    free(res->mask);
    free(res->contour);
    free(res->silhouette[0]);
    free(res->silhouette[1]);
    free(res->polyline);
    free(res->polyline_bridge);
    res->polyline_bridge = NULL;
    res->mask = NULL;
    res->contour = res->polyline = res->silhouette[0] = res->silhouette[1] = NULL;
    res->n_contour = res->n_polyline = res->n_silhouette[0] = res->n_silhouette[1] = 0;
}

void recon_result_free(recon_result *res)
{
    free_arrays(res);
    memset(res, 0, sizeof *res);
}

/* Bits of the image borders the mask touches: 1 top, 2 bottom, 4 left, 8 right. */
static unsigned border_contact(const uint8_t *m, int w, int h)
{
    unsigned b = 0;
    for (int i = 0; i < w; i++) {
        b |= m[i] ? 1u : 0u;
        b |= m[(size_t)(h - 1) * w + i] ? 2u : 0u;
    }
    for (int j = 0; j < h; j++) {
        b |= m[(size_t)j * w] ? 4u : 0u;
        b |= m[(size_t)j * w + w - 1] ? 8u : 0u;
    }
    return b;
}

/* Quantile of v[0..n) (GSL's linear-time selection, in a copy in tmp). */
static double quantile(const double *v, int n, double q, double *tmp)
{
    if (n <= 0)
        return 0;
    memcpy(tmp, v, (size_t)n * sizeof *tmp);
    return gsl_stats_select(tmp, 1, (size_t)n, (size_t)(q * (n - 1) + 0.5));
}

/* Drops points more than 1 px (plus a third of the local slope, dx per row:
 * a near-horizontal outline is measured less precisely per row) from their
 * 7-row neighbourhood's robust line: the median of x_j - s (j - k) over the
 * window, s the slope across it. A decoration or a highlight spoiling one
 * row's ramp is dropped; a steep but smooth outline is kept. */
static int drop_outliers(vec2 *pts, double *contrast, uint8_t *gap, int n)
{
    if (n < 7)
        return n;
    double *dev = malloc((size_t)n * sizeof *dev);
    if (!dev)
        return n;
    for (int k = 0; k < n; k++) {
        int a = k < 3 ? 0 : (k + 3 >= n ? n - 7 : k - 3);
        /* the slope across the window, from ends other than the point tested
         * (a bad end row would tilt its own line toward itself) */
        int i0 = a + (k == a), i1 = a + 6 - (k == a + 6);
        double slope = (pts[i1].x - pts[i0].x) / (pts[i1].y - pts[i0].y);
        double v[7]; /* insertion-sorted: qsort's call overhead dominates for 7 */
        for (int i = 0; i < 7; i++) {
            double x = pts[a + i].x - slope * (pts[a + i].y - pts[k].y);
            int q = i;
            for (; q > 0 && v[q - 1] > x; q--)
                v[q] = v[q - 1];
            v[q] = x;
        }
        dev[k] = fabs(pts[k].x - v[3]) - fabs(slope) / 3;
    }
    int m = 0;
    for (int k = 0; k < n; k++)
        if (dev[k] <= 1.0) {
            pts[m] = pts[k];
            gap[m] = gap[k];
            contrast[m++] = contrast[k];
        }
    free(dev);
    return m;
}

/* Sub-pixel outline of one side (-1 left, +1 right) on rows j0..j1; ext[j]
 * is the body's outermost pixel of row j on that side (-1: none), outer[j]
 * the object's. Fills pts, contrast and gap (object again beyond a gap);
 * returns the count. */
static int trace_side(const image_t *img, const float *gray, int alpha, const int *ext, const int *outer, int side,
                      double delta, vec2 *pts, double *contrast, uint8_t *gap, float *buf)
{
    const int w = img->width, h = img->height;
    int n = 0;
    for (int j = 0; j < h; j++) {
        if (ext[j] < 0)
            continue;
        /* The outline's slope (dx per row) from the neighbouring rows: the
         * widest step decides the window. */
        double slope = 0;
        if (j > 0 && ext[j - 1] >= 0)
            slope = fabs((double)(ext[j - 1] - ext[j]));
        if (j + 1 < h && ext[j + 1] >= 0)
            slope = fmax(slope, fabs((double)(ext[j + 1] - ext[j])));
        /* The search counts as object what differs from the backdrop by a
         * quarter of this row's step (the pixel 3 px inside against the one
         * 12 px outside) or by delta (the noise), whichever is more: JPEG
         * ringing beside a strong edge is not the edge. */
        recon_signal sig = recon_signal_row(img, gray, alpha, j, buf);
        int in = ext[j] - 3 * side, outp = ext[j] + 12 * side;
        double d = delta;
        if (in >= 0 && in < w && outp >= 0 && outp < w)
            d = fmax(d, 0.25 * recon_signal_distance(&sig, in, outp));
        recon_edge e = recon_subpixel_edge(&sig, ext[j], side, slope, d);
        if (!e.ok)
            continue;
        gap[n] = outer[j] != ext[j];
        pts[n] = v2(e.x, j + 0.5);
        contrast[n++] = e.contrast;
    }
    return drop_outliers(pts, contrast, gap, n);
}

/* Every value of the photo is in [0, 1] (not -0, not NaN): the bits of such
 * a float, read as an unsigned integer, are at most those of 1. One compare
 * and an OR a value (no running maximum: SSE2 has no unsigned max). */
RECON_VECTOR_CLONES static int in_unit_range(const image_t *img)
{
    const float *v = img->data;
    const size_t n = (size_t)img->width * img->height * img->channels;
    uint32_t over = 0;
#pragma omp simd reduction(| : over)
    for (size_t i = 0; i < n; i++) {
        uint32_t bits;
        memcpy(&bits, v + i, sizeof bits);
        over |= bits > 0x3f800000u;
    }
    return !over;
}

/* Roughness of an outline: median |second difference| of x over its middle. */
static double roughness(const vec2 *p, int n, double *tmp, double *tmp2)
{
    int m = 0;
    for (int k = n / 10 + 1; k < n - n / 10 - 1; k++)
        tmp[m++] = fabs(p[k + 1].x - 2 * p[k].x + p[k - 1].x);
    return quantile(tmp, m, 0.5, tmp2);
}

/* ---- the vessel's mask */

/* The vessel's mask by segmentation: low-resolution min-cut, the vessel among
 * its objects, a stand or shadow cut off at the foot, the full-resolution
 * band. Sets the start axis, the excluded parts found, and the edge search's
 * noise delta. */
static recon_status segment_vessel(const image_t *img, const float *prior, recon_result *res, vec2 *origin,
                                   vec2 *dir, double *delta, char *err, size_t errlen)
{
    recon_segmentation seg;
    int src = recon_segment(img, prior, &seg);
    recon_status st = RECON_OK;
    if (src < 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    if (src > 0) {
        st = fail(RECON_ERR_NO_OBJECT, err, errlen, "no object found: nothing in the photo stands out from its backdrop");
        goto out;
    }
    recon_excluded stand;
    char why[256];
    st = recon_select_object(seg.object, seg.w, seg.h, &res->dropped_objects, &stand, why, sizeof why);
    if (st != RECON_OK) {
        fail(st, err, errlen, "%s", why);
        goto out;
    }
    if (stand.row1 > 0) {
        stand.row0 *= seg.factor;
        stand.row1 = (stand.row1 + 1) * seg.factor - 1;
        res->excluded[res->n_excluded++] = stand;
    }
    /* The axis of the vessel alone, for the support cut's symmetry test. */
    seg.have_axis = recon_mask_axis(seg.object, seg.w, seg.h, &seg.axis_x0, &seg.axis_slope) == 0;
    if (recon_cut_support(&seg, seg.object, res->excluded, RECON_MAX_EXCLUDED, &res->n_excluded) != 0 ||
        recon_colour_model_prepare(&seg.model) != 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    if (recon_mask_axis(seg.object, seg.w, seg.h, &seg.axis_x0, &seg.axis_slope) != 0) {
        st = fail(RECON_ERR_NO_OBJECT, err, errlen, "no object found: the object is too small");
        goto out;
    }
    /* The band's refinement at full resolution can open again a band that the
     * low resolution joined across. */
    if (recon_refine_mask(img, &seg, seg.object, res->mask) != 0 ||
        recon_mask_join_bands(res->mask, img->width, img->height, RECON_BAND_MAX_ROWS * seg.factor) != 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    /* The axis at full resolution: x = f x0 + slope y. */
    double f = seg.factor;
    *dir = v2_norm(v2(-seg.axis_slope, -1));
    *origin = v2(f * seg.axis_x0 + seg.axis_slope * img->height, img->height);
    /* The edge search starts where a pixel differs from the backdrop by four
     * noise sigmas of its gray (Rec.601 weights on the residual covariance). */
    static const double wg[3] = {0.299, 0.587, 0.114};
    double var = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            var += wg[i] * wg[j] * seg.model.backdrop.cov[3 * i + j];
    *delta = fmax(4 * sqrt(var), 3.0 / 255);
out:
    recon_segmentation_free(&seg);
    return st;
}

/* A surface of revolution meets every row in one interval (each imaged
 * cross-section is an ellipse around the axis, and the silhouette is their
 * union), so background between two of the object's runs of a row is not
 * the outline: a window (a hole, kept), or a washed-out part of the body.
 * Background open to the outside only from below, under object everywhere
 * (a foot's lit centre as light as the backdrop: a bay cut up into the
 * foot), is the body: filled row by row from the top, each gap between two
 * runs of the row whose every pixel lies under object (already filled
 * included). A gap under background (between a spout and the neck, between
 * two handles above the rim) opens upwards and stays. lab, stat: the
 * labelling of the background in the box (x0, y0, bw, bh) and its
 * components' flags, stat[4 c] set where component c reaches the box's
 * border (outside; the rest are the windows kept). */
static void fill_bays_from_below(uint8_t *mask, int w, int x0, int y0, int bw, int bh, const int *lab,
                                 const long *stat)
{
    for (int y = 1; y < bh; y++) {
        uint8_t *m = mask + (size_t)(y0 + y) * w + x0;
        const uint8_t *up = m - w;
        const int *l = lab + (size_t)y * bw;
        int x = 0;
        while (x < bw && !m[x])
            x++;
        while (x < bw) {
            while (x < bw && m[x])
                x++;
            int g0 = x, capped = 1;
            while (x < bw && !m[x]) {
                capped = capped && up[x] && stat[4 * l[x]];
                x++;
            }
            if (x < bw && capped)
                memset(m + g0, 1, (size_t)(x - g0));
        }
    }
}

/* Fills the holes of the vessel's mask except its windows: a hole entirely on
 * one side of the axis whose mirror image is mostly background is the loop of
 * a handle (the body continues behind it), whereas a hole inside the body (a
 * decoration as light as the backdrop) has the body around its mirror image.
 *
 * Only the object's bounding box, grown by a pixel (within the image), is
 * labelled: a background component of the whole image reaches the image's
 * border exactly when its part in the box reaches the box's border (a path
 * out of the box crosses that border; from a background pixel on it a
 * straight line outwards, outside the object's box, reaches the image's
 * border), so the holes, and every pixel of them, are the same. */
static int fill_holes_but_windows(uint8_t *mask, int w, int h, vec2 origin, vec2 dir)
{
    int box[4];
    if (!recon_mask_box(mask, w, h, box))
        return 0; /* no object: no hole */
    int x0 = box[0], y0 = box[1], x1 = box[2], y1 = box[3];
    x0 = x0 > 0 ? x0 - 1 : 0;
    y0 = y0 > 0 ? y0 - 1 : 0;
    x1 = x1 + 1 < w ? x1 + 1 : w - 1;
    y1 = y1 + 1 < h ? y1 + 1 : h - 1;
    const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
    uint8_t *inv = malloc((size_t)bw * bh);
    int *lab = malloc((size_t)bw * bh * sizeof *lab);
    long *area = NULL;
    if (!inv || !lab) {
        free(inv);
        free(lab);
        return -1;
    }
    for (int y = 0; y < bh; y++) {
        const uint8_t *m = mask + (size_t)(y0 + y) * w + x0;
        uint8_t *v = inv + (size_t)y * bw;
        for (int x = 0; x < bw; x++)
            v[x] = !m[x];
    }
    int n = recon_mask_label(inv, bw, bh, lab, &area);
    if (n < 0) {
        free(inv);
        free(lab);
        return -1;
    }
    /* per component: touches the box's border, sides seen, mirrored pixels on background */
    long *stat = calloc((size_t)(n + 1) * 4, sizeof *stat);
    if (!stat) {
        free(area);
        free(inv);
        free(lab);
        return -1;
    }
    vec2 nrm = v2(-dir.y, dir.x);
    for (int x = 0; x < bw; x++)
        stat[4 * lab[x]] = stat[4 * lab[(size_t)(bh - 1) * bw + x]] = 1;
    for (int y = 0; y < bh; y++)
        stat[4 * lab[(size_t)y * bw]] = stat[4 * lab[(size_t)y * bw + bw - 1]] = 1;
    int holes = 0;
    for (int c = 1; c <= n; c++)
        holes += !stat[4 * c];
    /* the rest only for the holes (the background around the object is
     * never filled) */
    for (int y = 0; holes && y < bh; y++)
        for (int x = 0; x < bw; x++) {
            int c = lab[(size_t)y * bw + x];
            if (!c || stat[4 * c])
                continue;
            long *s = stat + 4 * c;
            vec2 p = v2(x0 + x + 0.5, y0 + y + 0.5);
            double r = v2_dot(v2_sub(p, origin), nrm);
            s[r < 0 ? 1 : 2] = 1;
            vec2 q = v2_sub(p, v2_scale(nrm, 2 * r));
            int qx = (int)floor(q.x), qy = (int)floor(q.y);
            s[3] += qx < 0 || qy < 0 || qx >= w || qy >= h || !mask[(size_t)qy * w + qx];
        }
    for (int y = 0; holes && y < bh; y++)
        for (int x = 0; x < bw; x++) {
            int c = lab[(size_t)y * bw + x];
            if (!c || stat[4 * c])
                continue;
            int window = !(stat[4 * c + 1] && stat[4 * c + 2]) && stat[4 * c + 3] > area[c] / 2;
            if (!window)
                mask[(size_t)(y0 + y) * w + x0 + x] = 1;
        }
    fill_bays_from_below(mask, w, x0, y0, bw, bh, lab, stat);
    free(stat);
    free(area);
    free(inv);
    free(lab);
    return 0;
}

/* A surface of revolution meets every row in one interval around its axis:
 * where a row has object on both sides of the axis but not at it (a
 * highlight as light as the backdrop in the middle of a foot), the gap
 * between the two is filled. Gaps off the axis (a handle's loop) stay. */
static void fill_across_axis(uint8_t *mask, int w, int h, vec2 origin, vec2 dir)
{
    /* Only below the first row the body holds the axis in: above it, object
     * on both sides is not the body (two handles rising above the rim). */
    int j0 = h, j1 = -1;
    for (int j = 0; j < h; j++) {
        int c = (int)floor(origin.x + (j + 0.5 - origin.y) * dir.x / dir.y);
        if (j0 == h && c >= 0 && c < w && mask[(size_t)j * w + c])
            j0 = j;
        if (memchr(mask + (size_t)j * w, 1, (size_t)w))
            j1 = j;
    }
    for (int j = j0; j <= j1; j++) {
        uint8_t *m = mask + (size_t)j * w;
        int c = (int)floor(origin.x + (j + 0.5 - origin.y) * dir.x / dir.y);
        if (c < 0 || c >= w)
            continue;
        /* The axis is known to a few pixels (a fraction of a degree over the
         * height): a gap that starts within 2% of the row's width of it is
         * the one around the axis. */
        const uint8_t *a = memchr(m, 1, (size_t)w), *b = memrchr(m, 1, (size_t)w);
        int reach = (int)fmax(3, 0.02 * (b - a + 1));
        for (int k = 1; m[c] && k <= reach; k++)
            c = c - k >= 0 && !m[c - k] ? c - k : (c + k < w && !m[c + k] ? c + k : c);
        if (m[c])
            continue;
        int l = c, r = c;
        while (l >= 0 && !m[l])
            l--;
        while (r < w && !m[r])
            r++;
        if (l >= 0 && r < w)
            memset(m + l + 1, 1, (size_t)(r - l - 1));
    }
}

/* Per row, the body's outermost pixel on each side (the run of the mask that
 * contains the axis, across gaps of up to 2 px) and the object's. ext: [0,h)
 * left body, [h,2h) right body, [2h,3h) left object, [3h,4h) right object;
 * -1 where the row has none. */
static void row_extents(const uint8_t *mask, int w, int h, vec2 origin, vec2 dir, int *ext)
{
    for (int j = 0; j < h; j++) {
        const uint8_t *m = mask + (size_t)j * w, *a = memchr(m, 1, (size_t)w);
        for (int k = 0; k < 4; k++)
            ext[k * h + j] = -1;
        if (!a)
            continue;
        ext[2 * h + j] = (int)(a - m);
        ext[3 * h + j] = (int)((const uint8_t *)memrchr(m, 1, (size_t)w) - m);
        /* the axis crosses row j at x = origin.x + (j + 0.5 - origin.y) dx/dy */
        double xc = origin.x + (j + 0.5 - origin.y) * dir.x / dir.y;
        int c = (int)floor(xc);
        if (c < 0 || c >= w || !m[c])
            continue; /* the row does not cross the body at the axis */
        for (int s = 0; s < 2; s++) {
            int step = s ? 1 : -1, x = c;
            for (;;) {
                /* to the end of the run of object from x */
                if (s) {
                    const uint8_t *z = memchr(m + x + 1, 0, (size_t)(w - x - 1));
                    x = z ? (int)(z - m) - 1 : w - 1;
                } else {
                    const uint8_t *z = memrchr(m, 0, (size_t)x);
                    x = z ? (int)(z - m) + 1 : 0;
                }
                int g = 1;
                while (g <= 3 && x + g * step >= 0 && x + g * step < w && !m[x + g * step])
                    g++;
                if (g <= 3 && x + g * step >= 0 && x + g * step < w)
                    x += g * step; /* a gap of up to 2 px: still the body */
                else
                    break;
            }
            ext[s * h + j] = x;
        }
    }
}

/* ---- the profile */

int recon_outline_points(const vec2 *sil, const uint8_t *gap, int n, vec2 origin, vec2 dir, int side, double H,
                          recon_outline_point *out)
{
    vec2 nrm = v2(-dir.y, dir.x);
    int m = 0;
    for (int k = n - 1; k >= 0; k--) { /* rows run top to bottom: backwards is base to rim */
        vec2 q = v2_sub(sil[k], origin);
        double h = v2_dot(q, dir);
        if (h <= 0 || h >= H || (m > 0 && h <= out[m - 1].h))
            continue;
        out[m++] = (recon_outline_point){h, side * v2_dot(q, nrm), sil[k].y, gap[k]};
    }
    return m;
}

/* A ledge (a lip's underside, a foot's step) runs nearly horizontally
 * between two rows: the row samples are far apart there, and the B-spline,
 * held only at the rows, would round it off far from the outline. Such a
 * segment (not a bridge) gets a point every pixel along it. */
static int is_ledge(vec2 a, vec2 b) { return fabs(b.x - a.x) > 2 * fabs(b.y - a.y) && fabs(b.x - a.x) > 1.5; }

static int densify_polyline(recon_result *res)
{
    const vec2 *p = res->polyline;
    const uint8_t *br = res->polyline_bridge;
    int n = res->n_polyline, total = n;
    for (int i = 0; i + 1 < n; i++)
        if (!br[i] && is_ledge(p[i], p[i + 1]))
            total += (int)ceil(v2_len(v2_sub(p[i + 1], p[i]))) - 1;
    vec2 *q = malloc((size_t)total * sizeof *q);
    uint8_t *qb = calloc((size_t)total, 1);
    if (!q || !qb) {
        free(q);
        free(qb);
        return -1;
    }
    int m = 0;
    for (int i = 0; i < n; i++) {
        q[m] = p[i];
        qb[m++] = br[i];
        if (i + 1 == n || br[i] || !is_ledge(p[i], p[i + 1]))
            continue;
        int k = (int)ceil(v2_len(v2_sub(p[i + 1], p[i])));
        for (int j = 1; j < k; j++)
            q[m++] = v2_lerp(p[i], p[i + 1], (double)j / k);
    }
    free(res->polyline);
    free(res->polyline_bridge);
    res->polyline = q;
    res->polyline_bridge = qb;
    res->n_polyline = m;
    return 0;
}

recon_status recon_extract(const image_t *img, const recon_options *opt, recon_result *res, char *err,
                           size_t errlen)
{
    memset(res, 0, sizeof *res);
    double t_start = now_seconds();
    if (!img || !img->data || img->channels < 1)
        return fail(RECON_ERR_SIZE, err, errlen, "no pixels");
    const int w = img->width, h = img->height;
    if (w < 32 || h < 32)
        return fail(RECON_ERR_SIZE, err, errlen, "image is %dx%d px; at least 32x32 needed", w, h);
    if ((double)w * h > 100e6)
        return fail(RECON_ERR_SIZE, err, errlen, "image is %dx%d px, over 100 megapixels", w, h);
    const size_t n = (size_t)w * h;
    res->width = w;
    res->height = h;
    recon_status st = RECON_OK;
    float *gray = malloc(n * sizeof *gray);
    res->mask = malloc(n);
    recon_border_set bs = {0};
    int *ext = NULL;
    double *con = NULL;
    uint8_t *gaps = NULL;
    recon_outline_point *pts = NULL;
    float *rowbuf = NULL;
    if (!gray || !res->mask) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }

    /* 1. The vessel's mask: alpha or a forced threshold, cleaned as before;
     * otherwise the segmentation. */
    vec2 origin = v2(0, 0), dir = v2(0, -1);
    double delta = 0.05;
    res->mask_mode = recon_mask_threshold(img, opt ? opt->threshold : -1, gray, res->mask, &res->threshold_used);
    if (res->mask_mode == RECON_MASK_GRAPH_CUT) {
        st = segment_vessel(img, opt ? opt->object_prior : NULL, res, &origin, &dir, &delta, err, errlen);
        if (st != RECON_OK)
            goto out;
    } else {
        long area = recon_mask_clean(res->mask, w, h, &res->dropped_objects, &res->holes_filled);
        if (area > 0 && recon_mask_close(res->mask, w, h, 4))
            area = -1;
        if (area < 0) {
            st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
            goto out;
        }
        if (area == 0) {
            st = fail(RECON_ERR_NO_OBJECT, err, errlen, "no object found (threshold %d)", res->threshold_used);
            goto out;
        }
        /* Half the threshold (at least 3/255) separates object from
         * background noise and JPEG ringing. */
        delta = res->mask_mode == RECON_MASK_ALPHA ? 0.05 : fmax(0.5 * res->threshold_used, 3.0) / 255;
        double x0, slope;
        if (recon_mask_axis(res->mask, w, h, &x0, &slope) == 0) {
            dir = v2_norm(v2(-slope, -1));
            origin = v2(x0 + slope * h, h);
        }
    }
    res->border_contact = border_contact(res->mask, w, h);
    /* Not a vessel: the backdrop on the axis between object on both sides
     * (measured on the object as segmented, before the fills below, which
     * assume a surface of revolution). */
    if (recon_axis_gap(res->mask, w, h, origin, dir, &res->axis_gap) != 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    if (res->axis_gap > RECON_MAX_AXIS_GAP) {
        st = fail(RECON_ERR_SHAPE, err, errlen,
                  "not a vessel: the backdrop lies on the object's axis, between object on both sides, over %.0f%% "
                  "of its height (a surface of revolution covers its axis; at most %.0f%%)",
                  100 * res->axis_gap, 100 * RECON_MAX_AXIS_GAP);
        goto out;
    }
    fill_across_axis(res->mask, w, h, origin, dir);
    if (fill_holes_but_windows(res->mask, w, h, origin, dir) != 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }

    /* 2. Outer contour (the first border met is the object's outer border). */
    if (recon_border_follow(res->mask, w, h, &bs) || bs.n_borders < 1) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    const recon_border *ob = &bs.borders[0];
    int nc = ob->count;
    res->contour = malloc((size_t)nc * sizeof *res->contour);
    if (!res->contour) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    for (int i = 0; i < nc; i++) {
        const int *p = bs.points + 2 * (size_t)(ob->start + i);
        res->contour[i] = v2(p[0] + 0.5, p[1] + 0.5);
    }
    res->n_contour = nc;
    recon_pca(res->contour, nc, &res->pca_mean, res->pca_axes, res->pca_eigenvalues);

    /* 3. Sub-pixel outlines of the body on both sides, every row. */
    ext = malloc((size_t)4 * h * sizeof *ext);
    con = malloc((size_t)h * 4 * sizeof *con);
    gaps = malloc((size_t)h * 2);
    pts = malloc((size_t)h * 2 * sizeof *pts);
    int direct = img->channels == 3 && in_unit_range(img);
    rowbuf = direct ? NULL : malloc((size_t)w * 3 * sizeof *rowbuf);
    if (!ext || !con || !gaps || !pts || (!direct && !rowbuf)) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    row_extents(res->mask, w, h, origin, dir, ext);
    double *tmp = con + 2 * h, median[2];
    for (int s = 0; s < 2; s++) {
        res->silhouette[s] = malloc((size_t)h * sizeof(vec2));
        if (!res->silhouette[s]) {
            st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
            goto out;
        }
        int m = trace_side(img, gray, res->mask_mode == RECON_MASK_ALPHA, ext + (size_t)s * h,
                           ext + (size_t)(2 + s) * h, s ? 1 : -1, delta, res->silhouette[s], con + s * h,
                           gaps + s * h, rowbuf);
        res->n_silhouette[s] = m;
        res->edge_contrast[s] = quantile(con + s * h, m, 0.1, tmp);
        res->edge_noise_px[s] = roughness(res->silhouette[s], m, tmp, tmp + h);
        median[s] = quantile(con + s * h, m, 0.5, tmp);
    }
    if (res->n_silhouette[0] < 3 || res->n_silhouette[1] < 3) {
        st = fail(RECON_ERR_NO_OBJECT, err, errlen, "the object's outline could not be measured on both sides");
        goto out;
    }
    /* Rows whose edge contrast is under a quarter of the better side's
     * typical contrast are washed out (a highlight on the edge, a glaze as
     * light as the backdrop): their position is not the outline. */
    for (int s = 0; s < 2; s++) {
        double floor_c = 0.25 * fmax(median[0], median[1]);
        int m = 0;
        for (int k = 0; k < res->n_silhouette[s]; k++)
            if (con[s * h + k] >= floor_c) {
                gaps[s * h + m] = gaps[s * h + k];
                res->silhouette[s][m++] = res->silhouette[s][k];
            }
        res->n_silhouette[s] = m;
    }

    /* 4. The axis: the mirror symmetry of the whole outline, from the robust
     * start. A side whose typical edge contrast is under half the other's
     * may be washed out in part (a highlight along it). */
    double hb = INFINITY, ht = -INFINITY;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < res->n_silhouette[s]; k++) {
            double hh = v2_dot(v2_sub(res->silhouette[s][k], origin), dir);
            hb = fmin(hb, hh);
            ht = fmax(ht, hh);
        }
    int washed = 0, suspect = median[0] < 0.5 * median[1] ? 1 : (median[1] < 0.5 * median[0] ? -1 : 0);
    const double h_lo = hb + 0.05 * (ht - hb) + 2, h_hi = ht - 0.05 * (ht - hb) - 2;
    {
        vec2 o = origin, d = dir;
        recon_symmetry_fit fit = {suspect, res->edge_noise_px[suspect > 0] / 1.65, 0};
        if (recon_axis_symmetry(res->silhouette[0], res->n_silhouette[0], res->silhouette[1], res->n_silhouette[1],
                                &o, &d, h_lo, h_hi, &fit, &washed)) {
            origin = o;
            dir = d;
            res->axis_from_symmetry = 1;
        }
    }
    /* When too few of a washed-out side's rows agree to move the axis (its
     * mask outline lies inside the true one on most rows), its limb, on the
     * rows where it still departs from the backdrop, is the outline: the
     * symmetry of the limbs, under the same one-sided consensus (a row whose
     * limb is washed out too lies inside), gives the axis. */
    if (washed && !res->axis_from_symmetry) {
        vec2 *limb = malloc((size_t)2 * h * sizeof *limb);
        int nl, nr, unused;
        if (!limb || recon_limb_points(img, gray, res->mask_mode == RECON_MASK_ALPHA, ext, origin, dir, washed, delta,
                                       rowbuf, limb, &nl, limb + h, &nr) != 0) {
            free(limb);
            st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
            goto out;
        }
        /* the limb's points are pixel-rough: noise 0.25 px */
        vec2 o = origin, d = dir;
        recon_symmetry_fit fit = {washed, 0.25, 1};
        if (recon_axis_symmetry(limb, nl, limb + h, nr, &o, &d, h_lo, h_hi, &fit, &unused)) {
            origin = o;
            dir = d;
            res->axis_from_symmetry = 1;
        }
        free(limb);
    }

    /* Not a vessel: a base that reaches much farther on one side of the
     * body's axis (an L's foot, a second vessel against the first). Only
     * about an axis the outline's mirror symmetry gave: the rows' midpoints
     * follow a part that stands out on one side over most of the height. */
    res->base_asymmetry = res->axis_from_symmetry ? recon_base_asymmetry(res->mask, w, h, origin, dir) : 0;
    if (res->base_asymmetry > RECON_MAX_BASE_ASYMMETRY) {
        st = fail(RECON_ERR_SHAPE, err, errlen,
                  "not a vessel: its base reaches %.1f%% of its height farther on one side of the axis than on the "
                  "other (a surface of revolution stands on a base symmetric about its axis; at most %.1f%%)",
                  100 * res->base_asymmetry, 100 * RECON_MAX_BASE_ASYMMETRY);
        goto out;
    }

    /* 5. The caps: where the outline meets its top and bottom, on each side. */
    int base_is_cut = 0;
    for (int i = 0; i < res->n_excluded; i++)
        base_is_cut |= res->excluded[i].what == RECON_PART_STAND || res->excluded[i].what == RECON_PART_SHADOW;
    const vec2 *const outline[2] = {res->silhouette[0], res->silhouette[1]};
    if (recon_find_caps(img, res->contour, nc, outline, res->n_silhouette, origin, dir, base_is_cut, res->corners) !=
        0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    /* The washed-out side's corners are wrong with its outline: mirror the
     * clean side's across the axis (the outline is symmetric). */
    if (washed) {
        static const int pairs[2][2] = {{CORNER_RIM_LEFT, CORNER_RIM_RIGHT}, {CORNER_BASE_LEFT, CORNER_BASE_RIGHT}};
        int clean = washed > 0 ? 1 : 0;
        for (int q = 0; q < 2; q++) {
            vec2 c = res->corners[pairs[q][clean]];
            vec2 foot = v2_add(origin, v2_scale(dir, v2_dot(v2_sub(c, origin), dir)));
            res->corners[pairs[q][1 - clean]] = v2_sub(v2_scale(foot, 2), c);
        }
    }
    double h_base = 0.5 * (v2_dot(v2_sub(res->corners[CORNER_BASE_LEFT], origin), dir) +
                           v2_dot(v2_sub(res->corners[CORNER_BASE_RIGHT], origin), dir));
    origin = v2_add(origin, v2_scale(dir, h_base));
    double H = 0.5 * (v2_dot(v2_sub(res->corners[CORNER_RIM_LEFT], origin), dir) +
                      v2_dot(v2_sub(res->corners[CORNER_RIM_RIGHT], origin), dir));
    if (!(H > 2)) {
        st = fail(RECON_ERR_SHAPE, err, errlen, "the outline has no height between its base and its rim");
        goto out;
    }
    res->axis_origin = origin;
    res->axis_direction = dir;
    res->tilt_deg = atan2(dir.x, -dir.y) * 180 / M_PI;
    /* A vessel stands on its foot: an axis more than 30 degrees from the
     * image's vertical is an object lying down or a photo turned on its side,
     * whose base and rim the caps would not find. */
    if (fabs(res->tilt_deg) > MAX_TILT_DEG) {
        st = fail(RECON_ERR_SHAPE, err, errlen,
                  "the object's axis leans %.0f degrees from the image's vertical (at most %.0f): photograph the vessel "
                  "upright, or rotate the photo",
                  res->tilt_deg, MAX_TILT_DEG);
        goto out;
    }

    /* 6. Side: the requested one, or the one whose edge has the better
     * contrast-to-noise (a highlight on the edge lowers the contrast there). */
    int s = 1;
    recon_side want = opt ? opt->side : RECON_SIDE_AUTO;
    if (want == RECON_SIDE_LEFT)
        s = 0;
    else if (want == RECON_SIDE_AUTO && washed)
        s = washed > 0; /* the clean side */
    else if (want == RECON_SIDE_AUTO) {
        double q0 = res->edge_contrast[0] / (res->edge_noise_px[0] + 0.05);
        double q1 = res->edge_contrast[1] / (res->edge_noise_px[1] + 0.05);
        s = q1 >= q0 ? 1 : 0;
    }
    res->side_used = s ? RECON_SIDE_RIGHT : RECON_SIDE_LEFT;

    /* 7. Parts: where the two sides disagree, the side that continues the
     * body, or a bridge; where they agree, their mean. */
    recon_outline_point *mp = pts, *op = pts + h;
    int nm = recon_outline_points(res->silhouette[s], gaps + s * h, res->n_silhouette[s], origin, dir, s ? 1 : -1, H,
                                  mp);
    int no = recon_outline_points(res->silhouette[1 - s], gaps + (1 - s) * h, res->n_silhouette[1 - s], origin, dir,
                                  s ? -1 : 1, H, op);
    double rmax = 0;
    for (int i = 0; i < nm; i++)
        rmax = fmax(rmax, mp[i].r);
    double tol = fmax(2.0, 0.02 * rmax);
    /* A washed-out side is not compared (its outline lies inside the true
     * one): the profile is the clean side's, its parts found on it alone. */
    res->r_max = rmax;
    if (recon_resolve_parts(mp, nm, op, washed ? 0 : no, s, tol, res->excluded, RECON_MAX_EXCLUDED, &res->n_excluded,
                                       &res->lr_disagreement, &res->excluded_fraction) != 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }

    /* 8. Polyline (r, h), base to rim, closed by the end heights. */
    res->polyline = malloc((size_t)(nm + 2) * sizeof *res->polyline);
    res->polyline_bridge = calloc((size_t)nm + 2, 1);
    if (!res->polyline || !res->polyline_bridge) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    /* Rows the main side's outline lost (washed out, no edge) are bridged
     * like a part's rows: the chord across them is not outline. They count
     * among the rows the profile does not measure. */
    int np = 0, missing = 0;
    for (int i = 0; i < nm; i++) {
        int lost = i > 0 ? (int)lround(fabs(mp[i].y - mp[i - 1].y)) - 1 : 0;
        if (lost > 2 && np > 0) {
            res->polyline_bridge[np - 1] = 1;
            missing += lost;
        }
        if (isnan(mp[i].r)) {
            if (np > 0)
                res->polyline_bridge[np - 1] = 1;
            continue;
        }
        if (np == 0) {
            /* the base: rows missing up to the first point are bridged */
            res->polyline_bridge[np] = mp[i].h > 3;
            res->polyline[np++] = v2(mp[i].r, 0);
        }
        res->polyline[np++] = v2(mp[i].r, mp[i].h);
    }
    if (np < 3) {
        st = fail(RECON_ERR_SHAPE, err, errlen, "the outline between the base and the rim is too short (%d points)",
                  np);
        goto out;
    }
    res->excluded_fraction = (res->excluded_fraction * nm + missing) / (nm + missing);
    res->polyline_bridge[np - 1] = res->polyline_bridge[np - 1] || H - res->polyline[np - 1].y > 3;
    res->polyline[np] = v2(res->polyline[np - 1].x, H);
    res->n_polyline = np + 1;
    if (densify_polyline(res) != 0)
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");

out:
    free(gray);
    free(ext);
    free(con);
    free(gaps);
    free(pts);
    free(rowbuf);
    recon_border_set_free(&bs);
    if (st != RECON_OK)
        free_arrays(res);
    res->ms_image_processing = (now_seconds() - t_start) * 1000;
    return st;
}
