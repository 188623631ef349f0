/* The geometry under recon_camera_meridian, against exact conics: the
 * point-ellipse distance against brute force, the symmetric ellipse fit on
 * exact arcs, noisy arcs with outliers and straight lines, the imaged
 * circle of a camera against projected circle points, and the horizon and
 * focal length from two imaged circles (with the second candidate that
 * explains them as well). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "perspective/perspective_internal.h"

/* Deterministic uniform and normal numbers. */
static unsigned long long rng_state = 12345;
static double uniform(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}
static double normal(void) { return sqrt(-2 * log(1 - uniform())) * cos(2 * M_PI * uniform()); }

/* Brute-force distance: the closest of 400k points on the ellipse. */
static double brute_distance(double w0, double a, double b, vec2 p)
{
    double best = INFINITY;
    for (int k = 0; k < 400000; k++) {
        double t = 2 * M_PI * k / 400000;
        best = fmin(best, hypot(p.x - a * cos(t), p.y - w0 - b * sin(t)));
    }
    return best;
}

Test(recon_camera_conic, distance_matches_brute_force)
{
    const double shapes[][3] = {{10, 300, 6}, {-40, 120, 90}, {5, 40, 160}, {0, 250, 1.5}, {3, 80, 80}};
    for (int s = 0; s < 5; s++) {
        double w0 = shapes[s][0], a = shapes[s][1], b = shapes[s][2];
        for (int k = 0; k < 40; k++) {
            double t = 2 * M_PI * uniform(), off = (uniform() - 0.5) * (k < 20 ? 4 : 0.8 * fmin(a, b));
            vec2 n = v2_norm(v2(cos(t) / a, sin(t) / b));
            vec2 p = v2_add(v2(a * cos(t), w0 + b * sin(t)), v2_scale(n, off));
            vec2 foot;
            double d = recon_ellipse_distance(w0, a, b, p, &foot), ref = brute_distance(w0, a, b, p);
            cr_assert_float_eq(fabs(d), ref, 1e-4 + 1e-6 * a, "shape %d point (%g, %g): %.9f vs %.9f", s, p.x, p.y,
                               fabs(d), ref);
            double q = (p.x / a) * (p.x / a) + ((p.y - w0) / b) * ((p.y - w0) / b);
            cr_assert(q > 1 ? d >= 0 : d <= 0, "sign: inside %d, d %g", q < 1, d);
            double on = (foot.x / a) * (foot.x / a) + ((foot.y - w0) / b) * ((foot.y - w0) / b);
            cr_assert_float_eq(on, 1.0, 1e-9, "the foot point is on the ellipse");
            cr_assert_float_eq(v2_len(v2_sub(p, foot)), fabs(d), 1e-9 * (1 + fabs(d)));
        }
    }
}

/* Points of the ellipse at angles t0..t1 (w0 + b sin t), n of them. */
static vec2 *arc(double w0, double a, double b, double t0, double t1, int n)
{
    vec2 *p = malloc((size_t)n * sizeof *p);
    for (int k = 0; k < n; k++) {
        double t = t0 + (t1 - t0) * (k + 0.5) / n;
        p[k] = v2(a * cos(t), w0 + b * sin(t));
    }
    return p;
}

Test(recon_camera_conic, exact_arcs)
{
    /* Far half of a thin rim, near half of a base, a short arc, a full
     * ellipse, and one taller than wide. */
    const double cases[][5] = {{420, 330, 7, 0.02, M_PI - 0.02},   {-400, 180, 40, M_PI + 0.05, 2 * M_PI - 0.05},
                               {100, 200, 30, 0.5, 2.2},          {0, 150, 60, 0, 2 * M_PI},
                               {-50, 40, 90, M_PI, 2 * M_PI}};
    for (int c = 0; c < 5; c++) {
        vec2 *p = arc(cases[c][0], cases[c][1], cases[c][2], cases[c][3], cases[c][4], 500);
        int half = cases[c][4] - cases[c][3] > M_PI + 0.01 ? 0 : cases[c][3] >= M_PI ? -1 : 1;
        recon_ellipse e;
        cr_assert_eq(recon_fit_axis_ellipse(p, 500, half, &e), 0);
        cr_expect_float_eq(e.w0, cases[c][0], 1e-6, "case %d: w0 %.9f", c, e.w0);
        cr_expect_float_eq(e.a, cases[c][1], 1e-6 * cases[c][1], "case %d: a %.9f", c, e.a);
        cr_expect_float_eq(e.b, cases[c][2], 1e-6, "case %d: b %.9f", c, e.b);
        cr_expect_eq(e.n_inliers, 500, "case %d", c);
        cr_expect_lt(e.rms_px, 1e-6, "case %d", c);
        free(p);
    }
}

