/* recon_find_caps: where the outline meets its top and its bottom. A flat rim
 * or base seen from a level camera is a straight edge between two corners;
 * seen from slightly above it is an ellipse whose ends (its widest points, at
 * the height of the circle's centre) bend the outline as sharply as a corner
 * does. So on each side the corner is the point of the outline that turns
 * most within the top (bottom) zone: no assumption of a flat edge, a level
 * camera, or of the rim being the widest point. Where nothing stands out
 * (a dome, a knob's rounded top) the end is the pole. See recon_internal.h. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

/* A corner turns at least 20 degrees over the chords, and three times as
 * much as the outline around it does in the zone (a dome or a sphere turns
 * evenly: its end is its pole). */
#define CORNER_MIN_TURN (20 * M_PI / 180)
#define CORNER_PEAK_RATIO 3.0
/* A chamfer or a rounded foot takes at most 5% off the radius. */
#define BEVEL_MAX_INSET 0.05

/* Turning angle of the closed contour at i between the chords from i-k and to
 * i+k, signed so that a convex turn of the outline is positive (orient: +1
 * for a clockwise contour in image coordinates, y down, -1 otherwise). */
static double turn_at(const vec2 *c, int n, int i, int k, int orient)
{
    vec2 a = v2_sub(c[i], c[((i - k) % n + n) % n]), b = v2_sub(c[(i + k) % n], c[i]);
    return orient * atan2(v2_cross(a, b), v2_dot(a, b));
}

/* Signed area (shoelace; positive: clockwise on screen with y down). */
static double signed_area(const vec2 *c, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        vec2 a = c[i], b = c[(i + 1) % n];
        s += a.x * b.y - b.x * a.y;
    }
    return 0.5 * s;
}

/* ---- An end seen from above: the circle's ellipse, left tangentially.
 *
 * Seen from above (below), the outline's end is the near (far) arc of the
 * base's (rim's) ellipse, and the wall's silhouette leaves it where the two
 * are tangent: the plane that touches the wall along the base circle holds
 * both the ray and the circle's tangent, so the images share their tangent
 * there and nothing turns sharply. What changes there is the curve: an
 * ellipse on one side, the wall on the other. In the end's frame (r across
 * the axis, d depth from the end) an ellipse symmetric about a line r = r_c
 * is r^2 = c0 + c1 r + c2 d + c3 d^2 (c2 > 0, c3 < 0), the wall on each side
 * r = p0 + p1 d + p2 d^2; the corner depth is the change point that
 * minimises the two models' squared residuals, accepted when they explain
 * the zone better than one ellipse does by an F-test (a dome's end is an
 * ellipse all the way). */

#define ELLIPSE_MIN_POINTS 10
#define WALL_MIN_POINTS 6
#define CHANGE_POINT_F 20.0 /* as the conic fit's line-or-ellipse test */

typedef struct {
    double r, d; /* across the axis (signed), depth from the end */
    int i;       /* its index on the contour */
} end_point;

/* Least squares on up to 4 columns: x solves (A^T A) x = A^T y. A
 * (nearly) singular system is refused before GSL's solver would call its
 * error handler, which aborts. */
static int solve_normal(gsl_matrix *ata, gsl_vector *aty, gsl_vector *x)
{
    gsl_permutation *perm = gsl_permutation_alloc(ata->size1);
    int sgn, rc = perm ? gsl_linalg_LU_decomp(ata, perm, &sgn) : -1;
    double umax = 0, umin = INFINITY;
    for (size_t i = 0; rc == 0 && i < ata->size1; i++) {
        umax = fmax(umax, fabs(gsl_matrix_get(ata, i, i)));
        umin = fmin(umin, fabs(gsl_matrix_get(ata, i, i)));
    }
    if (rc == 0 && !(umin > 1e-12 * umax))
        rc = -1;
    if (rc == 0)
        rc = gsl_linalg_LU_solve(ata, perm, aty, x);
    gsl_permutation_free(perm);
    if (rc == 0)
        for (size_t i = 0; i < x->size; i++)
            if (!isfinite(gsl_vector_get(x, i)))
                rc = -1;
    return rc;
}

/* Sum of squared (Sampson) distances of the points with d in [lo, hi] to
 * the best symmetric ellipse; INFINITY when there is none. */
