/* The camera from the imaged axis and the imaged base and rim circles
 * (recon_camera.h; the geometry is in docs/algorithms-recon.md,
 * "Perspective").
 *
 * In the camera frame (rectified so that the imaged axis passes through the
 * principal point, origin there, w up the axis) every imaged cross-section
 * is an ellipse symmetric about u = 0, and the vanishing line of the
 * cross-section planes is a line w = w_h. Two such ellipses meet in four
 * complex points: two conjugate pairs, each on a line w = const; one pair
 * is the image of the circular points, and the image of the absolute conic,
 * (u^2 + w^2 + f^2 = 0 for square pixels and this principal point), passes
 * through them: f^2 = k^2 - w_h^2 for the pair u = +-i k, w = w_h. The
 * elevation of the optical axis is then atan(w_h / f). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_statistics_double.h>

#include "perspective/perspective_internal.h"

#define DEG (180.0 / M_PI)
/* The focal length from the ellipses is used when its standard error is
 * under a third of it (1/f three sigmas from 0, the orthographic limit). */
#define MAX_REL_SIGMA_F (1.0 / 3.0)
/* Floor of an ellipse parameter's standard error in the circle fit, px. */
#define MIN_SIGMA_PX 0.02
/* Fields of view across the image that a photo of a vessel can have. */
#define MIN_FOV_DEG 1.0
#define MAX_FOV_DEG 120.0
/* An arc is its circle's image unless its ellipse misses it by more than
 * ARC_NOISE_RATIO times its edge noise and more than ARC_MISFIT_PX. */
#define ARC_NOISE_RATIO 3.0
#define ARC_MISFIT_PX 2.33
#define PITCH_STEP (0.25 / DEG)
#define PITCH_LIMIT (60.0 / DEG)
/* 35 mm film frame diagonal, mm (36 x 24). */
#define FRAME_35MM_DIAGONAL 43.2666153055679

double recon_focal_from_fov(int width, double fov_deg) { return 0.5 * width / tan(0.5 * fov_deg / DEG); }

double recon_focal_from_35mm(int width, int height, double focal_35mm)
{
    return focal_35mm * hypot(width, height) / FRAME_35MM_DIAGONAL;
}

/* ------------------------------------------------------------------ frames */

static vec2 homog(const double H[9], vec2 p)
{
    double x = H[0] * p.x + H[1] * p.y + H[2], y = H[3] * p.x + H[4] * p.y + H[5];
    double z = H[6] * p.x + H[7] * p.y + H[8];
    return v2(x / z, y / z);
}

static void invert3(const double A[9], double B[9])
{
    B[0] = A[4] * A[8] - A[5] * A[7], B[1] = A[2] * A[7] - A[1] * A[8], B[2] = A[1] * A[5] - A[2] * A[4];
    B[3] = A[5] * A[6] - A[3] * A[8], B[4] = A[0] * A[8] - A[2] * A[6], B[5] = A[2] * A[3] - A[0] * A[5];
    B[6] = A[3] * A[7] - A[4] * A[6], B[7] = A[1] * A[6] - A[0] * A[7], B[8] = A[0] * A[4] - A[1] * A[3];
    double det = A[0] * B[0] + A[1] * B[3] + A[2] * B[6];
    for (int i = 0; i < 9; i++)
        B[i] /= det;
}

static vec2 frame_right(const recon_camera *cam) { return v2(-cam->up.y, cam->up.x); }

vec2 recon_camera_to_frame(const recon_camera *cam, vec2 p)
{
    vec2 q = v2_sub(homog(cam->rectify, p), cam->origin);
    return v2(v2_dot(q, frame_right(cam)), v2_dot(q, cam->up));
}

vec2 recon_camera_to_image(const recon_camera *cam, vec2 f)
{
    vec2 q = v2_add(cam->origin, v2_add(v2_scale(frame_right(cam), f.x), v2_scale(cam->up, f.y)));
    return homog(cam->unrectify, q);
}

static int perspective(const recon_camera *cam) { return cam->focal_px > 0; }

