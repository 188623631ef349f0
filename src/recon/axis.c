/* The axis of revolution: PCA of the contour, and its refinement by the
 * mirror symmetry of the sub-pixel left and right outlines. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

void recon_pca(const vec2 *pts, int n, vec2 *mean, vec2 axes[2], double eig[2])
{
    double mx = 0, my = 0;
    for (int i = 0; i < n; i++) {
        mx += pts[i].x;
        my += pts[i].y;
    }
    mx /= n > 0 ? n : 1;
    my /= n > 0 ? n : 1;
    double sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < n; i++) {
        double dx = pts[i].x - mx, dy = pts[i].y - my;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if (n > 0) {
        sxx /= n;
        sxy /= n;
        syy /= n;
    }
    /* Symmetric 2x2 eigenproblem in closed form. */
    double tr = 0.5 * (sxx + syy), det = sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    eig[0] = tr + det;
    eig[1] = tr - det;
    double th = 0.5 * atan2(2 * sxy, sxx - syy); /* angle of the major axis */
    *mean = v2(mx, my);
    axes[0] = v2(cos(th), sin(th));
    axes[1] = v2(-sin(th), cos(th));
}

typedef struct {
    double h, r;
} hr_t;

static int cmp_h(const void *a, const void *b)
{
    double x = ((const hr_t *)a)->h, y = ((const hr_t *)b)->h;
    return (x > y) - (x < y);
}

/* r of the left outline at height h, by linear interpolation, and its slope
 * dr/dh; NAN where the outline is missing, gappy or too flat to compare. */
static double left_at(const hr_t *L, int nl, double h, double *slope)
{
    int lo = 0, hi = nl - 1;
    if (nl < 2 || h < L[0].h || h > L[nl - 1].h)
        return NAN;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (L[mid].h <= h)
            lo = mid;
        else
            hi = mid;
    }
    double dh = L[hi].h - L[lo].h;
    if (dh <= 1e-9 || dh > 3 || fabs(L[hi].r - L[lo].r) > 2 * dh)
        return NAN;
    *slope = (L[hi].r - L[lo].r) / dh;
    return L[lo].r + (h - L[lo].h) / dh * (L[hi].r - L[lo].r);
}

/* dr/dh of the right outline at its point i, over its points i-3 and i+3
 * (rows of the photo) in the frame (o, d); 0 when they are missing. */
static int right_slope(const vec2 *right, int nr, int i, vec2 o, vec2 d, double *slope)
{
    if (i < 3 || i + 3 >= nr || fabs(right[i + 3].y - right[i - 3].y) > 8)
        return 0;
    vec2 n = v2(-d.y, d.x), a = v2_sub(right[i - 3], o), b = v2_sub(right[i + 3], o);
    double dh = v2_dot(b, d) - v2_dot(a, d);
    if (fabs(dh) < 1e-9)
        return 0;
    *slope = (v2_dot(b, n) - v2_dot(a, n)) / dh;
    return 1;
}

/* The line e = a + b x of the symmetric rows when one outline may be washed
 * out. A washed-out outline can only lie inside the true one, so every row's
 * residual e = r_right - r_left lies on one side of the true line (above it
 * when the left is washed out, washed = +1; below for the right, -1) and the
 * clean rows lie on it, within the edge noise. Candidates: lines through two
 * rows of an even subsample; score (over every other row): rows within tau
 * of the line, minus four for each row more than tau on the wrong side. A
 * median, or a consensus without the one-sided penalty, fails here: a
 * highlight along most of an edge leaves few clean rows, outvoted by
 * washed-out rows whose error drifts slowly (a line through those passes
 * above the clean rows, which the penalty counts). */
static void washed_consensus_line(const double *e, const double *x, int m, int washed, double tau, int samples,
                                  double *a, double *b)
{
    enum { STRIDE = 2 };
    double xlo = x[0], xhi = x[0], best = -INFINITY;
    for (int i = 1; i < m; i++)
        xlo = fmin(xlo, x[i]), xhi = fmax(xhi, x[i]);
    for (int p = 0; p < samples; p++)
        for (int q = p + 1; q < samples; q++) {
            int i = (int)((long)p * (m - 1) / (samples - 1)), k = (int)((long)q * (m - 1) / (samples - 1));
            if (fabs(x[k] - x[i]) < 0.05 * (xhi - xlo))
                continue;
            double bb = (e[k] - e[i]) / (x[k] - x[i]), aa = e[i] - bb * x[i], score = 0;
            for (int j = 0; j < m; j += STRIDE) {
                double r = e[j] - aa - bb * x[j];
                score += fabs(r) <= tau ? 1.0 : (washed * r < -tau ? -4.0 : 0.0);
            }
            if (score > best) {
                best = score;
                *a = aa;
                *b = bb;
            }
        }
}

