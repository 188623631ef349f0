/* Is the outline a vessel's? Checks the four corners against the shape of a
 * surface of revolution seen from the side: a flat rim and a flat base
 * (level corner pairs at the two ends of the outline) joined by side walls. */
#include <math.h>
#include <stdio.h>

#include "recon/recon_internal.h"

int recon_check_vessel(const vec2 *corners, vec2 dir, const vec2 *contour, int n, const int *ext,
                       int h, char *why, size_t len)
{
    const double tilt = atan2(dir.x, -dir.y) * 180 / M_PI;
    if (fabs(tilt) > 30) {
        snprintf(why, len, "the axis is tilted %.1f° from the image vertical (over 30°): photograph the vessel upright",
                 tilt);
        return 0;
    }
    vec2 right = v2(-dir.y, dir.x);
    double amin = INFINITY, amax = -INFINITY, bmin = INFINITY, bmax = -INFINITY;
    for (int i = 0; i < n; i++) {
        double a = v2_dot(contour[i], dir), b = v2_dot(contour[i], right);
        amin = fmin(amin, a);
        amax = fmax(amax, a);
        bmin = fmin(bmin, b);
        bmax = fmax(bmax, b);
    }
    const double extent = amax - amin;
    static const char *PAIR[2] = {"rim", "base"};
    for (int p = 0; p < 2; p++) {
        vec2 l = corners[2 * p], r = corners[2 * p + 1], lr = v2_sub(r, l);
        /* A rim (base) is a line, or an ellipse arc ending in two corners at
         * the same height, at the top (bottom) of the outline. */
        if (v2_len(lr) < fmax(3.0, 0.02 * (bmax - bmin))) {
            snprintf(why, len, "the two %s corners coincide: no flat %s", PAIR[p], PAIR[p]);
            return 0;
        }
        double level = asin(fmin(1.0, fabs(v2_dot(lr, dir)) / v2_len(lr))) * 180 / M_PI;
        if (level > 10) {
            snprintf(why, len, "the %s corners are %.0f° off level in the axis frame: no flat %s", PAIR[p], level,
                     PAIR[p]);
            return 0;
        }
        for (int s = 0; s < 2; s++) {
            double a = (v2_dot(corners[2 * p + s], dir) - amin) / extent;
            if (p == 0 ? a < 0.8 : a > 0.2) {
                snprintf(why, len, "the %s corners are at %.0f%% of the outline's height, not at its %s", PAIR[p],
                         100 * a, p == 0 ? "top" : "bottom");
                return 0;
            }
        }
    }
    /* Below a rim corner the wall goes down (a vessel's mouth is its widest
     * point near the top); on a disc, an ellipse or a rounded box the outline
     * keeps widening: at 10% of the height below both rim corners it juts out
     * by more than 0.4 of that drop. */
    const int drop = (int)fmax(3.0, 0.1 * extent);
    int widening = 0;
    for (int s = 0; s < 2; s++) {
        int j0 = (int)floor(corners[s].y), j1 = j0 + drop, sign = s ? 1 : -1;
        const int *e = ext + (size_t)s * h;
        if (j0 >= 0 && j1 < h && e[j0] >= 0 && e[j1] >= 0 && sign * (e[j1] - e[j0]) > 0.4 * drop)
            widening++;
    }
    if (widening == 2) {
        snprintf(why, len, "the outline keeps widening below the rim corners: a rounded shape, not a flat rim");
        return 0;
    }
    return 1;
}