/* The camera sits at (0, 0, -D), D = f; its right axis is X, its up axis
 * (0, cos e, sin e) and its optical axis (0, -sin e, cos e), e the pitch. */
vec2 recon_camera_frame_of(const recon_camera *cam, vec3 p)
{
    double c = cos(cam->pitch), s = sin(cam->pitch);
    if (!perspective(cam))
        return v2(p.x, p.y * c + p.z * s);
    double f = cam->focal_px, vz = p.z + f;
    double yc = p.y * c + vz * s, zc = -p.y * s + vz * c;
    return v2(f * p.x / zc, f * yc / zc);
}

ray3 recon_camera_ray(const recon_camera *cam, vec2 q)
{
    double c = cos(cam->pitch), s = sin(cam->pitch);
    if (!perspective(cam))
        return (ray3){v3(q.x, q.y * c, q.y * s), v3(0, -s, c)};
    double f = cam->focal_px;
    return (ray3){v3(0, 0, -f), v3(q.x, q.y * c - f * s, q.y * s + f * c)};
}

/* Identity rectification (the orthographic frame): origin and up given. */
static void set_frame_identity(recon_camera *cam, vec2 origin, vec2 up)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(cam->rectify, I, sizeof I);
    memcpy(cam->unrectify, I, sizeof I);
    cam->origin = origin;
    cam->up = up;
}

/* The perspective frame for focal length f: the rotation about the optical
 * centre that brings the plane through the centre and the imaged axis onto
 * the optical axis (Rodrigues), as the homography K R K^-1; origin at the
 * principal point, up along the rectified axis. */
static void set_frame_perspective(recon_camera *cam, const recon_result *res, double f)
{
    vec2 c = cam->principal_point, p0 = res->axis_origin, p1 = v2_add(p0, v2_scale(res->axis_direction, 100));
    vec3 r0 = v3((p0.x - c.x) / f, (p0.y - c.y) / f, 1), r1 = v3((p1.x - c.x) / f, (p1.y - c.y) / f, 1);
    vec3 n = v3_norm(v3_cross(r0, r1)), m = v3_norm(v3(n.x, n.y, 0));
    vec3 k = v3_cross(n, m);
    double sn = v3_len(k), cs = v3_dot(n, m), R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (sn > 1e-15) {
        k = v3_scale(k, 1 / sn);
        double K[9] = {0, -k.z, k.y, k.z, 0, -k.x, -k.y, k.x, 0}, K2[9];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                K2[3 * i + j] = 0;
                for (int l = 0; l < 3; l++)
                    K2[3 * i + j] += K[3 * i + l] * K[3 * l + j];
            }
        for (int i = 0; i < 9; i++)
            R[i] += sn * K[i] + (1 - cs) * K2[i];
    }
    /* H = K R K^-1 with K = [f 0 cx; 0 f cy; 0 0 1]. */
    double Kin[9] = {1 / f, 0, -c.x / f, 0, 1 / f, -c.y / f, 0, 0, 1}, RK[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            RK[3 * i + j] = 0;
            for (int l = 0; l < 3; l++)
                RK[3 * i + j] += R[3 * i + l] * Kin[3 * l + j];
        }
    for (int j = 0; j < 3; j++) {
        double a = RK[j], b = RK[3 + j], z = RK[6 + j];
        cam->rectify[j] = f * a + c.x * z;
        cam->rectify[3 + j] = f * b + c.y * z;
        cam->rectify[6 + j] = z;
    }
    invert3(cam->rectify, cam->unrectify);
    cam->origin = c;
    cam->up = v2_norm(v2_sub(homog(cam->rectify, p1), homog(cam->rectify, p0)));
}

/* ------------------------------------------------------------------ circles */

