/* recon_corner_knot: a corner picked on the pixel contour, found again on the
 * sub-pixel outline of its side.
 *
 * The wall's silhouette meets the end circle's ellipse tangentially (caps.c),
 * and near its end the ellipse bends toward the axis at its curvature a / b^2,
 * a pixel or two in radius from a camera near level: in the end's frame (u
 * along the axis from the picked point toward the wall, r across it) the
 * outline is the wall's line on the wall side of the junction, and there the
 * ellipse leaves that line as a parabola,
 *     |r| = p0 + p1 u + c (u_c - u)_+^2,  c < 0,
 * a quadratic spline with one knot: the corner. For a given knot the fit is
 * linear least squares; the knot is scanned in KNOT_STEP px steps for the
 * least squared residual and kept when the spline explains the window better
 * than the wall's line alone by an F-test (as caps.c's change point). The
 * pixel contour's corner is a pixel centre that the chords' turn pulls past
 * the junction onto the ellipse (the turn keeps growing there): 1.7-3 px from
 * it on the drawn chamfer. A corner that is sharp in the image (a flat end seen
 * level) has no rows beyond it and is left as picked. */
#include <math.h>

#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit.h>

#include "recon/recon_internal.h"

#define KNOT_STEP 0.05
#define KNOT_F 20.0
#define KNOT_MIN_WALL 3 /* points on the wall's side of the knot */
#define KNOT_MIN_END 2  /* and on the end's */

/* Point i continues the run from its neighbour (one row apart, y being the
 * outline's row) within the window and on the corner's side of the axis. */
static int in_run(const vec2 *outline, int i, int from, vec2 origin, vec2 dir, vec2 nrm, double side, double h_pick,
                  double window)
{
    vec2 q = v2_sub(outline[i], origin);
    return fabs(outline[i].y - outline[from].y) < 1.5 && fabs(v2_dot(q, dir) - h_pick) <= window &&
           side * v2_dot(q, nrm) > 0;
}

int recon_corner_knot(const vec2 *outline, int n, vec2 origin, vec2 dir, int toward_top, double window,
                      vec2 *corner)
{
    const vec2 nrm = v2(-dir.y, dir.x);
    const double sign = toward_top ? 1 : -1, h_pick = v2_dot(v2_sub(*corner, origin), dir);
    const double side = v2_dot(v2_sub(*corner, origin), nrm) > 0 ? 1 : -1;
    /* The run of consecutive rows through the picked height, within the
     * window: the junction is only seen where the outline is measured on
     * every row (a washed-out or nearly level edge drops its rows). */
    int i0 = -1;
    for (int i = 0; i < n; i++) {
        vec2 q = v2_sub(outline[i], origin);
        double dh = fabs(v2_dot(q, dir) - h_pick);
        if (dh <= window && side * v2_dot(q, nrm) > 0 &&
            (i0 < 0 || dh < fabs(v2_dot(v2_sub(outline[i0], origin), dir) - h_pick)))
            i0 = i;
    }
    if (i0 < 0)
        return 0;
    int lo = i0, hi = i0;
    while (lo > 0 && in_run(outline, lo - 1, lo, origin, dir, nrm, side, h_pick, window))
        lo--;
    while (hi < n - 1 && in_run(outline, hi + 1, hi, origin, dir, nrm, side, h_pick, window))
        hi++;
    int m = hi - lo + 1;
    if (m < KNOT_MIN_WALL + KNOT_MIN_END) /* 5 points: one more than the spline's parameters */
        return 0;
    gsl_matrix *x = gsl_matrix_alloc((size_t)m, 3), *cov = gsl_matrix_alloc(3, 3);
    gsl_vector *u = gsl_vector_alloc((size_t)m), *r = gsl_vector_alloc((size_t)m), *p = gsl_vector_alloc(3);
    gsl_multifit_linear_workspace *work = gsl_multifit_linear_alloc((size_t)m, 3);
    int refined = 0;
    if (x && cov && u && r && p && work) {
        double u_lo = INFINITY, u_hi = -INFINITY;
        for (int i = lo, k = 0; i <= hi; i++) {
            vec2 q = v2_sub(outline[i], origin);
            double h = v2_dot(q, dir), rr = side * v2_dot(q, nrm);
            gsl_vector_set(u, (size_t)k, sign * (h_pick - h));
            gsl_vector_set(r, (size_t)k++, rr);
            u_lo = fmin(u_lo, sign * (h_pick - h));
            u_hi = fmax(u_hi, sign * (h_pick - h));
        }
        double l0, l1, c00, c01, c11, sse_line, best = INFINITY, best_uc = 0, best_p[3] = {0};
        gsl_fit_linear(u->data, 1, r->data, 1, (size_t)m, &l0, &l1, &c00, &c01, &c11, &sse_line);
        for (double uc = u_lo; uc <= u_hi; uc += KNOT_STEP) {
            int wall = 0;
            for (int k = 0; k < m; k++) {
                double t = gsl_vector_get(u, (size_t)k);
                wall += t > uc;
                gsl_matrix_set(x, (size_t)k, 0, 1);
                gsl_matrix_set(x, (size_t)k, 1, t);
                gsl_matrix_set(x, (size_t)k, 2, t < uc ? (uc - t) * (uc - t) : 0);
            }
            double sse;
            if (wall < KNOT_MIN_WALL || m - wall < KNOT_MIN_END || gsl_multifit_linear(x, r, p, cov, &sse, work) != 0)
                continue;
            if (sse < best && gsl_vector_get(p, 2) < 0) {
                best = sse;
                best_uc = uc;
                for (int j = 0; j < 3; j++)
                    best_p[j] = gsl_vector_get(p, (size_t)j);
            }
        }
        /* the knot and c are 2 parameters beyond the line's 2 */
        double f = (sse_line - best) / 2 / (fmax(best, 1e-12) / (m - 4));
        if (isfinite(best) && f > KNOT_F) {
            double h = h_pick - sign * best_uc, rr = best_p[0] + best_p[1] * best_uc;
            *corner = v2_add(origin, v2_add(v2_scale(dir, h), v2_scale(nrm, side * rr)));
            refined = 1;
        }
    }
    gsl_multifit_linear_free(work);
    gsl_vector_free(p);
    gsl_vector_free(r);
    gsl_vector_free(u);
    gsl_matrix_free(cov);
    gsl_matrix_free(x);
    return refined;
}
