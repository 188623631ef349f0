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

#include <gsl/gsl_statistics_double.h>

#include "recon/recon_internal.h"

/* A corner turns at least 20 degrees over the chords, and three times as
 * much as the outline around it does in the zone (a dome or a sphere turns
 * evenly: its end is its pole). */
#define CORNER_MIN_TURN (20 * M_PI / 180)
#define CORNER_PEAK_RATIO 3.0

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

int recon_find_caps(const vec2 *contour_px, int n, vec2 origin, vec2 dir, int base_is_cut, vec2 corners[CORNER_COUNT])
{
    double *turns = malloc((size_t)(n > 0 ? n : 1) * sizeof *turns);
    vec2 *contour = malloc((size_t)(n > 0 ? n : 1) * sizeof *contour);
    if (!turns || !contour) {
        free(turns);
        free(contour);
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
    int picked[2][2], poles[2][2];
    for (int end = 0; end < 2; end++) { /* 0: top (rim), 1: bottom (base) */
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
        int best_b = -1, pick[2] = {-1, -1};
        double best = -INFINITY;
        for (int b = 0; b < nb; b++) {
            double side_best[2];
            int side_pick[2];
            for (int s = 0; s < 2; s++) {
                side_best[s] = -INFINITY;
                side_pick[s] = -1;
                for (int c = b - 2; c <= b + 2; c++)
                    if (c >= 0 && c < nb && bt[s * nb + c] > side_best[s]) {
                        side_best[s] = bt[s * nb + c];
                        side_pick[s] = bi[s * nb + c];
                    }
            }
            double score = fmin(side_best[0], side_best[1]);
            if (score > best + 1e-9) { /* ties: the bin nearest the end */
                best = score;
                best_b = b;
                pick[0] = side_pick[0];
                pick[1] = side_pick[1];
            }
        }
        if (m > 0 && best < fmax(CORNER_MIN_TURN, CORNER_PEAK_RATIO * gsl_stats_median(turns, 1, (size_t)m)))
            best_b = -1;
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
         * corner: it ends the vessel. Neither a corner nor a widest point: the
         * outline only widens from the end (a dome), and its pole ends it. */
        int ring = 0;
        if (wide_b >= 0 && best_b > wide_b + 2)
            for (int b = wide_b + 1; b < best_b && !ring; b++)
                ring = bw[b] >= 0 && bw[b] < bw[wide_b] - fmax(1.0, 0.01 * bw[wide_b]);
        if (wide_b >= 0 && (best_b < 0 || ring)) {
            pick[0] = bo[wide_b];
            pick[1] = bo[nb + wide_b];
        } else if (best_b < 0) {
            pick[0] = pole[0];
            pick[1] = pole[1];
        }
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
     * has cut the base, whose depth then says nothing of the camera. */
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
    if (!base_is_cut && rad[0] > 1 && rad[1] > 1 && poles[0][0] >= 0 && poles[0][1] >= 0 &&
        depth[0] > rad[0] * depth[1] / rad[1] + 2 * rad[0] / rad[1] + 3)
        for (int s = 0; s < 2; s++)
            picked[0][s] = poles[0][s];
    for (int end = 0; end < 2; end++)
        for (int s = 0; s < 2; s++) {
            int q = end ? (s ? CORNER_BASE_RIGHT : CORNER_BASE_LEFT) : (s ? CORNER_RIM_RIGHT : CORNER_RIM_LEFT);
            double h_end = end ? h_bot : h_top;
            corners[q] = picked[end][s] >= 0 ? contour_px[picked[end][s]] : v2_add(origin, v2_scale(dir, h_end));
        }
    free(turns);
    free(contour);
    return 0;
}
