/* Robust fit of an ellipse symmetric about the imaged axis to an arc of the
 * outline (perspective_internal.h).
 *
 * The model (u/a)^2 + ((w - w0)/b)^2 = 1 has three parameters: the image of
 * a circle coaxial with the vessel is symmetric about the imaged axis once
 * the camera frame is rectified (recon_camera.h), so its axes are aligned
 * with the frame and its centre is on u = 0. A general five-parameter conic
 * fitted to one half of a thin ellipse (the outline shows only the far half
 * of the rim and the near half of the base) is badly conditioned in exactly
 * the directions this removes.
 *
 * Start: the exact symmetric conic A u^2 + B w^2 + C w + D = 0 through three
 * points, one from each third of the arc (ordered by u), for a fixed
 * sequence of samples; the one with the most points within 1 px (Sampson
 * distance) wins, and the algebraic least-squares conic of those points
 * starts the refinement: Levenberg–Marquardt on the orthogonal distances
 * (Eberly's point-ellipse distance), iteratively reweighted with Tukey's
 * biweight at 4.685 robust sigmas. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "perspective/perspective_internal.h"

enum { RANSAC_TRIALS = 100, START_COUNT = 2, IRLS_STEPS = 100 };
#define INLIER_PX 1.0   /* consensus band of the start */
#define TUKEY_C 4.685   /* Tukey's biweight constant: 95% efficiency at the normal */
#define MAD_TO_SIGMA 1.4826
#define MIN_SIGMA_PX 0.01 /* scale floor: exact data must not shrink the band to nothing */
#define F_CURVED 20.0     /* an ellipse, not a line: F(2, m) beyond p = 1e-8 for any m over 40 */

/* Root s of F(s) = (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 - 1 (Eberly,
 * "Distance from a point to an ellipse"), bracketed by [z1 - 1, |(r0 z0,
 * z1)| - 1]; F(0) = g. F is decreasing and convex there, so Newton's method
 * from s = 0 (the point on the curve) lands, after at most one step, left
 * of the root and then approaches it from the left without overshooting;
 * a step that would leave the bracket bisects instead. Points near the
 * ellipse, the ones a fit is made of, take a few steps; the bisection
 * alone takes ~60 (and Newton from the bracket's end hundreds on thin
 * ellipses). */
static double eberly_root(double r0, double z0, double z1, double g)
{
    double n0 = r0 * z0, lo = z1 - 1, hi = g < 0 ? 0 : hypot(n0, z1) - 1, s = 0;
    for (int i = 0; i < 200; i++) {
        double q0 = n0 / (s + r0), q1 = z1 / (s + 1);
        double F = q0 * q0 + q1 * q1 - 1;
        if (F > 0)
            lo = s;
        else if (F < 0)
            hi = s;
        else
            break;
        double dF = -2 * (q0 * q0 / (s + r0) + q1 * q1 / (s + 1)), next = s - F / dF;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        double step = fabs(next - s);
        s = next;
        if (step <= 1e-15 * (1 + fabs(s)))
            break;
    }
    return s;
}

/* Nearest point (x0, x1) of x^2/e0^2 + y^2/e1^2 = 1 (e0 >= e1 > 0) to
 * (y0, y1), both coordinates >= 0; returns the distance. */
static double distance_q1(double e0, double e1, double y0, double y1, double *x0, double *x1)
{
    if (y1 > 0) {
        if (y0 > 0) {
            double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
            if (g == 0) {
                *x0 = y0, *x1 = y1;
                return 0;
            }
            double r0 = (e0 / e1) * (e0 / e1), s = eberly_root(r0, z0, z1, g);
            *x0 = r0 * y0 / (s + r0);
            *x1 = y1 / (s + 1);
            return hypot(*x0 - y0, *x1 - y1);
        }
        *x0 = 0, *x1 = e1;
        return fabs(y1 - e1);
    }
    double num = e0 * y0, den = e0 * e0 - e1 * e1;
    if (num < den) {
        double q = num / den;
        *x0 = e0 * q;
        *x1 = e1 * sqrt(1 - q * q);
        return hypot(*x0 - y0, *x1);
    }
    *x0 = e0, *x1 = 0;
    return fabs(y0 - e0);
}