static double ellipse_sse(const end_point *p, int n, double lo, double hi, int *count, double *aspect)
{
    double m[16] = {0}, v[4] = {0}, xs[4];
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (p[i].d < lo || p[i].d > hi)
            continue;
        double a[4] = {1, p[i].r, p[i].d, p[i].d * p[i].d}, y = p[i].r * p[i].r;
        for (int u = 0; u < 4; u++) {
            v[u] += a[u] * y;
            for (int w = 0; w < 4; w++)
                m[4 * u + w] += a[u] * a[w];
        }
        k++;
    }
    *count = k;
    if (k < ELLIPSE_MIN_POINTS)
        return INFINITY;
    gsl_matrix_view mv = gsl_matrix_view_array(m, 4, 4);
    gsl_vector_view vv = gsl_vector_view_array(v, 4), xv = gsl_vector_view_array(xs, 4);
    if (solve_normal(&mv.matrix, &vv.vector, &xv.vector) != 0 || xs[2] <= 0 || xs[3] >= 0)
        return INFINITY;
    if (aspect)
        *aspect = 1 / sqrt(-xs[3]);
    double sse = 0;
    for (int i = 0; i < n; i++) {
        if (p[i].d < lo || p[i].d > hi)
            continue;
        double res = p[i].r * p[i].r - (xs[0] + xs[1] * p[i].r + xs[2] * p[i].d + xs[3] * p[i].d * p[i].d);
        double gr = 2 * p[i].r - xs[1], gd = -(xs[2] + 2 * xs[3] * p[i].d);
        double g2 = gr * gr + gd * gd;
        sse += g2 > 0 ? res * res / g2 : 0;
    }
    return sse;
}

/* Sum of squared residuals of |r| = p0 + p1 d + p2 d^2 on side s (r > 0 or
 * not) for d in (lo, hi]; INFINITY with too few points. */
static double wall_sse(const end_point *p, int n, int s, double lo, double hi)
{
    double m[9] = {0}, v[3] = {0}, xs[3], dmin = INFINITY, dmax = -INFINITY;
    int k = 0;
    for (int i = 0; i < n; i++) {
        if ((p[i].r > 0) != s || p[i].d <= lo || p[i].d > hi)
            continue;
        double a[3] = {1, p[i].d, p[i].d * p[i].d}, y = fabs(p[i].r);
        for (int u = 0; u < 3; u++) {
            v[u] += a[u] * y;
            for (int w = 0; w < 3; w++)
                m[3 * u + w] += a[u] * a[w];
        }
        dmin = fmin(dmin, p[i].d);
        dmax = fmax(dmax, p[i].d);
        k++;
    }
    if (k < WALL_MIN_POINTS || dmax - dmin < 3)
        return INFINITY;
    gsl_matrix_view mv = gsl_matrix_view_array(m, 3, 3);
    gsl_vector_view vv = gsl_vector_view_array(v, 3), xv = gsl_vector_view_array(xs, 3);
    if (solve_normal(&mv.matrix, &vv.vector, &xv.vector) != 0)
        return INFINITY;
    double sse = 0;
    for (int i = 0; i < n; i++) {
        if ((p[i].r > 0) != s || p[i].d <= lo || p[i].d > hi)
            continue;
        double res = fabs(p[i].r) - (xs[0] + xs[1] * p[i].d + xs[2] * p[i].d * p[i].d);
        sse += res * res;
    }
    return sse;
}

/* The depth where the outline leaves the end's ellipse for the wall, or -1
 * when one ellipse explains the zone as well (a dome) or nothing fits. */
static double ellipse_leaving_depth(const end_point *p, int n, double zone, double *aspect)
{
    int n_all;
    double sse1 = ellipse_sse(p, n, -INFINITY, zone, &n_all, NULL), best = INFINITY, best_d = -1, asp = 0;
    for (double delta = 2; delta < zone - 3; delta += 0.5) {
        int k;
        double a, e = ellipse_sse(p, n, -INFINITY, delta, &k, &a);
        if (!isfinite(e))
            continue;
        double t = e + wall_sse(p, n, 0, delta, zone) + wall_sse(p, n, 1, delta, zone);
        if (t < best) {
            best = t;
            best_d = delta;
            asp = a;
        }
    }
    const int extra = 3 + 3 + 1; /* two walls and the change point, beyond the ellipse's 4 */
    if (best_d < 0 || n_all <= 4 + extra + 1)
        return -1;
    double f = isfinite(sse1) ? (sse1 - best) / extra / (fmax(best, 1e-12) / (n_all - 4 - extra)) : INFINITY;
    if (f <= CHANGE_POINT_F)
        return -1;
    *aspect = asp;
    return best_d;
}