void recon_circle_image(const recon_camera *cam, double y, double r, double out[3])
{
    double wn = recon_camera_frame_of(cam, v3(0, y, -r)).y, wf = recon_camera_frame_of(cam, v3(0, y, r)).y;
    out[0] = 0.5 * (wn + wf);
    out[2] = 0.5 * fabs(wf - wn);
    if (!perspective(cam)) {
        out[1] = r;
        return;
    }
    /* The widest point: u = f r cos(phi) / (z0 + rho sin(phi)) is largest at
     * sin(phi) = -rho / z0, where it is f r / sqrt(z0^2 - rho^2). */
    double f = cam->focal_px, z0 = f * cos(cam->pitch) - y * sin(cam->pitch), rho = r * cos(cam->pitch);
    out[1] = z0 > rho ? f * r / sqrt(z0 * z0 - rho * rho) : INFINITY;
}

/* Weighted squared misfit of the circle (y, r) to the ellipse. */
static double circle_misfit(const recon_camera *cam, double y, double r, const double obs[3], const double sig[3],
                            double res[3])
{
    double pred[3];
    recon_circle_image(cam, y, r, pred);
    double s = 0;
    for (int k = 0; k < 3; k++) {
        res[k] = (pred[k] - obs[k]) / sig[k];
        s += res[k] * res[k];
    }
    return isfinite(s) ? s : INFINITY;
}

double recon_circle_of_ellipse(const recon_camera *cam, const recon_ellipse *e, double *y, double *r)
{
    /* A line (b = 0) says nothing about its width: a weak pull toward its
     * half span keeps the radius determined. */
    double obs[3] = {e->w0, e->a, e->b};
    double sig[3] = {fmax(e->sigma_w0, MIN_SIGMA_PX), e->b > 0 ? fmax(e->sigma_a, MIN_SIGMA_PX) : fmax(e->a, 1),
                     fmax(e->sigma_b, MIN_SIGMA_PX)};
    double c = cos(cam->pitch), s = sin(cam->pitch), Y, R;
    if (perspective(cam)) {
        double f = cam->focal_px;
        Y = f * (e->w0 * c - f * s) / (e->w0 * s + f * c); /* the axis point imaged at w0 */
        R = e->a * (f * c - Y * s) / f;
    } else {
        Y = e->w0 / c;
        R = e->a;
    }
    if (!(R > 0) || !isfinite(Y))
        return INFINITY;
    double res[3], chi = circle_misfit(cam, Y, R, obs, sig, res);
    for (int it = 0; it < 50 && isfinite(chi); it++) {
        double J[3][2], hy = 1e-6 * (fabs(Y) + R + 1), hr = 1e-6 * (R + 1), tmp[3];
        circle_misfit(cam, Y + hy, R, obs, sig, tmp);
        for (int k = 0; k < 3; k++)
            J[k][0] = (tmp[k] - res[k]) / hy;
        circle_misfit(cam, Y, R + hr, obs, sig, tmp);
        for (int k = 0; k < 3; k++)
            J[k][1] = (tmp[k] - res[k]) / hr;
        double a00 = 0, a01 = 0, a11 = 0, g0 = 0, g1 = 0;
        for (int k = 0; k < 3; k++) {
            a00 += J[k][0] * J[k][0], a01 += J[k][0] * J[k][1], a11 += J[k][1] * J[k][1];
            g0 += J[k][0] * res[k], g1 += J[k][1] * res[k];
        }
        double det = a00 * a11 - a01 * a01;
        if (!(det > 0))
            break;
        double dy = -(a11 * g0 - a01 * g1) / det, dr = -(a00 * g1 - a01 * g0) / det, lam = 1, next = INFINITY;
        for (; lam > 1e-4; lam *= 0.5) {
            if (R + lam * dr > 0 && (next = circle_misfit(cam, Y + lam * dy, R + lam * dr, obs, sig, tmp)) <= chi)
                break;
        }
        if (!(next <= chi))
            break;
        Y += lam * dy, R += lam * dr;
        int done = chi - next < 1e-12 * (1 + chi);
        chi = circle_misfit(cam, Y, R, obs, sig, res);
        if (done)
            break;
    }
    *y = Y, *r = R;
    return chi;
}

/* ------------------------------------------------------------------ horizon */