double recon_ellipse_distance(double w0, double a, double b, vec2 p, vec2 *foot)
{
    double x = fabs(p.x), y = fabs(p.y - w0), f0, f1, d;
    if (a >= b)
        d = distance_q1(a, b, x, y, &f0, &f1);
    else
        d = distance_q1(b, a, y, x, &f1, &f0);
    if (foot)
        *foot = v2(copysign(f0, p.x), w0 + copysign(f1, p.y - w0));
    double q = (p.x / a) * (p.x / a) + ((p.y - w0) / b) * ((p.y - w0) / b);
    return q < 1 ? -d : d;
}

/* The three-parameter ellipse of the symmetric conic A u^2 + B w^2 + C w + D
 * = 0; 0 when it is not a real ellipse. */
static int conic_to_ellipse(const double c[4], double *w0, double *a, double *b)
{
    if (!(c[0] * c[1] > 0))
        return 0;
    *w0 = -c[2] / (2 * c[1]);
    double k = c[2] * c[2] / (4 * c[1]) - c[3];
    double a2 = k / c[0], b2 = k / c[1];
    if (!(a2 > 0 && b2 > 0))
        return 0;
    *a = sqrt(a2);
    *b = sqrt(b2);
    return isfinite(*w0) && isfinite(*a) && isfinite(*b);
}

/* The symmetric conic through three points: the vector orthogonal to the
 * rows (u^2, w^2, w, 1), by cofactors. */
static void conic_through(vec2 p, vec2 q, vec2 r, double c[4])
{
    double m[3][4] = {{p.x * p.x, p.y * p.y, p.y, 1}, {q.x * q.x, q.y * q.y, q.y, 1}, {r.x * r.x, r.y * r.y, r.y, 1}};
    for (int k = 0; k < 4; k++) {
        int col[3], n = 0;
        for (int j = 0; j < 4; j++)
            if (j != k)
                col[n++] = j;
        double det = m[0][col[0]] * (m[1][col[1]] * m[2][col[2]] - m[1][col[2]] * m[2][col[1]]) -
                     m[0][col[1]] * (m[1][col[0]] * m[2][col[2]] - m[1][col[2]] * m[2][col[0]]) +
                     m[0][col[2]] * (m[1][col[0]] * m[2][col[1]] - m[1][col[1]] * m[2][col[0]]);
        c[k] = (k & 1 ? -1 : 1) * det;
    }
}

/* MSAC cost of the ellipse: the sum over the points of min(d^2, tol^2),
 * d the Sampson distance (first-order distance to the curve). */
static double msac_cost(const vec2 *p, int n, double w0, double a, double b, double tol)
{
    double cost = 0;
    for (int i = 0; i < n; i++) {
        double du = p[i].x / a, dw = (p[i].y - w0) / b;
        double f = du * du + dw * dw - 1, g = 2 * hypot(du / a, dw / b), d = f / g;
        cost += fmin(d * d, tol * tol);
    }
    return cost;
}

/* Median of |v[0..n)| (v is reordered; a selection, not a sort). */
static double median_abs(double *v, int n)
{
    for (int i = 0; i < n; i++)
        v[i] = fabs(v[i]);
    return gsl_stats_median(v, 1, (size_t)n);
}

/* Solves the symmetric 3x3 system M x = y by Cholesky; 0 when not positive
 * definite. inv (may be NULL) receives M^-1. */
static int solve3(const double M[3][3], const double y[3], double x[3], double inv[3][3])
{
    double L[3][3] = {{0}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j <= i; j++) {
            double s = M[i][j];
            for (int k = 0; k < j; k++)
                s -= L[i][k] * L[j][k];
            if (i == j) {
                if (!(s > 0))
                    return 0;
                L[i][i] = sqrt(s);
            } else
                L[i][j] = s / L[j][j];
        }
    for (int c = -1; c < 3; c++) { /* c = -1: the system; 0..2: the columns of the inverse */
        if (c >= 0 && !inv)
            break;
        double b[3], z[3];
        for (int i = 0; i < 3; i++)
            b[i] = c < 0 ? y[i] : (i == c);
        for (int i = 0; i < 3; i++) {
            z[i] = b[i];
            for (int k = 0; k < i; k++)
                z[i] -= L[i][k] * z[k];
            z[i] /= L[i][i];
        }
        for (int i = 2; i >= 0; i--) {
            for (int k = i + 1; k < 3; k++)
                z[i] -= L[k][i] * z[k];
            z[i] /= L[i][i];
        }
        for (int i = 0; i < 3; i++) {
            if (c < 0)
                x[i] = z[i];
            else
                inv[i][c] = z[i];
        }
    }
    return 1;
}

