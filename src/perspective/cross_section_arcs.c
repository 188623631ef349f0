/* The outline's top and bottom arcs, sub-pixel (perspective_internal.h).
 *
 * Between the rim corners the outline is the image of the rim circle, between
 * the base corners that of the base circle: nearly horizontal arcs, which
 * recon_extract's row-wise silhouettes do not cover. Each pixel column is
 * measured like a silhouette row (recon_subpixel_edge_flat: the area-based
 * edge of the anti-aliased ramp), on a copy of the column's signal. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "perspective/perspective_internal.h"
#include "recon/recon.h"

/* Columns this far inside the corners are left out: the corner is where the
 * wall's outline meets the arc, found within a few pixels. */
#define CORNER_MARGIN_PX 3.0
#define CORNER_MARGIN_FRAC 0.02

/* Rows j0..j1 of column i of the signal recon_extract measures edges on:
 * alpha when the mask came from it, else the photo's colours (one channel
 * for a gray photo), clamped to [0, 1] as recon_extract clamps its rows.
 * col holds up to 3 values per row. */
static recon_signal column_signal(const image_t *img, int alpha, int i, int j0, int j1, float *col)
{
    int C = img->channels, ch = !alpha && C >= 3 ? 3 : 1;
    for (int j = j0; j <= j1; j++) {
        const float *p = img->data + ((size_t)j * img->width + i) * C;
        for (int k = 0; k < ch; k++) {
            float v = p[alpha ? C - 1 : k];
            col[(size_t)(j - j0) * ch + k] = v > 0 ? (v < 1 ? v : 1) : 0;
        }
    }
    return (recon_signal){col, j1 - j0 + 1, ch};
}

/* The mask's outermost object row in column i, from the top (side -1) or
 * the bottom (+1); -1 when the column is empty. */
static int extreme_row(const recon_result *res, int i, int side)
{
    for (int k = 0; k < res->height; k++) {
        int j = side < 0 ? k : res->height - 1 - k;
        if (res->mask[(size_t)j * res->width + i])
            return j;
    }
    return -1;
}

/* The outermost object row of column i near the mask's extreme row
 * `here`, on side (-1 up, +1 down): the outermost step between neighbouring
 * pixels of at least a third of the largest step within 20 px inside and
 * 40 px outside the mask. A soft floor shadow that the mask took in, or a
 * mask cut short by a shadow trim, moves the mask's edge by several pixels;
 * the silhouette is the sharp step, the shadow a gentle ramp. */
static int outermost_step(const image_t *img, int alpha, int i, int here, int side, float *col)
{
    int h = img->height, j_in = here - side * 20, j_out = here + side * 40;
    j_in = j_in < 1 ? 1 : j_in > h - 2 ? h - 2 : j_in;
    j_out = j_out < 1 ? 1 : j_out > h - 2 ? h - 2 : j_out;
    int j0 = (j_in < j_out ? j_in : j_out) - 1, j1 = (j_in < j_out ? j_out : j_in) + 1;
    recon_signal s = column_signal(img, alpha, i, j0, j1, col);
    double big = 0; /* rows j are s's pixels j - j0 from here on */
    for (int j = j_in; j != j_out + side; j += side)
        big = fmax(big, recon_signal_distance(&s, j - j0, j - side - j0));
    for (int j = j_out; j != j_in - side; j -= side)
        if (recon_signal_distance(&s, j - j0, j - side - j0) >= big / 3)
            return j - side;
    return here;
}

/* The outline's sub-pixel edge in columns i0..i1 on side (-1 top, +1
 * bottom), a point per column where it is found. */
static int trace_columns(const image_t *img, const recon_result *res, int i0, int i1, int side, float *col,
                         int *edge_row, vec2 *out)
{
    i0 = i0 < 1 ? 1 : i0;
    i1 = i1 > res->width - 2 ? res->width - 2 : i1;
    int alpha = res->mask_mode == RECON_MASK_ALPHA, h = res->height;
    /* As recon_extract: half the mask threshold (at least 3/255) tells the
     * object from background noise. */
    double delta = alpha ? 0.05 : fmax(0.5 * res->threshold_used, 3.0) / 255;
    for (int i = i0; i <= i1; i++) {
        int here = extreme_row(res, i, side);
        edge_row[i - i0] = here >= 0 ? outermost_step(img, alpha, i, here, side, col) : -1;
    }
    int n = 0;
    for (int i = i0; i <= i1; i++) {
        int here = edge_row[i - i0];
        if (here < 0)
            continue;
        /* The arc's slope (rows per column) from the neighbouring columns. */
        double slope = 0;
        if (i > i0 && edge_row[i - i0 - 1] >= 0)
            slope = fabs((double)(edge_row[i - i0 - 1] - here));
        if (i < i1 && edge_row[i - i0 + 1] >= 0)
            slope = fmax(slope, fabs((double)(edge_row[i - i0 + 1] - here)));
        /* The rows recon_subpixel_edge may read: a few inside, and outside
         * only the ramp's |slope| + 1 pixels and two of backdrop. It takes
         * the backdrop from its farthest row and the edge from the first
         * pixel inward that differs from it; 12 px out, a floor shadow's
         * gentle ramp under the base differs from the backdrop beside the
         * edge, and the edge came out where the shadow fades (up to 12 px
         * below the base's ellipse on incense_bowl_sweep_e4). */
        int span = (int)ceil(slope), reach = span + 16;
        int j0 = here - (side < 0 ? span + 3 : reach), j1 = here + (side > 0 ? span + 3 : reach);
        j0 = j0 < 0 ? 0 : j0;
        j1 = j1 > h - 1 ? h - 1 : j1;
        recon_signal sig = column_signal(img, alpha, i, j0, j1, col);
        recon_edge e = recon_subpixel_edge_flat(&sig, here - j0, side, slope, delta);
        if (e.ok)
            out[n++] = v2(i + 0.5, j0 + e.x);
    }
    return n;
}

