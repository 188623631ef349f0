/* recon_extract: photo -> mask -> contour -> corners -> axis -> sub-pixel
 * silhouette -> profile polyline. See include/celadon/recon.h. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "core/core.h"
#include "recon/recon_internal.h"

static const char *CORNER_NAME[CORNER_COUNT] = {"rim left", "rim right", "base left", "base right"};

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

/* Frees the arrays and clears their pointers and counts; scalars stay. */
static void free_arrays(recon_result *res)
{
    free(res->mask);
    free(res->contour);
    free(res->approx);
    free(res->silhouette[0]);
    free(res->silhouette[1]);
    free(res->polyline);
    res->mask = NULL;
    res->contour = res->approx = res->polyline = res->silhouette[0] = res->silhouette[1] = NULL;
    res->n_contour = res->n_approx = res->n_polyline = res->n_silhouette[0] = res->n_silhouette[1] = 0;
}

void recon_result_free(recon_result *res)
{
    free_arrays(res);
    memset(res, 0, sizeof *res);
}

static const char *border_touched(const uint8_t *m, int w, int h)
{
    for (int i = 0; i < w; i++) {
        if (m[i])
            return "top";
        if (m[(size_t)(h - 1) * w + i])
            return "bottom";
    }
    for (int j = 0; j < h; j++) {
        if (m[(size_t)j * w])
            return "left";
        if (m[(size_t)j * w + w - 1])
            return "right";
    }
    return NULL;
}

/* Midpoint of two corners (a rim or a base pair). */
static vec2 pair_midpoint(const vec2 *corners, int a, int b)
{
    return v2_scale(v2_add(corners[a], corners[b]), 0.5);
}

/* Quantile of v[0..n) (GSL's linear-time selection, in a copy in tmp:
 * sorting for one quantile would cost n log n). */
static double quantile(const double *v, int n, double q, double *tmp)
{
    if (n <= 0)
        return 0;
    memcpy(tmp, v, (size_t)n * sizeof *tmp);
    return gsl_stats_select(tmp, 1, (size_t)n, (size_t)(q * (n - 1) + 0.5));
}

/* Drops points more than 1 px from the median x of their 7-row neighbourhood
 * (a decoration or a highlight spoiling one row's ramp); an outline is smooth
 * at that scale, and the median of a straight run is its centre value. */
static int drop_outliers(vec2 *pts, double *contrast, int n)
{
    if (n < 7)
        return n;
    double *dev = malloc((size_t)n * sizeof *dev);
    if (!dev)
        return n;
    for (int k = 0; k < n; k++) {
        int a = k < 3 ? 0 : (k + 3 >= n ? n - 7 : k - 3);
        double v[7]; /* insertion-sorted: qsort's call overhead dominates for 7 */
        for (int i = 0; i < 7; i++) {
            double x = pts[a + i].x;
            int q = i;
            for (; q > 0 && v[q - 1] > x; q--)
                v[q] = v[q - 1];
            v[q] = x;
        }
        dev[k] = fabs(pts[k].x - v[3]);
    }
    int m = 0;
    for (int k = 0; k < n; k++)
        if (dev[k] <= 1.0) {
            pts[m] = pts[k];
            contrast[m++] = contrast[k];
        }
    free(dev);
    return m;
}

/* Sub-pixel outline of one side (-1 left, +1 right) on rows j0..j1; ext[j]
 * is the mask's outermost object pixel of row j on that side (-1: none).
 * Fills pts and contrast; returns the count. */
static int trace_side(const float *gray, const int *ext, int w, int h, int j0, int j1, int side, double delta,
                      vec2 *pts, double *contrast)
{
    int n = 0;
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < h; j++) {
        if (ext[j] < 0)
            continue;
        /* The outline's slope (dx per row) from the neighbouring rows: the
         * widest step decides the window. */
        double slope = 0;
        if (j > 0 && ext[j - 1] >= 0)
            slope = fabs((double)(ext[j - 1] - ext[j]));
        if (j + 1 < h && ext[j + 1] >= 0)
            slope = fmax(slope, fabs((double)(ext[j + 1] - ext[j])));
        recon_edge e = recon_subpixel_edge(gray, w, h, j, ext[j], side, slope, delta);
        if (!e.ok)
            continue;
        pts[n] = v2(e.x, j + 0.5);
        contrast[n++] = e.contrast;
    }
    return drop_outliers(pts, contrast, n);
}