int recon_horizon_candidates(const recon_ellipse *B, const recon_ellipse *T, double w_h[2], double f2[2])
{
    /* k^2 b_i^2 = a_i^2 ((w_h - w_i)^2 - b_i^2) for both ellipses; equating
     * the two k^2 gives a quadratic in w_h (written without dividing by b,
     * so that a line, b = 0, is a double root at itself). */
    double P = T->b * T->b * B->a * B->a, Q = B->b * B->b * T->a * T->a;
    double A2 = P - Q, A1 = -2 * (P * B->w0 - Q * T->w0);
    double A0 = P * (B->w0 * B->w0 - B->b * B->b) - Q * (T->w0 * T->w0 - T->b * T->b);
    double roots[2];
    int nr = 0;
    if (fabs(A2) <= 1e-14 * (P + Q)) {
        if (A1 != 0)
            roots[nr++] = -A0 / A1;
    } else {
        /* a line's double root comes out with a discriminant of rounding
         * size, either sign */
        double disc = A1 * A1 - 4 * A2 * A0;
        if (disc < 0 && disc > -1e-9 * A1 * A1)
            disc = 0;
        if (disc >= 0) {
            double q = -0.5 * (A1 + copysign(sqrt(disc), A1)); /* no cancellation */
            roots[nr++] = q / A2;
            if (q != 0)
                roots[nr++] = A0 / q;
        }
    }
    const recon_ellipse *E = B->b / fmax(B->a, 1e-300) >= T->b / fmax(T->a, 1e-300) ? B : T;
    int n = 0;
    for (int i = 0; i < nr && E->b > 0; i++) {
        double x = roots[i];
        double k2 = E->a * E->a * ((x - E->w0) * (x - E->w0) - E->b * E->b) / (E->b * E->b);
        double f = k2 - x * x;
        /* outside both ellipses; on a line (b = 0), a circle at the
         * camera's height, is outside too: the horizon is that line */
        int outside = ((x - B->w0) * (x - B->w0) > B->b * B->b || B->b == 0) &&
                      ((x - T->w0) * (x - T->w0) > T->b * T->b || T->b == 0);
        if (f > 0 && outside && isfinite(f)) {
            w_h[n] = x;
            f2[n++] = f;
        }
    }
    return n;
}

/* The candidate of the requested kind: the horizon between the two
 * ellipses (the camera between the base's and the rim's heights), or above
 * both (the camera above the rim). Returns 0 or -1. */
static int pick_horizon(const recon_ellipse *B, const recon_ellipse *T, int above_rim, double *w_h, double *f)
{
    double wh[2], f2[2];
    int n = recon_horizon_candidates(B, T, wh, f2);
    for (int i = 0; i < n; i++) {
        /* a horizon on a line arc (a circle at the camera's height) is
         * between, at its end */
        int between = (wh[i] - B->w0) * (wh[i] - T->w0) <= 0, above = wh[i] > B->w0 && wh[i] > T->w0;
        if (above_rim ? above : between) {
            *w_h = wh[i];
            *f = sqrt(f2[i]);
            return 0;
        }
    }
    return -1;
}

/* Standard errors of f and of the elevation atan(w_h / f) from the ellipse
 * parameters' standard errors (numerical derivatives). */
static void horizon_sigma(const recon_ellipse *B, const recon_ellipse *T, int above_rim, double *sf, double *se)
{
    double wh0, f0;
    *sf = *se = INFINITY;
    if (pick_horizon(B, T, above_rim, &wh0, &f0))
        return;
    double vf = 0, ve = 0;
    for (int k = 0; k < 6; k++) {
        recon_ellipse b = *B, t = *T;
        recon_ellipse *e = k < 3 ? &b : &t;
        double *p = k % 3 == 0 ? &e->w0 : k % 3 == 1 ? &e->a : &e->b;
        double s = k % 3 == 0 ? e->sigma_w0 : k % 3 == 1 ? e->sigma_a : e->sigma_b;
        if (k % 3 != 0 && e->b == 0)
            continue; /* a line (the F-test's choice) has w0 alone: its a and b are not fitted */
        if (!isfinite(s))
            return;
        *p += s;
        double wh, f;
        if (pick_horizon(&b, &t, above_rim, &wh, &f))
            return;
        vf += (f - f0) * (f - f0);
        ve += (atan2(wh, f) - atan2(wh0, f0)) * (atan2(wh, f) - atan2(wh0, f0));
    }
    *sf = sqrt(vf);
    *se = sqrt(ve);
}