Test(recon_camera_conic, noise_and_outliers)
{
    /* A thin far-half arc like a rim 5 degrees below the camera, 0.1 px of
     * noise, and a fifth of the points anywhere within 10 px (a highlight,
     * a decoration, a shadow). */
    const double w0 = 420, a = 330, b = 9;
    int n = 600, bad = 0;
    vec2 *p = arc(w0, a, b, 0.05, M_PI - 0.05, n);
    for (int k = 0; k < n; k++) {
        if (k % 5 == 2) {
            p[k].y += 10 * (2 * uniform() - 1);
            bad += fabs(recon_ellipse_distance(w0, a, b, p[k], NULL)) > 1;
        } else {
            p[k].y += 0.1 * normal();
        }
    }
    recon_ellipse e;
    cr_assert_eq(recon_fit_axis_ellipse(p, n, 1, &e), 0);
    cr_expect_float_eq(e.w0, w0, 0.05, "w0 %.4f", e.w0);
    cr_expect_float_eq(e.b, b, 0.05, "b %.4f", e.b);
    cr_expect_float_eq(e.a, a, 0.005 * a, "a %.3f", e.a);
    cr_expect_float_eq(e.rms_px, 0.1, 0.02, "rms of the inliers %.3f", e.rms_px);
    /* The outliers further than 1 px are left out, the rest kept. */
    cr_expect_leq(e.n_inliers, n - bad + bad / 10, "%d inliers, %d outliers", e.n_inliers, bad);
    cr_expect_geq(e.n_inliers, (n - n / 5) * 97 / 100, "%d inliers", e.n_inliers);
    /* The standard errors describe the scatter: b within 4 of them. */
    cr_expect_lt(fabs(e.b - b), 4 * e.sigma_b + 1e-3, "b off by %.4f, sigma %.4f", e.b - b, e.sigma_b);
    free(p);
}

Test(recon_camera_conic, straight_line_is_a_degenerate_ellipse)
{
    int n = 400;
    vec2 *p = malloc((size_t)n * sizeof *p);
    for (int k = 0; k < n; k++)
        p[k] = v2(-200 + k, 512.25 + 0.05 * normal());
    recon_ellipse e;
    for (int half = -1; half <= 1; half += 2) {
        cr_assert_eq(recon_fit_axis_ellipse(p, n, half, &e), 0);
        cr_expect_eq(e.b, 0.0, "half %d: b %g: no curvature in a line", half, e.b);
        cr_expect_float_eq(e.w0, 512.25, 0.02);
    }
    free(p);
}

/* A perspective camera frame with the given focal length and pitch. */
static recon_camera camera(double f, double pitch_deg)
{
    recon_camera c = {0};
    c.focal_px = f;
    c.pitch = pitch_deg * M_PI / 180;
    return c;
}

Test(recon_camera_conic, circle_image_matches_projected_points)
{
    const double cfg[][4] = {{3000, 5, -300, 200}, {2500, -8, 250, 120}, {4000, 20, -700, 300}, {3000, 0, 40, 90}};
    for (int k = 0; k < 4; k++) {
        recon_camera c = camera(cfg[k][0], cfg[k][1]);
        double y = cfg[k][2], r = cfg[k][3], e[3];
        recon_circle_image(&c, y, r, e);
        double umax = -INFINITY, wmin = INFINITY, wmax = -INFINITY;
        for (int q = 0; q < 200000; q++) {
            double phi = 2 * M_PI * q / 200000;
            vec2 im = recon_camera_frame_of(&c, v3(r * cos(phi), y, r * sin(phi)));
            umax = fmax(umax, im.x), wmin = fmin(wmin, im.y), wmax = fmax(wmax, im.y);
        }
        cr_expect_float_eq(e[0], 0.5 * (wmin + wmax), 1e-3, "config %d: centre", k);
        cr_expect_float_eq(e[1], umax, 1e-3, "config %d: half width", k);
        cr_expect_float_eq(e[2], 0.5 * (wmax - wmin), 1e-3, "config %d: half height", k);
    }
}

