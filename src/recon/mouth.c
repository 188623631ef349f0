/* recon_mouth_open: is the outline's top an open mouth seen from above? An
 * open vessel seen from above shows its rim as a whole ellipse: the
 * outline's top is the ellipse's far arc, and its near arc crosses the
 * photo inside the outline, where the lip or the interior above it meets
 * the outer wall below it. A dome (a lid's knob, a closed top) has no such
 * curve. So the far arc is fitted by an ellipse about the axis, and the
 * photo is asked for a step along the near arc that this ellipse predicts.
 * See recon_internal.h. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

enum { NEAR_ARC_SAMPLES = 64 };
/* The near arc's step (over 4 px) is three times the wall's own change
 * below it (4-8 px under the step), and at least 4/255, on most of the arc
 * (its 30th percentile). */
#define STEP_OVER_WALL 3.0
#define STEP_MIN (4.0 / 255)
#define STEP_QUANTILE 0.3
/* An arc lies on its ellipse when within this rms, px. */
#define ARC_RMS_MAX 1.5

/* The photo's luminance at the point r across the axis, d below the top. */
static double luminance_at(const image_t *img, vec2 origin, vec2 dir, double h_top, double r, double d)
{
    float c[3];
    recon_sample_rgb(img, v2_add(origin, v2_add(v2_scale(v2(-dir.y, dir.x), r), v2_scale(dir, h_top - d))), c);
    return (c[0] + c[1] + c[2]) / 3.0;
}

/* The ellipse r^2/a^2 + (d - b)^2/b^2 = 1 about the axis, d the depth below
 * the top, fitted to the contour's points with d <= depth: G = r^2 - p d +
 * q d^2 = 0, least squares in p and q, each point's equation weighted by
 * 1 / |grad G|^2 of the previous fit (Sampson's distance: the algebraic
 * residual near the top, where the arc runs across the axis, counted r^2
 * for a fraction of a pixel). Returns the rms Sampson distance of those
 * points (INFINITY when there is no such ellipse). */
static double fit_far_arc(const vec2 *contour, int n, vec2 origin, vec2 dir, double h_top, double depth, double *a,
                          double *b)
{
    vec2 nrm = v2(-dir.y, dir.x);
    double p = 0, qq = 0, rms = INFINITY;
    for (int it = 0; it < 6; it++) {
        double sdd = 0, sd3 = 0, sd4 = 0, sr2d = 0, sr2d2 = 0, se = 0;
        int m = 0;
        for (int i = 0; i < n; i++) {
            vec2 v = v2_sub(contour[i], origin);
            double d = h_top - v2_dot(v, dir), r = v2_dot(v, nrm);
            if (d < 0 || d > depth)
                continue;
            double gr = 2 * r, gd = 2 * qq * d - p, g2 = it ? gr * gr + gd * gd : 1;
            if (g2 < 1e-12)
                continue;
            double wt = 1 / g2, e = r * r - p * d + qq * d * d;
            se += e * e * wt;
            sdd += wt * d * d, sd3 += wt * d * d * d, sd4 += wt * d * d * d * d;
            sr2d += wt * r * r * d, sr2d2 += wt * r * r * d * d;
            m++;
        }
        if (it)
            rms = sqrt(se / m);
        double det = sdd * sd4 - sd3 * sd3;
        if (m < 8 || fabs(det) < 1e-300)
            return INFINITY;
        p = (sr2d * sd4 - sr2d2 * sd3) / det;
        qq = (sr2d * sd3 - sr2d2 * sdd) / det;
        if (!(p > 0 && qq > 0))
            return INFINITY;
    }
    *b = p / (2 * qq);
    *a = sqrt(qq) * *b;
    return rms;
}