/* ------------------------------------------------------------------ solve */

/* The misfit of the ellipses in use (bit 0: the base, bit 1: the rim). */
static double total_misfit(recon_camera *cam, double pitch, int use)
{
    double y, r, m = 0;
    cam->pitch = pitch;
    if (use & 1)
        m += recon_circle_of_ellipse(cam, &cam->base, &y, &r);
    if (use & 2)
        m += recon_circle_of_ellipse(cam, &cam->rim, &y, &r);
    return m;
}

/* The pitch that best explains the ellipses in use (as total_misfit) for
 * the camera's focal length (or the orthographic model): a scan, then golden-section search; its
 * standard error from the misfit's curvature (a chi-square in the pitch). */
static void fit_pitch(recon_camera *cam, double lo, double hi, int use, double *sigma)
{
    double best = lo, fbest = INFINITY;
    for (double p = lo; p <= hi + 1e-12; p += PITCH_STEP) {
        double v = total_misfit(cam, p, use);
        if (v < fbest)
            fbest = v, best = p;
    }
    const double g = 0.5 * (sqrt(5.0) - 1);
    double a = fmax(lo, best - PITCH_STEP), b = fmin(hi, best + PITCH_STEP);
    double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = total_misfit(cam, x1, use), f2 = total_misfit(cam, x2, use);
    for (int it = 0; it < 80 && b - a > 1e-12; it++) {
        if (f1 <= f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - g * (b - a), f1 = total_misfit(cam, x1, use);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + g * (b - a), f2 = total_misfit(cam, x2, use);
        }
    }
    double p = 0.5 * (a + b), h = 0.05 / DEG;
    double c0 = total_misfit(cam, p, use);
    double curv = (total_misfit(cam, p + h, use) - 2 * c0 + total_misfit(cam, p - h, use)) / (h * h);
    *sigma = curv > 0 ? sqrt(2 / curv) : INFINITY;
    cam->pitch = p;
}

/* The outline's own edge noise along an arc (one point per column): in
 * each run of EDGE_WINDOW successive columns the rms residual of a
 * least-squares parabola (a smooth curve is one over so few columns, to
 * well under the noise), corrected for its 3 parameters; the median over
 * the runs (the arc's steep ends are a minority). Noise correlated over a
 * few columns (JPEG blocks, anti-aliasing) is in it; a misfit of the whole
 * arc by its ellipse is not. Returns 0 when no run is whole. */
#define EDGE_WINDOW 15
static double arc_edge_noise(const vec2 *arc, int n)
{
    double *run_rms = malloc((size_t)(n > 0 ? n : 1) * sizeof *run_rms);
    int m = 0;
    for (int i = 0; run_rms && i + EDGE_WINDOW <= n; i += EDGE_WINDOW) {
        if (fabs(arc[i + EDGE_WINDOW - 1].x - arc[i].x - (EDGE_WINDOW - 1)) > 0.5)
            continue; /* a gap */
        /* y = c0 + c1 x + c2 x^2 with x centred on the run (odd powers sum to 0) */
        double S0 = EDGE_WINDOW, S2 = 0, S4 = 0, T0 = 0, T1 = 0, T2 = 0, x0 = arc[i + EDGE_WINDOW / 2].x;
        for (int k = i; k < i + EDGE_WINDOW; k++) {
            double x = arc[k].x - x0;
            S2 += x * x, S4 += x * x * x * x;
            T0 += arc[k].y, T1 += x * arc[k].y, T2 += x * x * arc[k].y;
        }
        double det = S0 * S4 - S2 * S2, c1 = T1 / S2;
        double c0 = (T0 * S4 - T2 * S2) / det, c2 = (S0 * T2 - S2 * T0) / det, ss = 0;
        for (int k = i; k < i + EDGE_WINDOW; k++) {
            double x = arc[k].x - x0, r = arc[k].y - (c0 + c1 * x + c2 * x * x);
            ss += r * r;
        }
        run_rms[m++] = sqrt(ss / (EDGE_WINDOW - 3));
    }
    double sigma = m > 0 ? gsl_stats_median(run_rms, 1, (size_t)m) : 0;
    free(run_rms);
    return sigma;
}