/* The symmetric conic minimising the algebraic error over the points
 * within tol of the ellipse (w0, a, b), in coordinates centred and scaled to
 * about unit size (the smallest eigenvector of the 4x4 scatter matrix of
 * (u^2, w^2, w, 1)). Returns 1 and updates the ellipse, or 0. */
static int algebraic_fit(const vec2 *p, int n, double tol, double *w0, double *a, double *b)
{
    double S = *a + *b, wm = *w0, M[16] = {0};
    int m = 0;
    for (int i = 0; i < n; i++) {
        double du = p[i].x / *a, dw = (p[i].y - *w0) / *b;
        if (fabs(du * du + dw * dw - 1) > tol * 2 * hypot(du / *a, dw / *b))
            continue;
        double u = p[i].x / S, w = (p[i].y - wm) / S, v[4] = {u * u, w * w, w, 1};
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++)
                M[4 * j + k] += v[j] * v[k];
        m++;
    }
    if (m < 6)
        return 0;
    gsl_matrix_view A = gsl_matrix_view_array(M, 4, 4);
    gsl_vector *eval = gsl_vector_alloc(4);
    gsl_matrix *evec = gsl_matrix_alloc(4, 4);
    gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(4);
    int ok = eval && evec && ws && gsl_eigen_symmv(&A.matrix, eval, evec, ws) == 0;
    double c[4], cw0, ca, cb;
    if (ok) {
        gsl_eigen_symmv_sort(eval, evec, GSL_EIGEN_SORT_VAL_ASC);
        for (int k = 0; k < 4; k++)
            c[k] = gsl_matrix_get(evec, k, 0);
        ok = conic_to_ellipse(c, &cw0, &ca, &cb);
    }
    gsl_eigen_symmv_free(ws);
    gsl_matrix_free(evec);
    gsl_vector_free(eval);
    if (!ok)
        return 0;
    *w0 = wm + S * cw0, *a = S * ca, *b = S * cb;
    return 1;
}

/* Starts: the START_COUNT three-point conics, over stratified samples, of
 * lowest MSAC cost (1 px), each replaced by the algebraic fit to the points
 * within 1 px of it. Returns how many were found. */
static int start_fits(const vec2 *p, int n, double th[START_COUNT][3])
{
    size_t *order = malloc((size_t)n * sizeof *order);
    double *u = malloc((size_t)n * sizeof *u);
    if (!order || !u) {
        free(order);
        free(u);
        return 0;
    }
    for (int i = 0; i < n; i++)
        u[i] = p[i].x;
    gsl_sort_index(order, u, 1, (size_t)n);
    double cost[START_COUNT];
    int found = 0;
    unsigned long long state = 0x9E3779B97F4A7C15ull;
    for (int t = 0; t < RANSAC_TRIALS; t++) {
        int k[3];
        for (int s = 0; s < 3; s++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            int lo = s * n / 3, hi = (s + 1) * n / 3;
            k[s] = (int)order[lo + (int)((state >> 33) % (unsigned long long)(hi - lo))];
        }
        double c[4], cw0, ca, cb;
        conic_through(p[k[0]], p[k[1]], p[k[2]], c);
        if (!conic_to_ellipse(c, &cw0, &ca, &cb))
            continue;
        double c_new = msac_cost(p, n, cw0, ca, cb, INLIER_PX);
        /* Insert into the sorted list of the best, skipping near-duplicates. */
        int dup = 0;
        for (int i = 0; i < found && !dup; i++)
            dup = fabs(th[i][0] - cw0) < 0.5 && fabs(th[i][1] - ca) < 0.02 * ca && fabs(th[i][2] - cb) < 0.1 * cb;
        if (dup || (found == START_COUNT && c_new >= cost[found - 1]))
            continue;
        int at = found < START_COUNT ? found++ : START_COUNT - 1;
        for (; at > 0 && cost[at - 1] > c_new; at--) {
            cost[at] = cost[at - 1];
            memcpy(th[at], th[at - 1], sizeof th[at]);
        }
        cost[at] = c_new;
        th[at][0] = cw0, th[at][1] = ca, th[at][2] = cb;
    }
    free(order);
    free(u);
    for (int i = 0; i < found; i++) /* keeps the three-point conic when it fails */
        algebraic_fit(p, n, INLIER_PX, &th[i][0], &th[i][1], &th[i][2]);
    return found;
}