/* Per side, the zone's point nearest the depth where the outline leaves the
 * end's ellipse, and that ellipse's b/a into *aspect (when not NULL); 0, or
 * -1 (pick and aspect untouched) when it does not. */
static int ellipse_corners(const end_point *p, int n, double zone, int pick[2], double *aspect)
{
    double b_over_a = 0, delta = ellipse_leaving_depth(p, n, zone, &b_over_a);
    if (delta < 0)
        return -1;
    int found[2] = {-1, -1};
    double gap[2] = {INFINITY, INFINITY};
    for (int i = 0; i < n; i++) {
        int s = p[i].r > 0;
        if (fabs(p[i].d - delta) < gap[s]) {
            gap[s] = fabs(p[i].d - delta);
            found[s] = p[i].i;
        }
    }
    if (found[0] < 0 || found[1] < 0)
        return -1;
    pick[0] = found[0];
    pick[1] = found[1];
    if (aspect)
        *aspect = b_over_a;
    return 0;
}

/* The mean depth below h_end of the two picked contour points (0 when one is missing). */
static double pick_depth(const vec2 *c, vec2 origin, vec2 dir, double h_end, const int pick[2])
{
    if (pick[0] < 0 || pick[1] < 0)
        return 0;
    return h_end - 0.5 * (v2_dot(v2_sub(c[pick[0]], origin), dir) + v2_dot(v2_sub(c[pick[1]], origin), dir));
}

static int by_depth(const void *a, const void *b)
{
    double da = ((const end_point *)a)->d, db = ((const end_point *)b)->d;
    return (da > db) - (da < db);
}

/* Where the outline leaves the rim's ellipse r^2/a^2 + (d - b)^2/b^2 = 1
 * (e[0] = a, e[1] = b; d the depth below the top) on each side: from the top
 * down, the deepest zone point within 1 px of it before three in a row
 * lie more than 3 px off, at least half its half-height down. Sorts p.
 * Returns 0, or -1 (pick untouched) when a side has none. */
static int leave_ellipse(end_point *p, int n, const double e[2], int pick[2])
{
    qsort(p, (size_t)n, sizeof *p, by_depth);
    int found[2] = {-1, -1}, off[2] = {0, 0};
    for (int i = 0; i < n; i++) {
        int s = p[i].r > 0;
        if (off[s] >= 3 || p[i].d > 2 * e[1])
            continue;
        /* Sampson's distance from the ellipse */
        double u = p[i].r / e[0], v = (p[i].d - e[1]) / e[1];
        double dist = fabs(u * u + v * v - 1) / (2 * sqrt(u * u / (e[0] * e[0]) + v * v / (e[1] * e[1])) + 1e-300);
        off[s] = dist > 3 ? off[s] + 1 : 0;
        if (dist <= 1 && p[i].d >= 0.5 * e[1])
            found[s] = p[i].i;
    }
    if (found[0] < 0 || found[1] < 0)
        return -1;
    pick[0] = found[0];
    pick[1] = found[1];
    return 0;
}

/* The mean distance of the picked points (one per side) from the axis. */
static double pick_half_width(const end_point *p, int n, const int pick[2])
{
    double w = 0;
    for (int i = 0; i < n; i++)
        if (p[i].i == pick[0] || p[i].i == pick[1])
            w += 0.5 * fabs(p[i].r);
    return w;
}

