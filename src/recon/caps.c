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

int recon_find_caps(const vec2 *contour, int n, vec2 origin, vec2 dir, vec2 corners[CORNER_COUNT])
{
    double *turns = malloc((size_t)(n > 0 ? n : 1) * sizeof *turns);
    if (!turns)
        return -1;
    vec2 nrm = v2(-dir.y, dir.x);
    double h_top = -INFINITY, h_bot = INFINITY;
    for (int i = 0; i < n; i++) {
        double h = v2_dot(v2_sub(contour[i], origin), dir);
        h_top = fmax(h_top, h);
        h_bot = fmin(h_bot, h);
    }
    double height = h_top - h_bot;
    int orient = signed_area(contour, n) > 0 ? 1 : -1;
    int k = (int)fmax(3, 0.01 * height);
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
        for (int s = 0; s < 2; s++) { /* 0: left, 1: right */
            int best = -1, pole = -1, m = 0;
            double bt = -INFINITY, bh = -INFINITY, ph = -INFINITY;
            for (int i = 0; i < n; i++) {
                vec2 q = v2_sub(contour[i], origin);
                double h = v2_dot(q, dir), r = v2_dot(q, nrm);
                if (sign * (h - h_end) < -zone || (s ? r <= 0 : r >= 0))
                    continue;
                if (sign * h > ph) {
                    ph = sign * h;
                    pole = i;
                }
                double t = turn_at(contour, n, i, k, orient);
                turns[m++] = fabs(t);
                /* the sharpest turn; among equals, the one nearest the end */
                if (t > bt + 1e-9 || (fabs(t - bt) <= 1e-9 && sign * h > bh)) {
                    bt = t;
                    bh = sign * h;
                    best = i;
                }
            }
            if (m > 0 && bt < fmax(CORNER_MIN_TURN, CORNER_PEAK_RATIO * gsl_stats_median(turns, 1, (size_t)m)))
                best = pole;
            int q = end ? (s ? CORNER_BASE_RIGHT : CORNER_BASE_LEFT) : (s ? CORNER_RIM_RIGHT : CORNER_RIM_LEFT);
            corners[q] = best >= 0 ? contour[best] : v2_add(origin, v2_scale(dir, h_end));
        }
    }
    free(turns);
    return 0;
}