/* An arc and the half of the ellipse it lies on (+1 upper: w >= w0, -1
 * lower, 0 either). */
typedef struct {
    const vec2 *p;
    int n, half;
} arc;

/* Signed distance of p from the arc's half of the ellipse th = (w0, a, b),
 * positive on its convex side, and (J not NULL) its gradient in th. On the
 * right side this is the distance from the whole ellipse. A point across
 * the centre line by delta (noise on a nearly flat arc) is measured as its
 * mirror image, less 2 delta: the distance to the half, not to the other
 * half, which would let a flat ellipse of height 2b swallow the noise of a
 * straight arc. Moving the curve by a parameter step moves it along its
 * normal by dF/dtheta / |grad F| at the foot point, F = (u/a)^2 + ((w -
 * w0)/b)^2 - 1; a mirrored point also moves with w0. */
static double half_distance(const double th[3], int half, vec2 p, double J[3])
{
    double w0 = th[0], a = th[1], b = th[2], across = half * (w0 - p.y);
    vec2 m = across > 0 ? v2(p.x, 2 * w0 - p.y) : p, q;
    double d = recon_ellipse_distance(w0, a, b, m, &q);
    if (J) {
        double qu = q.x, qv = q.y - w0, gu = qu / (a * a), gv = qv / (b * b), g = hypot(gu, gv);
        J[0] = -gv / g;
        J[1] = -qu * qu / (a * a * a) / g;
        J[2] = -qv * qv / (b * b * b) / g;
        if (across > 0)
            J[0] += 2 * gv / g - 2 * half; /* the mirror moves by 2 dw0, the offset by -2 half dw0 */
    }
    return across > 0 ? d - 2 * across : d;
}

/* MSAC cost of the residuals r[0..n) (half distances): how refined
 * candidates compare. */
static double msac_cost_exact(const double *r, int n, double tol)
{
    double cost = 0;
    for (int i = 0; i < n; i++)
        cost += fmin(r[i] * r[i], tol * tol);
    return cost;
}

/* The distances r of all the points from the ellipse th and their
 * gradients J (half_distance), and the weighted sum of squares of those of
 * weight wt > 0. The sum only grows, so once it passes `limit` the pass
 * stops and returns INFINITY (r and J then incomplete). */
static double weighted_ssr(const arc *A, const double th[3], const double *wt, double limit, double *r,
                           double (*J)[3])
{
    double s = 0;
    for (int i = 0; i < A->n; i++) {
        r[i] = half_distance(th, A->half, A->p[i], J[i]);
        if (wt[i] > 0 && (s += wt[i] * r[i] * r[i]) > limit)
            return INFINITY;
    }
    return s;
}

/* Scratch arrays of a fit of n points: the residuals and gradients at the
 * current parameters (r, J) and at a trial step (r_try, J_try), the
 * weights. */
typedef struct {
    double *r, *r_try, *wt;
    double (*J)[3], (*J_try)[3];
} fit_work;

/* Iteratively reweighted Levenberg–Marquardt from th: Tukey weights from
 * the current residuals (scale 1.4826 MAD), then one damped step that must
 * lower the weighted sum of squares (the distance is far from linear in the
 * parameters of a thin ellipse: undamped Gauss–Newton steps overshoot into
 * the line limit b -> 0, a -> inf). An accepted step's residuals and
 * gradients are the next round's. sigma receives the final scale. Returns
 * 1 when it converged with enough inliers, w->r then holding the
 * residuals at th. */