int recon_axis_symmetry(const vec2 *left, int nl, const vec2 *right, int nr, vec2 *origin, vec2 *dir, double h_lo,
                        double h_hi, const recon_symmetry_fit *fit, int *washed_side)
{
    const int suspect = fit->suspect;
    int washed = 0;
    *washed_side = 0;
    hr_t *L = malloc((size_t)(nl > 0 ? nl : 1) * sizeof *L);
    double *e = malloc((size_t)(nr > 0 ? nr : 1) * 3 * sizeof *e);
    if (!L || !e) {
        free(L);
        free(e);
        return 0;
    }
    double *hs = e + nr, *tmp = hs + nr;
    vec2 o = *origin, d = *dir;
    int ok = 0;
    for (int iter = 0; iter < 6; iter++) {
        vec2 n = v2(-d.y, d.x);
        for (int i = 0; i < nl; i++) {
            vec2 q = v2_sub(left[i], o);
            L[i] = (hr_t){v2_dot(q, d), -v2_dot(q, n)};
        }
        qsort(L, (size_t)nl, sizeof *L, cmp_h);
        int m = 0;
        for (int i = 0; i < nr; i++) {
            vec2 q = v2_sub(right[i], o);
            double h = v2_dot(q, d);
            if (h < h_lo || h > h_hi)
                continue;
            double slope, rl = left_at(L, nl, h, &slope);
            if (isnan(rl))
                continue;
            /* Rotating the axis by dth also moves each point's height by
             * -+dth r, which shifts the left outline by its slope: the
             * residual's derivative in dth is 2 (h + slope r). The two
             * outlines' slopes agree (mirror images); a left limb, found
             * row by row, is too rough for one, and the right outline's
             * slope over +-3 rows serves. */
            if (fit->limb && suspect > 0 && !right_slope(right, nr, i, o, d, &slope))
                continue;
            e[m] = v2_dot(q, n) - rl;
            hs[m++] = h + slope * rl;
        }
        if (m < 20)
            break;
        /* Inliers: rows whose residual is near the line e = a + b x. First,
         * is the suspect side washed out? Yes when under 70% of the rows
         * agree with its one-sided consensus line. Then the inliers are near
         * that line at first (the start may be off by a few degrees), later
         * within 0.75 px of zero. Otherwise: near the median, within three
         * robust sigmas (at least 0.5 px; at most 1.5 px once aligned: a row
         * further off is not symmetric, whatever the spread of the rest). */
        double a = 0, b = 0, tol = 0.75;
        if (iter == 0 && suspect) {
            tol = fmax(0.25, fmin(0.75, 3 * fit->noise_px));
            washed_consensus_line(e, hs, m, suspect, tol, fit->limb ? 64 : 32, &a, &b);
            int agree = 0;
            for (int i = 0; i < m; i++)
                agree += fabs(e[i] - a - b * hs[i]) <= tol;
            washed = agree < 0.7 * m ? suspect : 0;
        }
        if (!washed) {
            for (int i = 0; i < m; i++)
                tmp[i] = e[i];
            a = gsl_stats_select(tmp, 1, (size_t)m, (size_t)(m / 2));
            b = 0;
            for (int i = 0; i < m; i++)
                tmp[i] = fabs(e[i] - a);
            tol = fmax(3 * 1.4826 * gsl_stats_select(tmp, 1, (size_t)m, (size_t)(m / 2)), 0.5);
            if (iter >= 2)
                tol = fmin(tol, 1.5);
        }
        /* Least squares e = 2 dc + 2 dth (x - xm) on the inliers, x = h + slope r. */
        double hm = 0, cnt = 0;
        for (int i = 0; i < m; i++)
            if (fabs(e[i] - a - b * hs[i]) <= tol) {
                hm += hs[i];
                cnt++;
            }
        /* Enough rows: 30% of them; 15% of a washed-out outline's. A limb
         * survives on fewer rows, scattered: at least 20 that give the tilt
         * within 0.05 deg (one standard error, below). */
        if (cnt < 20 || cnt < (washed ? (fit->limb ? 0.0 : 0.15) : 0.3) * m)
            break;
        hm /= cnt;
        double se = 0, shh = 0, seh = 0;
        for (int i = 0; i < m; i++)
            if (fabs(e[i] - a - b * hs[i]) <= tol) {
                double x = hs[i] - hm;
                se += e[i];
                seh += e[i] * x;
                shh += x * x;
            }
        if (shh <= 0)
            break;
        double dc = 0.5 * se / cnt, dth = 0.5 * seh / shh, delta = dc - dth * hm;
        if (fit->limb) {
            /* e = 2 dc + 2 dth (x - xm) + noise: dth's standard error is s / (2 sqrt shh) */
            double rss = 0;
            for (int i = 0; i < m; i++)
                if (fabs(e[i] - a - b * hs[i]) <= tol) {
                    double r = e[i] - 2 * dc - 2 * dth * (hs[i] - hm);
                    rss += r * r;
                }
            if (0.5 * sqrt(rss / (cnt - 2) / shh) > 0.05 * M_PI / 180)
                break;
        }
        o = v2_add(o, v2_scale(n, delta));
        d = v2_norm(v2_add(d, v2_scale(n, dth)));
        ok = 1;
        if (fabs(delta) < 1e-4 && fabs(dth) < 1e-7)
            break;
    }
    free(L);
    free(e);
    /* A symmetric pair of outlines moves the axis a little; a large move means
     * one outline is unreliable: keep the corner-based axis then. */
    double turn = acos(fmin(1.0, fabs(v2_dot(d, *dir)))) * 180 / M_PI;
    vec2 n0 = v2(-dir->y, dir->x);
    *washed_side = washed; /* also when the axis stays: the outline is washed out all the same */
    if (!ok || turn > 8.0 || fabs(v2_dot(v2_sub(o, *origin), n0)) > 0.1 * (h_hi - h_lo) + 5)
        return 0;
    *origin = o;
    *dir = d;
    return 1;
}