int recon_mouth_open(const image_t *img, const vec2 *contour, int n, vec2 origin, vec2 dir, double h_top,
                     double depth, double ellipse[2])
{
    double a, b;
    /* the top half of the zone first (the far arc, if any), then the far
     * half of the ellipse that gives */
    if (!img || !isfinite(fit_far_arc(contour, n, origin, dir, h_top, 0.5 * depth, &a, &b)) || b < 3 ||
        fit_far_arc(contour, n, origin, dir, h_top, b, &a, &b) > ARC_RMS_MAX || b < 3)
        return 0;
    /* The near arc: per column the sharpest step within a band around the
     * one this ellipse predicts (the far arc's top gives b to a few px),
     * against the wall's own change below it; the steps found must lie on
     * the far arc's ellipse's near half, d = c + b' sqrt(1 - r^2/a^2) with
     * c and b' within 30% of b (a painted band is no such curve). */
    double step[NEAR_ARC_SAMPLES], wall[NEAR_ARC_SAMPLES], sq[NEAR_ARC_SAMPLES], dk[NEAR_ARC_SAMPLES];
    double band = fmax(4, 0.25 * b), low[NEAR_ARC_SAMPLES];
    /* the outline's lowest point under each column: the near arc must lie
     * inside the outline, with wall below it (a sphere's or an egg's lower
     * outline is its top's ellipse's near arc, and a step) */
    vec2 nrm = v2(-dir.y, dir.x);
    for (int k = 0; k < NEAR_ARC_SAMPLES; k++)
        low[k] = -INFINITY;
    for (int i = 0; i < n; i++) {
        vec2 v = v2_sub(contour[i], origin);
        int k = (int)lround((v2_dot(v, nrm) / a + 0.6) / 1.2 * (NEAR_ARC_SAMPLES - 1));
        if (k >= 0 && k < NEAR_ARC_SAMPLES)
            low[k] = fmax(low[k], h_top - v2_dot(v, dir));
    }
    for (int k = 0; k < NEAR_ARC_SAMPLES; k++) {
        double r = a * (-0.6 + 1.2 * k / (NEAR_ARC_SAMPLES - 1));
        sq[k] = sqrt(1 - r * r / (a * a));
        double dn = b + b * sq[k], best = -1, at = dn;
        if (low[k] < dn + band + 10)
            return 0;
        for (double o = -band; o <= band; o += 0.5) {
            double g = fabs(luminance_at(img, origin, dir, h_top, r, dn + o - 2) -
                            luminance_at(img, origin, dir, h_top, r, dn + o + 2));
            if (g > best)
                best = g, at = dn + o;
        }
        step[k] = best;
        dk[k] = at;
        wall[k] = fabs(luminance_at(img, origin, dir, h_top, r, at + 4) - luminance_at(img, origin, dir, h_top, r, at + 8));
    }
    /* d_k = c + b' sq_k by least squares */
    double s1 = 0, ss = 0, sd = 0, ssd = 0, N = NEAR_ARC_SAMPLES;
    for (int k = 0; k < NEAR_ARC_SAMPLES; k++)
        s1 += sq[k], ss += sq[k] * sq[k], sd += dk[k], ssd += sq[k] * dk[k];
    double det = N * ss - s1 * s1;
    if (fabs(det) < 1e-12)
        return 0;
    double bn = (N * ssd - s1 * sd) / det, c = (sd - bn * s1) / N, se = 0;
    for (int k = 0; k < NEAR_ARC_SAMPLES; k++)
        se += (dk[k] - c - bn * sq[k]) * (dk[k] - c - bn * sq[k]);
    gsl_sort(step, 1, NEAR_ARC_SAMPLES);
    gsl_sort(wall, 1, NEAR_ARC_SAMPLES);
    double s30 = gsl_stats_quantile_from_sorted_data(step, 1, NEAR_ARC_SAMPLES, STEP_QUANTILE);
    double wmed = gsl_stats_median_from_sorted_data(wall, 1, NEAR_ARC_SAMPLES);
    ellipse[0] = a;
    ellipse[1] = b;
    return s30 > STEP_MIN && s30 > STEP_OVER_WALL * wmed && fabs(bn - b) < 0.3 * b && fabs(c - b) < 0.3 * b &&
           sqrt(se / N) < ARC_RMS_MAX;
}
