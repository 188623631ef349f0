/* See vessel_size.h. */
#include "museum/vessel_size.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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

static double curve_max(const bspline_t *curve, int axis)
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

double vessel_shape_max_radius(const bspline_t *curve) { return curve_max(curve, 0); }

double vessel_shape_top(const bspline_t *curve) { return curve_max(curve, 1); }

double vessel_size_height_m(double height_cm, double diameter_cm, double shape_height, double shape_max_radius,
                            vessel_size_source *source)
{
    if (height_cm > 0) {
        *source = VESSEL_SIZE_HEIGHT;
        return height_cm / 100.0;
    }
    if (diameter_cm > 0 && shape_height > 0 && shape_max_radius > 0) {
        *source = VESSEL_SIZE_DIAMETER;
        return diameter_cm / 100.0 * shape_height / (2.0 * shape_max_radius);
    }
    *source = VESSEL_SIZE_DEFAULT;
    return MUSEUM_DEFAULT_HEIGHT_CM / 100.0;
}

void vessel_size_line(double height_cm, double diameter_cm, char *buf, size_t len)
{
    if (height_cm > 0 && diameter_cm > 0)
        snprintf(buf, len, "Height %.1f cm, diameter %.1f cm", height_cm, diameter_cm);
    else if (height_cm > 0)
        snprintf(buf, len, "Height %.1f cm", height_cm);
    else if (diameter_cm > 0)
        snprintf(buf, len, "Diameter %.1f cm; height not recorded", diameter_cm);
    else
        snprintf(buf, len, "Height not recorded");
}

const char *vessel_size_source_name(vessel_size_source s)
{
    return s == VESSEL_SIZE_HEIGHT ? "catalogue height" : s == VESSEL_SIZE_DIAMETER ? "catalogue diameter"
                                                                                    : "default (not recorded)";
}
