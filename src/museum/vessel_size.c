/* See vessel_size.h. */
#include "museum/vessel_size.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* r(s) of one Bézier piece is a cubic in s; its derivative's roots in
 * (0, 1) are where r can peak between the ends. */
static double piece_max_radius(const bezier3_t *b)
{
    double m = fmax(fabs(b->p[0].x), fabs(b->p[3].x));
    /* r'(s)/3 = a s^2 + b s + c in the Bernstein form's differences. */
    double d0 = b->p[1].x - b->p[0].x, d1 = b->p[2].x - b->p[1].x, d2 = b->p[3].x - b->p[2].x;
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
            m = fmax(m, fabs(bezier3_eval(b, roots[k]).x));
    return m;
}

double vessel_shape_max_radius(const bspline_t *curve)
{
    bezier3_t *pieces;
    int n = bspline_to_bezier(curve, &pieces);
    if (n < 0)
        return -1.0;
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fmax(m, piece_max_radius(&pieces[i]));
    free(pieces);
    return m;
}

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
