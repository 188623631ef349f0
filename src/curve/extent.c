/* The largest radius or height a profile curve reaches (see bspline.h). */
#include <math.h>
#include <stdlib.h>

#include "celadon/bspline.h"

/* A coordinate of one Bézier piece (r: axis 0, as |r|; h: axis 1) is a
 * cubic in s; its derivative's roots in (0, 1) are where it can peak
 * between the ends. */
static double coordinate(vec2 p, int axis) { return axis == 0 ? fabs(p.x) : p.y; }

static double piece_max(const bezier3_t *b, int axis)
{
    double v[4];
    for (int i = 0; i < 4; i++)
        v[i] = axis == 0 ? b->p[i].x : b->p[i].y;
    double m = fmax(coordinate(b->p[0], axis), coordinate(b->p[3], axis));
    /* c'(s)/3 = a s^2 + b s + c in the Bernstein form's differences. */
    double d0 = v[1] - v[0], d1 = v[2] - v[1], d2 = v[3] - v[2];
    double qa = d0 - 2 * d1 + d2, qb = 2 * (d1 - d0), qc = d0;
    double roots[2];
    int n = 0;
    if (fabs(qa) < 1e-14 * (fabs(qb) + fabs(qc) + 1e-300)) {
        if (qb != 0)
            roots[n++] = -qc / qb;
    } else {
        double disc = qb * qb - 4 * qa * qc;
        if (disc >= 0) {
            double sq = sqrt(disc);
            roots[n++] = (-qb - sq) / (2 * qa);
            roots[n++] = (-qb + sq) / (2 * qa);
        }
    }
    for (int k = 0; k < n; k++)
        if (roots[k] > 0 && roots[k] < 1)
            m = fmax(m, coordinate(bezier3_eval(b, roots[k]), axis));
    return m;
}

double bspline_largest(const bspline_t *curve, int axis)
{
    bezier3_t *pieces;
    int n = bspline_to_bezier(curve, &pieces);
    if (n < 0)
        return -1.0;
    double m = -INFINITY;
    for (int i = 0; i < n; i++)
        m = fmax(m, piece_max(&pieces[i], axis));
    free(pieces);
    return m;
}