int recon_find_caps(const image_t *img, const vec2 *contour_px, int n, const vec2 *const outline[2],
                    const int n_outline[2], vec2 origin, vec2 dir, int base_is_cut, vec2 corners[CORNER_COUNT])
{
    double *turns = malloc((size_t)(n > 0 ? n : 1) * sizeof *turns);
    vec2 *contour = malloc((size_t)(n > 0 ? n : 1) * sizeof *contour);
    end_point *zp = malloc((size_t)(n > 0 ? n : 1) * sizeof *zp);
    if (!turns || !contour || !zp) {
        free(turns);
        free(contour);
        free(zp);
        return -1;
    }
    /* The pixel staircase turns by up to 45 degrees from one step to the
     * next: average each point with its two neighbours on either side
     * ([1 2 3 2 1] / 9) before measuring turns. */
    for (int i = 0; i < n; i++) {
        static const double wt[5] = {1, 2, 3, 2, 1};
        vec2 acc = v2(0, 0);
        for (int j = -2; j <= 2; j++)
            acc = v2_add(acc, v2_scale(contour_px[((i + j) % n + n) % n], wt[j + 2] / 9));
        contour[i] = acc;
    }
    vec2 nrm = v2(-dir.y, dir.x);
    double h_top = -INFINITY, h_bot = INFINITY;
    for (int i = 0; i < n; i++) {
        double h = v2_dot(v2_sub(contour[i], origin), dir);
        h_top = fmax(h_top, h);
        h_bot = fmin(h_bot, h);
    }
    double height = h_top - h_bot;
    int orient = signed_area(contour, n) > 0 ? 1 : -1;
    int k = (int)fmax(5, 0.01 * height);
    /* per end: the picked points, and the extreme point (pole) per side */
    int picked[2][2], poles[2][2], turned[2] = {0, 0};
    double base_aspect = 0; /* b/a of the base's ellipse where it was left tangentially, else 0 */
    int mouth_open = 0;     /* the top is an open mouth seen from above (recon_mouth_open) ... */
    double mouth[2] = {0, 0}; /* ... and its rim's ellipse */
    for (int pass = 0; pass < 2; pass++) {
        int end = 1 - pass; /* 1: bottom (base) first, 0: top (rim) */
        double h_end = end ? h_bot : h_top, sign = end ? -1 : 1;
        /* The zone: half the radius of the outline's last 5% toward this end
         * (an ellipse's half-height is r sin(elevation): up to 30 degrees). */
        double r5 = 0;
        for (int i = 0; i < n; i++) {
            vec2 q = v2_sub(contour[i], origin);
            if (sign * (v2_dot(q, dir) - h_end) >= -0.05 * height)
                r5 = fmax(r5, fabs(v2_dot(q, nrm)));
        }
        double zone = 0.5 * r5 + 3;
        /* Seen from above, the rim's ellipse is no rounder than the base's
         * (the rim is seen less steeply), and a wall that flares out of it
         * leaves it on its near half, down to twice its half-height below
         * the top: where the base's ellipse is measured, the top's zone
         * reaches that deep. */
        if (end == 0)
            zone = fmax(zone, 2 * fmin(base_aspect, 0.5) * r5 + 3);
        /* An open mouth seen from above shows its rim's near arc: the rim's
         * ellipse is measured on the outline's top, and the wall leaves it
         * down to twice its half-height below the top (the last 5% of the
         * height can be a small part of a wide far arc: a bowl seen from
         * 25 degrees, whose rim's ends lay 59 px deep, the zone 41). */
        if (end == 0 && (mouth_open = recon_mouth_open(img, contour, n, origin, dir, h_end, zone, mouth)))
            zone = fmax(zone, 2 * mouth[1] + 3);
        /* The rim (base) is a circle: both sides turn at the same height. Per
         * 1 px bin of height in the zone and per side, the sharpest turn; the
         * corners are the pair at the height where the weaker of the two
         * sides (each the best within 2 px, a tilt's worth) turns most. */
        int nb = (int)ceil(zone) + 1, m = 0;
        double *bt = malloc((size_t)nb * 5 * sizeof *bt), *bw = bt + 2 * nb, *br = bw + nb;
        int *bi = malloc((size_t)nb * 4 * sizeof *bi), *bo = bi + 2 * nb, pole[2] = {-1, -1};
        if (!bt || !bi) {
            free(bt);
            free(bi);
            free(turns);
            free(contour);
            free(zp);
            return -1;
        }
        for (int b = 0; b < 2 * nb; b++) {
            bt[b] = br[b] = -INFINITY;
            bi[b] = bo[b] = -1;
        }
        double ph[2] = {-INFINITY, -INFINITY};
        for (int i = 0; i < n; i++) {
            vec2 q = v2_sub(contour[i], origin);
            double h = v2_dot(q, dir), r = v2_dot(q, nrm), depth = sign * (h_end - h);
            if (depth > zone || r == 0)
                continue;
            int s = r > 0, b = (int)floor(depth < 0 ? 0 : depth);
            if (sign * h > ph[s]) {
                ph[s] = sign * h;
                pole[s] = i;
            }
            double t = turn_at(contour, n, i, k, orient);
            zp[m] = (end_point){r, depth, i};
            turns[m++] = fabs(t);
            if (b < nb && t > bt[s * nb + b]) {
                bt[s * nb + b] = t;
                bi[s * nb + b] = i;
            }
            if (b < nb && fabs(r) > br[s * nb + b]) { /* the outermost point per bin and side */
                br[s * nb + b] = fabs(r);
                bo[s * nb + b] = i;
            }
        }
        for (int b = 0; b < nb; b++) /* the half-width per bin where both sides have a point */
            bw[b] = bo[b] >= 0 && bo[nb + b] >= 0 ? 0.5 * (br[b] + br[nb + b]) : -1;
        /* The corners are where the outline turns onto the rim's (base's)
         * ellipse: the pair at the height where the weaker side turns
         * most. But a chamfer or a rounded foot turns twice, onto the
         * ellipse and again onto the wall above it, and the upper turn may
         * be the sharper (the chords see the lower one half on the
         * ellipse's own curve); the base is the lower, the bevel part of
         * the wall. So of the runs of bins whose score passes the bar, the
         * first from the end wins over the sharpest when it lies within a
         * bevel's inset of it (a bump on the near arc of a base seen from
         * above, far inside the arc's ends, does not). Ties: the bin
         * nearest the end. */
        double bar = m > 0 ? fmax(CORNER_MIN_TURN, CORNER_PEAK_RATIO * gsl_stats_median(turns, 1, (size_t)m))
                           : CORNER_MIN_TURN;
        int best_b = -1, pick[2] = {-1, -1}, first_b = -1, first_pick[2] = {-1, -1}, first_done = 0;
        double best = -INFINITY, first = -INFINITY;
        for (int b = 0; b < nb; b++) {
            double side_best[2] = {-INFINITY, -INFINITY};
            int side_pick[2] = {-1, -1};
            for (int s = 0; s < 2; s++)
                for (int c = b - 2; c <= b + 2; c++)
                    if (c >= 0 && c < nb && bt[s * nb + c] > side_best[s]) {
                        side_best[s] = bt[s * nb + c];
                        side_pick[s] = bi[s * nb + c];
                    }
            double score = fmin(side_best[0], side_best[1]);
            if (score < bar) {
                first_done |= first_b >= 0;
                continue;
            }
            if (!first_done && score > first + 1e-9) {
                first = score;
                first_b = b;
                first_pick[0] = side_pick[0], first_pick[1] = side_pick[1];
            }
            if (score > best + 1e-9) {
                best = score;
                best_b = b;
                pick[0] = side_pick[0], pick[1] = side_pick[1];
            }
        }
        if (first_b >= 0 && first_b != best_b &&
            pick_half_width(zp, m, first_pick) >= (1 - BEVEL_MAX_INSET) * pick_half_width(zp, m, pick)) {
            best_b = first_b;
            pick[0] = first_pick[0], pick[1] = first_pick[1];
        }
        /* The circle's ellipse is where the outline is widest near the end:
         * a rounded edge, or a wall that meets that ellipse tangentially,
         * does not turn sharply there, but the outline narrows above it. The
         * candidate: the first height, from the end, within 1 px of the
         * widest before the outline narrows by 1 px (and 1%). */
        int wide_b = -1;
        double run = -INFINITY;
        for (int b = 0, first = -1; b < nb; b++) {
            if (bw[b] < 0)
                continue;
            if (bw[b] > run + 1) {
                run = bw[b];
                first = b;
            } else if (bw[b] > run) {
                run = bw[b];
            } else if (bw[b] < run - fmax(1.0, 0.01 * run)) {
                wide_b = first;
                break;
            }
        }
        /* A widest point nearer the end than the corner, with the outline
         * narrowing between the two, is a foot ring (lip) below (above) the
         * corner: it ends the vessel. Neither a corner nor a widest point:
         * the end's ellipse left tangentially by the wall (seen from above or
         * below), else the outline only widens from the end (a dome), and its
         * pole ends it. */
        int ring = 0;
        if (wide_b >= 0 && best_b > wide_b + 2)
            for (int b = wide_b + 1; b < best_b && !ring; b++)
                ring = bw[b] >= 0 && bw[b] < bw[wide_b] - fmax(1.0, 0.01 * bw[wide_b]);
        turned[end] = best_b >= 0;
        if (wide_b >= 0 && (best_b < 0 || ring)) {
            pick[0] = bo[wide_b];
            pick[1] = bo[nb + wide_b];
            turned[end] = 0;
        } else if (best_b < 0 && ellipse_corners(zp, m, zone, pick, end && !base_is_cut ? &base_aspect : NULL) != 0) {
            pick[0] = pole[0];
            pick[1] = pole[1];
        }
        /* An open mouth's rim is its ellipse: corners picked above its ends
         * on its back arc, would make that arc profile; they are where the
         * outline leaves the ellipse instead, on each side. */
        if (end == 0 && mouth_open && pick_depth(contour, origin, dir, h_end, pick) < 0.75 * mouth[1] &&
            leave_ellipse(zp, m, mouth, pick) == 0)
            turned[end] = 0;
        for (int s = 0; s < 2; s++) {
            picked[end][s] = pick[s];
            poles[end][s] = pole[s];
        }
        free(bt);
        free(bi);
    }
    /* A rim seen from an elevation e is an ellipse whose ends lie r sin(e)
     * below the outline's top; the base's ellipse lies as deep, or deeper by
     * a foot ring's height: depth / r at the base bounds sin(e) from above.
     * A top picked deeper than that ratio allows (within 2 px of measurement
     * at the base scaled by the radii, and 3 px of its own) is no rim but a
     * dome, a knob's rounded top: its pole. Not where a stand or a shadow
     * has cut the base, whose depth then says nothing of the camera; nor
     * at an open mouth (recon_mouth_open): its rim is the ellipse it shows.
     * The base's points lie on its ellipse's near half when the wall widens
     * upward from the base, the rim's below its ends when the wall flares
     * out of it, and a bowl seen from 20 degrees above was closed into a
     * dome by this bound. */
    double depth[2], rad[2];
    for (int end = 0; end < 2; end++) {
        double h_end = end ? h_bot : h_top;
        depth[end] = rad[end] = 0;
        for (int s = 0; s < 2; s++)
            if (picked[end][s] >= 0) {
                vec2 q = v2_sub(contour[picked[end][s]], origin);
                depth[end] += 0.5 * fabs(h_end - v2_dot(q, dir));
                rad[end] += 0.5 * fabs(v2_dot(q, nrm));
            }
    }
    if (!base_is_cut && !mouth_open && rad[0] > 1 && rad[1] > 1 && poles[0][0] >= 0 && poles[0][1] >= 0 &&
        depth[0] > rad[0] * depth[1] / rad[1] + 2 * rad[0] / rad[1] + 3) {
        for (int s = 0; s < 2; s++)
            picked[0][s] = poles[0][s];
        turned[0] = 0;
    }
    for (int end = 0; end < 2; end++)
        for (int s = 0; s < 2; s++) {
            int q = end ? (s ? CORNER_BASE_RIGHT : CORNER_BASE_LEFT) : (s ? CORNER_RIM_RIGHT : CORNER_RIM_LEFT);
            double h_end = end ? h_bot : h_top;
            corners[q] = picked[end][s] >= 0 ? contour_px[picked[end][s]] : v2_add(origin, v2_scale(dir, h_end));
            /* A turn's pick is a pixel centre on the ellipse's side of the
             * junction; a base cut by a stand or a shadow meets no ellipse. */
            if (turned[end] && picked[end][s] >= 0 && !(end && base_is_cut))
                recon_corner_knot(outline[s], n_outline[s], origin, dir, !end, k, &corners[q]);
        }
    free(turns);
    free(contour);
    free(zp);
    return 0;
}