/* One arc: columns strictly between the corners' x (less the margin). */
static int trace_arc(const image_t *img, const recon_result *res, vec2 c0, vec2 c1, int side, float *col,
                     int *edge_row, vec2 *out)
{
    double lo = fmin(c0.x, c1.x), hi = fmax(c0.x, c1.x);
    double margin = fmax(CORNER_MARGIN_PX, CORNER_MARGIN_FRAC * (hi - lo));
    return trace_columns(img, res, (int)ceil(lo + margin), (int)floor(hi - margin - 1), side, col, edge_row, out);
}

int recon_outline_columns(const image_t *img, const recon_result *res, int i0, int i1, int side, vec2 *out)
{
    float *col = malloc((size_t)res->height * 3 * sizeof *col);
    int *edge_row = malloc((size_t)res->width * sizeof *edge_row);
    int n = col && edge_row ? trace_columns(img, res, i0, i1, side, col, edge_row, out) : -1;
    free(col);
    free(edge_row);
    return n;
}

int recon_outline_arcs(const image_t *img, const recon_result *res, vec2 **top, int *n_top, vec2 **bottom,
                       int *n_bottom)
{
    *top = malloc((size_t)res->width * sizeof **top);
    *bottom = malloc((size_t)res->width * sizeof **bottom);
    float *col = malloc((size_t)res->height * 3 * sizeof *col);
    int *edge_row = malloc((size_t)res->width * sizeof *edge_row);
    if (!*top || !*bottom || !col || !edge_row) {
        free(*top);
        free(*bottom);
        free(col);
        free(edge_row);
        *top = *bottom = NULL;
        return -1;
    }
    *n_top = trace_arc(img, res, res->corners[CORNER_RIM_LEFT], res->corners[CORNER_RIM_RIGHT], -1, col, edge_row,
                       *top);
    *n_bottom = trace_arc(img, res, res->corners[CORNER_BASE_LEFT], res->corners[CORNER_BASE_RIGHT], 1, col,
                          edge_row, *bottom);
    free(col);
    free(edge_row);
    return 0;
}

/* Luminance of the photo at a camera-frame point. */
static double frame_luma(const image_t *img, const recon_camera *cam, double u, double w)
{
    float rgb[3];
    recon_sample_rgb(img, recon_camera_to_image(cam, v2(u, w)), rgb);
    return 0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2];
}

/* Median of v[0..n) (sorts v). */
static double median(double *v, int n)
{
    gsl_sort(v, 1, (size_t)n);
    return gsl_stats_median_from_sorted_data(v, 1, (size_t)n);
}

int recon_rim_near_arc_visible(const image_t *img, const recon_camera *cam, const recon_ellipse *rim)
{
    enum { SAMPLES = 64 };
    /* The samples above the near half (up to 4 px) must stay 1.5 px below
     * the far half, 1.6 b above it at the outermost samples (u = 0.6 a). */
    if (!(rim->b >= 1.5) || !(rim->a >= 20.0))
        return -1;
    const int reach = (int)fmin(4, floor(1.6 * rim->b - 1.5));
    double step[SAMPLES], wall[SAMPLES];
    for (int k = 0; k < SAMPLES; k++) {
        double u = rim->a * 0.6 * (2.0 * (k + 0.5) / SAMPLES - 1);
        double near = rim->w0 - rim->b * sqrt(1 - (u / rim->a) * (u / rim->a));
        double below = frame_luma(img, cam, u, near - 2);
        step[k] = 0;
        for (int d = 1; d <= reach; d++)
            step[k] = fmax(step[k], fabs(frame_luma(img, cam, u, near + d) - below));
        wall[k] = fabs(below - frame_luma(img, cam, u, near - 6));
    }
    /* From above, the near half's edge parts the outer wall from the lip or
     * the inside of the mouth: within `reach` px above it the photo departs from
     * the wall 2 px below it by at least 4/255 and by three times the wall's
     * own change over the 4 px further down. From below, the wall goes on
     * across it, shaded as a glossy flare may be, but without a step. */
    double band = median(step, SAMPLES), quiet = median(wall, SAMPLES);
    return band > 3 * quiet && band > 4.0 / 255;
}