/* The typical distance of the arc's points from its ellipse (1.4826 times
 * the median: a chipped lip or a highlight over a few columns does not
 * count), px; INFINITY when out of memory. */
static double arc_misfit(const recon_camera *cam, const recon_ellipse *e, const vec2 *arc, int n)
{
    double *d = malloc((size_t)(n > 0 ? n : 1) * sizeof *d);
    if (!d)
        return INFINITY;
    for (int i = 0; i < n; i++)
        d[i] = e->b > 0 ? fabs(recon_ellipse_distance(e->w0, e->a, e->b, recon_camera_to_frame(cam, arc[i]), NULL))
                        : fabs(recon_camera_to_frame(cam, arc[i]).y - e->w0);
    double m = n > 0 ? 1.4826 * gsl_stats_median(d, 1, (size_t)n) : 0;
    free(d);
    return m;
}

/* Whether each arc is its circle's image as far as the photo can tell (bit
 * 0: the base, bit 1: the rim): an arc farther from its ellipse than
 * ARC_NOISE_RATIO times its own edge noise (what noise cannot explain) and
 * than ARC_MISFIT_PX (the quality gate's limit for the profile curve
 * against the outline) is some other curve, a foot that flares out of the
 * base or a shadow's edge, and its ellipse says nothing of the camera. The
 * failed arcs' errors go to note. */
static int arcs_are_ellipses(const recon_camera *cam, const vec2 *top, int n_top, const vec2 *bottom, int n_bottom,
                             char *note, size_t notelen)
{
    static const char *const names[2] = {"base", "rim"};
    const recon_ellipse *e[2] = {&cam->base, &cam->rim};
    const vec2 *arc[2] = {bottom, top};
    int n[2] = {n_bottom, n_top}, ok = 3;
    for (int k = 0; k < 2; k++) {
        double noise = arc_edge_noise(arc[k], n[k]), misfit = arc_misfit(cam, e[k], arc[k], n[k]);
        if (misfit > ARC_NOISE_RATIO * noise && misfit > ARC_MISFIT_PX) {
            ok &= ~(1 << k);
            snprintf(note, notelen,
                     "the %s arc is no ellipse: %.1f px from its fitted ellipse, %.0f times its edge noise "
                     "(%.2f px)",
                     names[k], misfit, misfit / noise, noise);
        }
    }
    return ok;
}

/* The widest a circle's image can be: the silhouette's largest half width
 * from the imaged axis, plus 2% and 2 px (the camera frame's
 * rectification). (Over the rows of an end's corners alone it would be
 * tighter, but corners found inside their arcs sit above the rim
 * ellipse's widest row.) */
static double silhouette_half_width(const recon_result *res)
{
    vec2 o = res->axis_origin, d = res->axis_direction;
    double hw = 0;
    for (int y = 0; y < res->height; y++) {
        const uint8_t *m = res->mask + (size_t)y * res->width, *a = memchr(m, 1, (size_t)res->width);
        if (!a)
            continue;
        double c = o.x + (y + 0.5 - o.y) * d.x / d.y; /* the axis on this row */
        const uint8_t *b = memrchr(m, 1, (size_t)res->width);
        hw = fmax(hw, fmax(fabs(a - m - c), fabs(b - m + 1 - c)));
    }
    return hw > 0 ? 1.02 * hw + 2 : INFINITY;
}

/* Fits both arcs in the camera's current frame, no wider than a_max
 * (silhouette_half_width). */
