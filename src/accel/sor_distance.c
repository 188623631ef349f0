/* Distance from a point to a closed surface of revolution. The nearest
 * surface point lies in the point's own meridian half-plane, so the 3D
 * distance is the planar distance from (rho, y) to the profile curve and the
 * cap segments. The curve part: the best of a dense sample on each Bézier
 * piece, polished by Newton on (B(s) - q) . B'(s) = 0. */
#include <stdlib.h>

#include "accel/accel_internal.h"

static vec2 bezier3_second(const bezier3_t *b, double s)
{
    vec2 a = v2_add(v2_sub(b->p[2], v2_scale(b->p[1], 2)), b->p[0]);
    vec2 c = v2_add(v2_sub(b->p[3], v2_scale(b->p[2], 2)), b->p[1]);
    return v2_scale(v2_lerp(a, c, s), 6.0);
}

static double piece_distance(const bezier3_t *b, vec2 q)
{
    enum { SAMPLES = 32 };
    double best_s = 0, best = INFINITY;
    for (int k = 0; k <= SAMPLES; k++) {
        double s = (double)k / SAMPLES, d = v2_len(v2_sub(bezier3_eval(b, s), q));
        if (d < best) {
            best = d;
            best_s = s;
        }
    }
    double s = best_s;
    for (int it = 0; it < 20; it++) {
        vec2 e = v2_sub(bezier3_eval(b, s), q), d1 = bezier3_deriv(b, s), d2 = bezier3_second(b, s);
        double f = v2_dot(e, d1), fp = v2_dot(d1, d1) + v2_dot(e, d2);
        if (!(fp > 0))
            break;
        double sn = fmin(1.0, fmax(0.0, s - f / fp));
        if (fabs(sn - s) < 1e-15)
            break;
        s = sn;
    }
    return fmin(best, v2_len(v2_sub(bezier3_eval(b, s), q)));
}

/* A lower bound on the distance from q to a piece: the distance to the box of
 * its control points, which contains it. */
static double box_distance(const bezier3_t *b, vec2 q)
{
    vec2 lo = b->p[0], hi = b->p[0];
    for (int k = 1; k < 4; k++) {
        lo = v2(fmin(lo.x, b->p[k].x), fmin(lo.y, b->p[k].y));
        hi = v2(fmax(hi.x, b->p[k].x), fmax(hi.y, b->p[k].y));
    }
    return hypot(fmax(0.0, fmax(lo.x - q.x, q.x - hi.x)), fmax(0.0, fmax(lo.y - q.y, q.y - hi.y)));
}

static double segment_distance(vec2 a, vec2 b, vec2 q)
{
    vec2 ab = v2_sub(b, a);
    double l2 = v2_dot(ab, ab), s = l2 > 0 ? fmin(1.0, fmax(0.0, v2_dot(v2_sub(q, a), ab) / l2)) : 0.0;
    return v2_len(v2_sub(v2_add(a, v2_scale(ab, s)), q));
}

double accel_sor_distance(const bspline_t *profile, double height, unsigned caps, vec3 p)
{
    vec2 c0 = profile->ctrl[0], c1 = profile->ctrl[profile->n_ctrl - 1]; /* clamped: the end points */
    double scale = height / c1.y;
    vec2 q = v2(hypot(p.x, p.z) / scale, p.y / scale);
    bezier3_t *pieces = NULL;
    int n = bspline_to_bezier(profile, &pieces);
    double d = INFINITY;
    for (int i = 0; i < n; i++)
        if (box_distance(&pieces[i], q) < d)
            d = fmin(d, piece_distance(&pieces[i], q));
    free(pieces);
    if (caps & SOR_CAP_BASE)
        d = fmin(d, segment_distance(v2(0, c0.y), c0, q));
    if (caps & SOR_CAP_MOUTH)
        d = fmin(d, segment_distance(v2(0, c1.y), c1, q));
    return d * scale;
}