/* Exact ellipses of a base and a rim circle seen by camera c. */
static void two_ellipses(const recon_camera *c, double yb, double rb, double yt, double rt, recon_ellipse *B,
                         recon_ellipse *T)
{
    double e[3];
    recon_circle_image(c, yb, rb, e);
    *B = (recon_ellipse){.w0 = e[0], .a = e[1], .b = e[2], .sigma_w0 = 0.01, .sigma_a = 0.01, .sigma_b = 0.01};
    recon_circle_image(c, yt, rt, e);
    *T = (recon_ellipse){.w0 = e[0], .a = e[1], .b = e[2], .sigma_w0 = 0.01, .sigma_a = 0.01, .sigma_b = 0.01};
}

Test(recon_camera_conic, horizon_from_two_circles)
{
    /* f, pitch, and the base and rim circles (height relative to the camera,
     * radius), world units of about a pixel: camera between the two, above
     * both, and level. */
    const double cfg[][6] = {
        {3000, 5, -500, 200, 300, 150}, {2841, 5, -450, 100, 60, 350}, {3400, 0, -250, 150, 250, 140},
        {2500, 15, -600, 180, -100, 220}};
    for (int k = 0; k < 4; k++) {
        recon_camera c = camera(cfg[k][0], cfg[k][1]);
        recon_ellipse B, T;
        two_ellipses(&c, cfg[k][2], cfg[k][3], cfg[k][4], cfg[k][5], &B, &T);
        double wh[2], f2[2], true_wh = cfg[k][0] * tan(cfg[k][1] * M_PI / 180);
        int n = recon_horizon_candidates(&B, &T, wh, f2), found = -1;
        for (int i = 0; i < n; i++)
            if (fabs(wh[i] - true_wh) < 1e-4 * cfg[k][0] && fabs(sqrt(f2[i]) - cfg[k][0]) < 1e-4 * cfg[k][0])
                found = i;
        cr_assert_geq(found, 0, "config %d: the true horizon is a candidate (%d found)", k, n);
        /* Whether the horizon separates the ellipses says whether the
         * camera is between the circles' heights. */
        int between = cfg[k][2] < 0 && cfg[k][4] > 0;
        cr_expect_eq((wh[found] - B.w0) * (wh[found] - T.w0) < 0, between, "config %d", k);
        /* The other candidate explains both ellipses exactly as well: the
         * ambiguity the mouth test resolves. */
        for (int i = 0; i < n; i++) {
            if (i == found)
                continue;
            recon_camera o = camera(sqrt(f2[i]), atan2(wh[i], sqrt(f2[i])) * 180 / M_PI);
            double y, r;
            cr_expect_lt(recon_circle_of_ellipse(&o, &B, &y, &r), 1e-6, "config %d: other candidate, base", k);
            cr_expect_lt(recon_circle_of_ellipse(&o, &T, &y, &r), 1e-6, "config %d: other candidate, rim", k);
        }
    }
}

Test(recon_camera_conic, circle_of_its_own_image)
{
    recon_camera c = camera(3000, 7);
    const double circles[][2] = {{-400, 150}, {120, 60}, {-30, 200}};
    for (int k = 0; k < 3; k++) {
        double e[3], y, r;
        recon_circle_image(&c, circles[k][0], circles[k][1], e);
        recon_ellipse el = {.w0 = e[0], .a = e[1], .b = e[2], .sigma_w0 = 0.05, .sigma_a = 0.1, .sigma_b = 0.05};
        cr_assert_lt(recon_circle_of_ellipse(&c, &el, &y, &r), 1e-8);
        cr_expect_float_eq(y, circles[k][0], 1e-5);
        cr_expect_float_eq(r, circles[k][1], 1e-5);
    }
}