static int fit_arcs(recon_camera *cam, const vec2 *top, int n_top, const vec2 *bottom, int n_bottom, double a_max,
                    vec2 *work)
{
    for (int i = 0; i < n_top; i++)
        work[i] = recon_camera_to_frame(cam, top[i]);
    if (recon_fit_axis_ellipse_within(work, n_top, 1, a_max, &cam->rim)) /* the rim's upper half */
        return -1;
    for (int i = 0; i < n_bottom; i++)
        work[i] = recon_camera_to_frame(cam, bottom[i]);
    return recon_fit_axis_ellipse_within(work, n_bottom, -1, a_max, &cam->base); /* the base's lower half */
}

/* Focal length and pitch from the ellipses alone. The two candidates are
 * told apart by whether the camera looks into the mouth (the rim's near
 * half is an edge in the photo): then it is above the rim. Returns 0, or -1
 * (with the reason in cam->note) when they give no usable focal length. */
static int focal_from_ellipses(const image_t *img, recon_camera *cam, double *sigma_e)
{
    int above = recon_rim_near_arc_visible(img, cam, &cam->rim) == 1;
    double wh, f, sf, se;
    if (pick_horizon(&cam->base, &cam->rim, above, &wh, &f) != 0) {
        above = !above; /* only the other kind exists */
        if (pick_horizon(&cam->base, &cam->rim, above, &wh, &f) != 0) {
            snprintf(cam->note, sizeof cam->note,
                     "the base and rim ellipses give no focal length (too flat or inconsistent)");
            return -1;
        }
    }
    horizon_sigma(&cam->base, &cam->rim, above, &sf, &se);
    if (!(sf < MAX_REL_SIGMA_F * f)) {
        snprintf(cam->note, sizeof cam->note,
                 "the base and rim ellipses are too flat to give a focal length (%.0f +- %.0f px)", f, sf);
        return -1;
    }
    double fov = 2 * atan(0.5 * img->width / f) * DEG;
    if (!(fov >= MIN_FOV_DEG && fov <= MAX_FOV_DEG)) {
        snprintf(cam->note, sizeof cam->note,
                 "the base and rim ellipses give an implausible field of view (%.1f deg across)", fov);
        return -1;
    }
    cam->focal_px = f;
    cam->sigma_focal_px = sf;
    cam->pitch = atan2(wh, f);
    *sigma_e = se;
    return 0;
}

/* Elevation of the original optical axis and roll of the imaged axis,
 * from the rectified camera's pitch and the frame. */
static void report_angles(recon_camera *cam)
{
    cam->roll_deg = atan2(cam->up.x, -cam->up.y) * DEG;
    if (!perspective(cam)) {
        cam->elevation_deg = cam->pitch * DEG;
        return;
    }
    /* World up in the rectified camera's coordinates (x right, y down, z
     * forward): cos(e) along the frame's up, -sin(e) along the optical axis;
     * the original optical axis is R^-1 z, i.e. the back-projection of the
     * principal point through the inverse rectification. */
    double f = cam->focal_px;
    vec2 o = homog(cam->rectify, cam->principal_point);
    vec3 axis = v3_norm(v3((o.x - cam->principal_point.x) / f, (o.y - cam->principal_point.y) / f, 1));
    vec3 up = v3(cos(cam->pitch) * cam->up.x, cos(cam->pitch) * cam->up.y, -sin(cam->pitch));
    cam->elevation_deg = asin(-v3_dot(axis, up)) * DEG;
}