/* Roughness of an outline: median |second difference| of x over its middle. */
static double roughness(const vec2 *p, int n, double *tmp, double *tmp2)
{
    int m = 0;
    for (int k = n / 10 + 1; k < n - n / 10 - 1; k++)
        tmp[m++] = fabs(p[k + 1].x - 2 * p[k].x + p[k - 1].x);
    return quantile(tmp, m, 0.5, tmp2);
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
    int *keep = NULL, *ext = NULL;
    double *con = NULL;
    if (!gray || !res->mask) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }

    /* 1. Mask: threshold; largest object, holes and rows filled; closing
     * (radius 4); floor shadow trimmed at the foot. */
    res->mask_mode = recon_mask_threshold(img, opt ? opt->threshold : -1, gray, res->mask, &res->threshold_used);
    long area = recon_mask_clean(res->mask, w, h, &res->dropped_objects, &res->holes_filled);
    if (area > 0 && recon_mask_close(res->mask, w, h, 4))
        area = -1;
    if (area < 0) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    if (area > 0 && res->mask_mode == RECON_MASK_BACKGROUND &&
        recon_mask_trim_soft(res->mask, gray, w, h, res->threshold_used / 255.0f)) {
        /* Trimming may leave thin slivers and pieces: an opening of radius 1
         * removes the slivers, then the largest object is kept again. */
        int dropped2, holes2;
        area = recon_mask_open(res->mask, w, h, 1) ? -1 : recon_mask_clean(res->mask, w, h, &dropped2, &holes2);
        if (area < 0) {
            st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
            goto out;
        }
    }
    if (area == 0) {
        st = fail(RECON_ERR_NO_OBJECT, err, errlen, "no object found (threshold %d)", res->threshold_used);
        goto out;
    }
    const char *edge = border_touched(res->mask, w, h);
    if (edge) {
        st = fail(RECON_ERR_TOUCHES_BORDER, err, errlen,
                  "the object touches the %s image border; leave a margin around the vessel", edge);
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
    keep = malloc((size_t)nc * sizeof *keep);
    if (!res->contour || !keep) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    for (int i = 0; i < nc; i++) {
        const int *p = bs.points + 2 * (size_t)(ob->start + i);
        res->contour[i] = v2(p[0] + 0.5, p[1] + 0.5);
    }
    res->n_contour = nc;

    /* 3. Douglas–Peucker with eps = 1 px: removes the pixel staircase and
     * keeps every real bend, so smooth arcs become chains of small turns and
     * the corner tests below can tell them from corners. */
    const double eps = 1.0;
    res->n_approx = recon_douglas_peucker_closed(res->contour, nc, eps, keep);
    res->approx = malloc((size_t)(res->n_approx > 0 ? res->n_approx : 1) * sizeof *res->approx);
    if (!res->approx) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    for (int k = 0; k < res->n_approx; k++)
        res->approx[k] = res->contour[keep[k]];

    recon_pca(res->contour, nc, &res->pca_mean, res->pca_axes, res->pca_eigenvalues);
    /* The axis of revolution is the eigenvector nearer the image vertical
     * (photos are upright), pointing up. */
    vec2 up = fabs(res->pca_axes[0].y) >= fabs(res->pca_axes[1].y) ? res->pca_axes[0] : res->pca_axes[1];
    if (up.y > 0)
        up = v2_scale(up, -1);
    int cidx[CORNER_COUNT];
    int found = recon_find_corners(res->contour, nc, keep, res->n_approx, res->pca_mean, up, cidx);
    if (found != 0xF) {
        char names[96] = "";
        for (int q = 0; q < CORNER_COUNT; q++)
            if (!(found & (1 << q))) {
                strcat(names, names[0] ? ", " : "");
                strcat(names, CORNER_NAME[q]);
            }
        st = fail(RECON_ERR_CORNERS, err, errlen, "cannot find the four outline corners: missing %s", names);
        goto out;
    }
    for (int q = 0; q < CORNER_COUNT; q++)
        res->corners[q] = res->contour[cidx[q]];

    /* 4. Axis: the line through the corner pairs' midpoints when both pairs
     * are perpendicular to it (within 4°); otherwise the PCA axis through the
     * contour's mean. Either is only the start of the symmetry fit (step 6). */
    vec2 m_rim = pair_midpoint(res->corners, CORNER_RIM_LEFT, CORNER_RIM_RIGHT);
    vec2 m_base = pair_midpoint(res->corners, CORNER_BASE_LEFT, CORNER_BASE_RIGHT);
    vec2 dir_c = v2_norm(v2_sub(m_rim, m_base));
    vec2 rim_pair = v2_norm(v2_sub(res->corners[CORNER_RIM_RIGHT], res->corners[CORNER_RIM_LEFT]));
    vec2 base_pair = v2_norm(v2_sub(res->corners[CORNER_BASE_RIGHT], res->corners[CORNER_BASE_LEFT]));
    const double perp_tol = sin(4 * M_PI / 180);
    int corners_ok = v2_len(v2_sub(m_rim, m_base)) >= 2 && fabs(v2_dot(rim_pair, dir_c)) < perp_tol &&
                     fabs(v2_dot(base_pair, dir_c)) < perp_tol && v2_dot(dir_c, up) > 0;
    vec2 starts_o[2] = {m_base, v2_add(res->pca_mean, v2_scale(up, v2_dot(v2_sub(m_base, res->pca_mean), up)))};
    vec2 starts_d[2] = {dir_c, up};
    int first = corners_ok ? 0 : 1;
    vec2 origin = starts_o[first], dir = starts_d[first];

    /* 5. Sub-pixel outlines on both sides, rim corner row to base corner row. */
    ext = malloc((size_t)2 * h * sizeof *ext);
    if (!ext) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    for (int j = 0; j < h; j++) {
        const uint8_t *m = res->mask + (size_t)j * w, *p = memchr(m, 1, (size_t)w);
        ext[j] = p ? (int)(p - m) : -1;
        ext[h + j] = p ? (int)((const uint8_t *)memrchr(m, 1, (size_t)w) - m) : -1;
    }
    int cap = h;
    con = malloc((size_t)cap * 4 * sizeof *con);
    if (!con) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    double *tmp = con + 2 * cap, median[2];
    for (int s = 0; s < 2; s++) {
        int side = s ? 1 : -1;
        vec2 rc = res->corners[s ? CORNER_RIM_RIGHT : CORNER_RIM_LEFT];
        vec2 bc = res->corners[s ? CORNER_BASE_RIGHT : CORNER_BASE_LEFT];
        int j0 = (int)floor(fmin(rc.y, bc.y)), j1 = (int)floor(fmax(rc.y, bc.y));
        res->silhouette[s] = malloc((size_t)cap * sizeof(vec2));
        if (!res->silhouette[s]) {
            st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
            goto out;
        }
        /* Half the mask threshold (at least 3/255) separates object from
         * background noise and JPEG ringing. */
        double delta = res->mask_mode == RECON_MASK_ALPHA ? 0.05 : fmax(0.5 * res->threshold_used, 3.0) / 255;
        int m = trace_side(gray, ext + (size_t)s * h, w, h, j0, j1, side, delta, res->silhouette[s], con + s * cap);
        res->n_silhouette[s] = m;
        res->edge_contrast[s] = quantile(con + s * cap, m, 0.1, tmp);
        res->edge_noise_px[s] = roughness(res->silhouette[s], m, tmp, tmp + cap);
        median[s] = quantile(con + s * cap, m, 0.5, tmp);
    }
    /* Rows whose edge contrast is under a quarter of the better side's
     * typical contrast are washed out (a highlight on the edge, a glaze as
     * light as the backdrop): their position is not the outline. */
    for (int s = 0; s < 2; s++) {
        double floor_c = 0.25 * fmax(median[0], median[1]);
        int m = 0;
        for (int k = 0; k < res->n_silhouette[s]; k++)
            if (con[s * cap + k] >= floor_c)
                res->silhouette[s][m++] = res->silhouette[s][k];
        res->n_silhouette[s] = m;
    }

    /* 6. Refine the axis by left/right symmetry on the middle 90% of the
     * height, from the preferred start, else from the other one. A side
     * whose typical edge contrast is under half the other's may be washed
     * out in part (a highlight along it). */
    int washed = 0, suspect = median[0] < 0.5 * median[1] ? 1 : (median[1] < 0.5 * median[0] ? -1 : 0);
    for (int k = 0; k < 2 && !res->axis_from_symmetry; k++) {
        vec2 o = starts_o[first ^ k], d = starts_d[first ^ k];
        double hb = v2_dot(v2_sub(m_base, o), d), ht = v2_dot(v2_sub(m_rim, o), d);
        if (recon_axis_symmetry(res->silhouette[0], res->n_silhouette[0], res->silhouette[1], res->n_silhouette[1],
                                &o, &d, hb + 0.05 * (ht - hb) + 2, ht - 0.05 * (ht - hb) - 2, suspect,
                                res->edge_noise_px[suspect > 0] / 1.65, &washed)) {
            origin = o;
            dir = d;
            res->axis_from_symmetry = 1;
        }
    }
    /* The washed-out side's corners are wrong with its outline: mirror the
     * clean side's across the refined axis (the outline is symmetric). */
    if (washed) { /* set only when the symmetry fit succeeded */
        static const int pairs[2][2] = {{CORNER_RIM_LEFT, CORNER_RIM_RIGHT}, {CORNER_BASE_LEFT, CORNER_BASE_RIGHT}};
        int clean = washed > 0 ? 1 : 0; /* index of the clean side in a pair */
        for (int q = 0; q < 2; q++) {
            vec2 c = res->corners[pairs[q][clean]];
            vec2 foot = v2_add(origin, v2_scale(dir, v2_dot(v2_sub(c, origin), dir)));
            res->corners[pairs[q][1 - clean]] = v2_sub(v2_scale(foot, 2), c);
        }
        m_rim = pair_midpoint(res->corners, CORNER_RIM_LEFT, CORNER_RIM_RIGHT);
        m_base = pair_midpoint(res->corners, CORNER_BASE_LEFT, CORNER_BASE_RIGHT);
    }
    char why[160];
    if (!recon_check_vessel(res->corners, dir, res->contour, nc, ext, h, why, sizeof why)) {
        st = fail(RECON_ERR_CORNERS, err, errlen, "not a vessel's outline: %s", why);
        goto out;
    }
    /* Origin: the base pair's midpoint projected onto the axis (h = 0). */
    origin = v2_add(origin, v2_scale(dir, v2_dot(v2_sub(m_base, origin), dir)));
    double H = v2_dot(v2_sub(m_rim, origin), dir);
    res->axis_origin = origin;
    res->axis_direction = dir;
    res->tilt_deg = atan2(dir.x, -dir.y) * 180 / M_PI;

    /* 7. Side: the requested one, or the one whose edge has the better
     * contrast-to-noise (a highlight on the edge lowers the contrast there). */
    int s = 1;
    recon_side want = opt ? opt->side : RECON_SIDE_AUTO;
    if (want == RECON_SIDE_LEFT)
        s = 0;
    else if (want == RECON_SIDE_AUTO) {
        double q0 = res->edge_contrast[0] / (res->edge_noise_px[0] + 0.05);
        double q1 = res->edge_contrast[1] / (res->edge_noise_px[1] + 0.05);
        s = q1 >= q0 ? 1 : 0;
    }
    res->side_used = s ? RECON_SIDE_RIGHT : RECON_SIDE_LEFT;

    /* 8. Polyline (r, h), base to rim: the sub-pixel points with 0 < h < H
     * (rows run top to bottom, so backwards), closed by the end heights. */
    int m = res->n_silhouette[s];
    res->polyline = malloc((size_t)(m + 2) * sizeof *res->polyline);
    if (!res->polyline) {
        st = fail(RECON_ERR_INTERNAL, err, errlen, "out of memory");
        goto out;
    }
    vec2 right = v2(-dir.y, dir.x);
    int np = 0;
    for (int k = m - 1; k >= 0; k--) {
        vec2 q = v2_sub(res->silhouette[s][k], origin);
        double r = (s ? 1 : -1) * v2_dot(q, right), hh = v2_dot(q, dir);
        if (hh <= 0 || hh >= H || (np > 1 && hh <= res->polyline[np - 1].y))
            continue;
        if (np == 0)
            res->polyline[np++] = v2(r, 0);
        res->polyline[np++] = v2(r, hh);
    }
    if (np < 3) {
        st = fail(RECON_ERR_CORNERS, err, errlen, "the outline between the corners is too short (%d points)", np);
        goto out;
    }
    res->polyline[np] = v2(res->polyline[np - 1].x, H);
    np++;
    res->n_polyline = np;

out:
    free(gray);
    free(keep);
    free(ext);
    free(con);
    recon_border_set_free(&bs);
    if (st != RECON_OK)
        free_arrays(res);
    res->ms_image_processing = (now_seconds() - t_start) * 1000;
    return st;
}