static int refine(const arc *A, double th[3], fit_work *w, double *sigma)
{
    int n = A->n;
    double lambda = 1e-3;
    for (int i = 0; i < n; i++)
        w->r[i] = half_distance(th, A->half, A->p[i], w->J[i]);
    for (int it = 0; it < IRLS_STEPS; it++) {
        const double *r = w->r, (*J)[3] = w->J;
        double *wt = w->wt;
        memcpy(wt, r, (size_t)n * sizeof *wt);
        *sigma = fmax(MAD_TO_SIGMA * median_abs(wt, n), MIN_SIGMA_PX);
        double c = TUKEY_C * *sigma, M[3][3] = {{0}}, g[3] = {0}, cost = 0;
        int inliers = 0;
        for (int i = 0; i < n; i++) {
            double q = fabs(r[i]) < c ? 1 - (r[i] / c) * (r[i] / c) : 0;
            wt[i] = q * q;
            inliers += wt[i] > 0;
            for (int j = 0; j < 3; j++) {
                g[j] += wt[i] * J[i][j] * r[i];
                for (int k = 0; k < 3; k++)
                    M[j][k] += wt[i] * J[i][j] * J[i][k];
            }
        }
        if (inliers < 6)
            return 0;
        for (int i = 0; i < n; i++)
            if (wt[i] > 0)
                cost += wt[i] * r[i] * r[i];
        double next[3], moved = 0;
        int accepted = 0;
        for (int tries = 0; tries < 30 && !accepted; tries++) {
            double D[3][3], step[3];
            memcpy(D, M, sizeof D);
            for (int j = 0; j < 3; j++)
                D[j][j] *= 1 + lambda;
            if (!solve3(D, g, step, NULL))
                return 0;
            /* The decrease the linear model promises; none left: converged. */
            double promise = 0;
            for (int j = 0; j < 3; j++)
                promise += g[j] * step[j];
            if (promise <= 1e-12 * cost)
                break;
            for (int j = 0; j < 3; j++)
                next[j] = th[j] - step[j];
            if (next[1] > 0 && next[2] > 0 && weighted_ssr(A, next, wt, cost, w->r_try, w->J_try) <= cost) {
                accepted = 1;
                for (int j = 0; j < 3; j++)
                    moved = fmax(moved, fabs(step[j]));
                memcpy(th, next, sizeof next);
                double *tr = w->r, (*tJ)[3] = w->J;
                w->r = w->r_try, w->J = w->J_try;
                w->r_try = tr, w->J_try = tJ;
                lambda = fmax(lambda / 3, 1e-9);
            } else {
                lambda *= 4;
            }
        }
        if (!accepted || moved < 1e-5) /* px: far below any edge's precision */
            break;
    }
    return 1;
}

/* Inlier statistics, and standard errors from the unit-weight normal matrix
 * of the inliers. Returns 0 when too few are left. */
static int summarise(const arc *A, const double th[3], double sigma, double (*J)[3], recon_ellipse *out)
{
    double M[3][3] = {{0}}, ss = 0, dmax = 0, zero[3] = {0}, tmp[3], cov[3][3];
    int m = 0;
    for (int i = 0; i < A->n; i++) {
        double d = half_distance(th, A->half, A->p[i], J[i]);
        if (fabs(d) >= TUKEY_C * sigma)
            continue;
        m++;
        ss += d * d;
        dmax = fmax(dmax, fabs(d));
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                M[j][k] += J[i][j] * J[i][k];
    }
    if (m < 6 || !solve3(M, zero, tmp, cov))
        return 0;
    double s2 = ss / (m - 3);
    *out = (recon_ellipse){.w0 = th[0], .a = th[1], .b = th[2], .n_points = A->n, .n_inliers = m};
    out->rms_px = sqrt(ss / m);
    out->max_px = dmax;
    out->sigma_w0 = sqrt(s2 * cov[0][0]);
    out->sigma_a = sqrt(s2 * cov[1][1]);
    out->sigma_b = sqrt(s2 * cov[2][2]);
    return 1;
}