int recon_camera_solve(const image_t *img, const recon_result *res, const recon_camera_options *opt,
                       const vec2 *top, int n_top, const vec2 *bottom, int n_bottom, recon_camera *cam, char *err,
                       size_t errlen)
{
    memset(cam, 0, sizeof *cam);
    cam->principal_point = v2(0.5 * img->width, 0.5 * img->height);
    double f_given = 0;
    if (opt && opt->fov_deg > 0 && opt->fov_deg < 180) {
        f_given = recon_focal_from_fov(img->width, opt->fov_deg);
        cam->method = RECON_CAMERA_FLAG;
    } else if (opt && opt->focal_35mm > 0) {
        f_given = recon_focal_from_35mm(img->width, img->height, opt->focal_35mm);
        cam->method = RECON_CAMERA_EXIF;
    }
    vec2 *work = malloc((size_t)(n_top > n_bottom ? n_top : n_bottom > 0 ? n_bottom : 1) * sizeof *work);
    if (!work) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    double sigma_e = INFINITY, a_max = silhouette_half_width(res);
    int ok = 0;
    /* The rectification depends on f: repeat until f settles. A yaw moves
     * the principal point off the imaged axis by d px; a relative change
     * df/f of the focal length moves the rectified points by about
     * d (x/f)^2 df/f, x up to the half diagonal. */
    double f_rect = f_given > 0 ? f_given : 2.0 * hypot(img->width, img->height);
    vec2 d = res->axis_direction, rel = v2_sub(cam->principal_point, res->axis_origin);
    double off = fabs(v2_cross(d, rel)), half_diag = 0.5 * hypot(img->width, img->height);
    for (int it = 0; it < 6; it++) {
        set_frame_perspective(cam, res, f_rect);
        cam->focal_px = 0;
        if (fit_arcs(cam, top, n_top, bottom, n_bottom, a_max, work)) {
            free(work);
            snprintf(err, errlen, "cannot fit the outline's top and bottom arcs (%d and %d points)", n_top, n_bottom);
            return -1;
        }
        if (f_given > 0) {
            cam->focal_px = f_given;
            fit_pitch(cam, -PITCH_LIMIT, PITCH_LIMIT, 3, &sigma_e);
            ok = 1;
            break;
        }
        ok = focal_from_ellipses(img, cam, &sigma_e) == 0;
        double x = half_diag / cam->focal_px;
        if (!ok || off * x * x * fabs(cam->focal_px - f_rect) / cam->focal_px < 0.01)
            break;
        f_rect = cam->focal_px;
    }
    /* Arcs that are no ellipse give no camera: with a known focal length
     * the pitch comes from the other arc alone, else the model is
     * orthographic. */
    int arcs_ok = arcs_are_ellipses(cam, top, n_top, bottom, n_bottom, cam->note, sizeof cam->note);
    if (arcs_ok != 3 && f_given > 0 && arcs_ok != 0)
        fit_pitch(cam, -PITCH_LIMIT, PITCH_LIMIT, arcs_ok, &sigma_e);
    else if (arcs_ok != 3)
        ok = 0;
    if (!ok) {
        /* Orthographic: every circle's image has b/a = sin(e); looking down
         * is assumed (a photo of a vessel is not taken from below it). */
        cam->method = RECON_CAMERA_ORTHOGRAPHIC;
        cam->focal_px = cam->sigma_focal_px = 0;
        set_frame_identity(cam, res->axis_origin, res->axis_direction);
        if (fit_arcs(cam, top, n_top, bottom, n_bottom, a_max, work)) {
            free(work);
            snprintf(err, errlen, "cannot fit the outline's top and bottom arcs (%d and %d points)", n_top, n_bottom);
            return -1;
        }
        if (((arcs_ok & 1) && cam->base.b > 0) || ((arcs_ok & 2) && cam->rim.b > 0))
            fit_pitch(cam, 0, PITCH_LIMIT, arcs_ok, &sigma_e);
        else
            cam->pitch = 0, sigma_e = 0;
    }
    free(work);
    if (!isfinite(recon_circle_of_ellipse(cam, &cam->base, &cam->base_y, &cam->base_r)) ||
        !isfinite(recon_circle_of_ellipse(cam, &cam->rim, &cam->rim_y, &cam->rim_r)) ||
        !(cam->rim_y > cam->base_y)) {
        snprintf(err, errlen, "the base and rim ellipses do not fit circles of this camera");
        return -1;
    }
    cam->sigma_elevation_deg = sigma_e * DEG;
    report_angles(cam);
    return 0;
}
