/* Ring placement for meshed SORs: the curvature domains at the chord and
 * normal tolerances of the angular tessellation, merged with boundaries the
 * caller keeps (see mesh_rings.h). */
#include <math.h>
#include <stdlib.h>

#include "celadon/curve_domains.h"
#include "celadon/mesh_rings.h"

/* The largest radius, bounded by the control polygon (the convex hull). */
static double max_radius(const bspline_t *profile)
{
    double rmax = 0.0;
    for (int i = 0; i < profile->n_ctrl; i++)
        rmax = fmax(rmax, fabs(profile->ctrl[i].x));
    return rmax;
}

double mesh_ring_tolerance(const bspline_t *profile, int segments)
{
    if (!profile || bspline_validate(profile) != NULL || segments < 3)
        return 0.0;
    double rmax = max_radius(profile);
    /* 1 - cos x = 2 sin^2(x/2), without the cancellation at large N. The
     * floor: finer profile chords than a few float ulps of r_max are lost
     * in the float vertices anyway (reached near N = 4500). */
    double s = sin(M_PI / (2.0 * segments));
    return rmax * fmax(2.0 * s * s, MESH_RING_TOL_FLOOR);
}

int mesh_rings(const bspline_t *profile, const double *keep, int n_keep, double tol_px, double **u, int *n)
{
    *u = NULL;
    *n = 0;
    if (!profile || bspline_validate(profile) != NULL || n_keep < 0 || (n_keep > 0 && !keep))
        return -1;
    double lo = profile->knots[0], hi = profile->knots[bspline_n_knots(profile) - 1];
    for (int i = 0; i < n_keep; i++)
        if (!(keep[i] >= lo && keep[i] <= hi) || (i > 0 && !(keep[i] > keep[i - 1])))
            return -1;
    /* The normal tolerance that goes with the chord tolerance tol = r_max (1 -
     * cos(pi/N)): 2 tol / r_max = 4 sin^2(pi/2N) ~ (pi/N)^2 radians. */
    double rmax = max_radius(profile), *dom = NULL;
    double tol_normal_deg = rmax > 0.0 ? 2.0 * tol_px / rmax * (180.0 / M_PI) : INFINITY;
    int nd = 0;
    if (curve_domains_by_curvature_variation(profile, tol_px, tol_normal_deg, &dom, &nd) != 0)
        return -1;
    double *out = malloc((size_t)(nd + n_keep) * sizeof *out);
    if (!out) {
        free(dom);
        return -1;
    }
    double eps = 1e-12 * (hi - lo);
    int i = 0, j = 0, k = 0;
    while (i < nd || j < n_keep) {
        double v = j >= n_keep || (i < nd && dom[i] <= keep[j]) ? dom[i++] : keep[j++];
        if (k == 0 || v - out[k - 1] > eps)
            out[k++] = v;
    }
    free(dom);
    *u = out;
    *n = k;
    return 0;
}