/* Whether the ellipse explains its inliers significantly better than the
 * line w = const through them: the F statistic of its two extra parameters
 * over F_CURVED. */
static int curved(const arc *A, const double th[3], double sigma)
{
    double ssr = 0, sw = 0, sww = 0;
    int m = 0;
    for (int i = 0; i < A->n; i++) {
        double d = half_distance(th, A->half, A->p[i], NULL);
        if (fabs(d) >= TUKEY_C * sigma)
            continue;
        ssr += d * d, sw += A->p[i].y, sww += A->p[i].y * A->p[i].y;
        m++;
    }
    double ssr_line = m > 0 ? sww - sw * sw / m : 0;
    return m > 6 && (ssr_line - ssr) / 2 > F_CURVED * ssr / (m - 3);
}

/* The line w = w0 through the points (a degenerate ellipse): robust mean
 * (within 3 robust sigmas of the median); r: n doubles of work. */
static void fit_line(const vec2 *p, int n, double *r, recon_ellipse *e)
{
    for (int i = 0; i < n; i++)
        r[i] = p[i].y;
    double med = gsl_stats_select(r, 1, (size_t)n, (size_t)n / 2); /* the upper median */
    for (int i = 0; i < n; i++)
        r[i] = p[i].y - med;
    double sigma = fmax(MAD_TO_SIGMA * median_abs(r, n), MIN_SIGMA_PX), sum = 0, umax = 0, ss = 0, dmax = 0;
    int m = 0;
    for (int i = 0; i < n; i++)
        if (fabs(p[i].y - med) <= 3 * sigma)
            sum += p[i].y, m++;
    double w0 = m ? sum / m : med;
    for (int i = 0; i < n; i++)
        if (fabs(p[i].y - med) <= 3 * sigma) {
            double d = p[i].y - w0;
            ss += d * d;
            dmax = fmax(dmax, fabs(d));
            umax = fmax(umax, fabs(p[i].x));
        }
    *e = (recon_ellipse){.w0 = w0, .a = umax, .b = 0, .n_points = n, .n_inliers = m};
    e->rms_px = m ? sqrt(ss / m) : 0;
    e->max_px = dmax;
    e->sigma_w0 = m > 1 ? sqrt(ss / (m - 1) / m) : INFINITY;
    e->sigma_a = INFINITY;
    e->sigma_b = e->sigma_w0;
}

int recon_fit_axis_ellipse(const vec2 *pts, int n, int half, recon_ellipse *out)
{
    return recon_fit_axis_ellipse_within(pts, n, half, INFINITY, out);
}

int recon_fit_axis_ellipse_within(const vec2 *pts, int n, int half, double a_max, recon_ellipse *out)
{
    memset(out, 0, sizeof *out);
    if (n < 6)
        return -1;
    double *r = malloc(3 * (size_t)n * sizeof *r), (*J)[3] = malloc(2 * (size_t)n * sizeof *J);
    if (!r || !J) {
        free(r);
        free(J);
        return -1;
    }
    /* Each start is refined; the result of lowest MSAC cost wins (the
     * orthogonal distance has local minima along thin arcs). */
    arc A = {pts, n, half};
    double starts[START_COUNT][3], th[3] = {0, 1, 1}, sigma = 0, best = INFINITY;
    int n_starts = start_fits(pts, n, starts), ok = 0;
    for (int k = 0; k < n_starts; k++) {
        double s_k;
        fit_work w = {r, r + n, r + 2 * (size_t)n, J, J + n};
        if (!refine(&A, starts[k], &w, &s_k))
            continue;
        double c = msac_cost_exact(w.r, n, INLIER_PX);
        if (c < best) {
            best = c, sigma = s_k, ok = 1;
            memcpy(th, starts[k], sizeof th);
        }
    }
    ok = ok && summarise(&A, th, sigma, J, out) && curved(&A, th, sigma) && out->a <= a_max;
    /* No ellipse, or no significant curvature: the arc is a line (a level
     * orthographic view, or a circle at the camera's height). */
    if (!ok)
        fit_line(pts, n, r, out);
    free(r);
    free(J);
    return 0;
}
