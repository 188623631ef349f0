/* The four outline corners (rim left/right, base left/right) from the
 * Shi–Tomasi response of the smoothed, rasterised Douglas–Peucker polygon. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

enum { WIN = 17, HALF = WIN / 2 };

/* Draws the polygon edge a-b (pixel-centre coordinates) into the window whose
 * top-left pixel is (ox, oy): one sample per half pixel, clipped first. */
static void draw_edge(float *win, int ox, int oy, vec2 a, vec2 b)
{
    double t0 = 0, t1 = 1;
    double lo[2] = {ox - 1.0, oy - 1.0}, hi[2] = {ox + WIN + 1.0, oy + WIN + 1.0};
    double p[2] = {a.x, a.y}, d[2] = {b.x - a.x, b.y - a.y};
    for (int k = 0; k < 2; k++) {
        if (fabs(d[k]) < 1e-12) {
            if (p[k] < lo[k] || p[k] > hi[k])
                return;
            continue;
        }
        double ta = (lo[k] - p[k]) / d[k], tb = (hi[k] - p[k]) / d[k];
        if (ta > tb) {
            double t = ta;
            ta = tb;
            tb = t;
        }
        t0 = fmax(t0, ta);
        t1 = fmin(t1, tb);
    }
    if (t0 > t1)
        return;
    double len = v2_len(v2_sub(b, a)) * (t1 - t0);
    int steps = (int)ceil(2 * len) + 1;
    for (int s = 0; s <= steps; s++) {
        double t = t0 + (t1 - t0) * s / steps;
        int x = (int)floor(a.x + t * d[0]) - ox, y = (int)floor(a.y + t * d[1]) - oy;
        if (x >= 0 && x < WIN && y >= 0 && y < WIN)
            win[y * WIN + x] = 1.0f;
    }
}

/* Signed turning angle of the contour at i, between the chords from i-k and
 * to i+k (positive: counterclockwise in image coordinates, y down). */
static double turning(const vec2 *c, int n, int i, int k)
{
    vec2 a = v2_sub(c[i], c[((i - k) % n + n) % n]), b = v2_sub(c[(i + k) % n], c[i]);
    return atan2(v2_cross(a, b), v2_dot(a, b));
}

/* Shi–Tomasi response of the blurred polygon raster around vertex v. */
static float vertex_response(const vec2 *poly, int m, int v)
{
    float win[WIN * WIN], tmp[WIN * WIN];
    memset(win, 0, sizeof win);
    int ox = (int)floor(poly[v].x) - HALF, oy = (int)floor(poly[v].y) - HALF;
    for (int k = 0; k < m; k++)
        draw_edge(win, ox, oy, poly[k], poly[(k + 1) % m]);
    recon_gaussian7(win, tmp, WIN, WIN);
    float best = 0;
    for (int y = HALF - 2; y <= HALF + 2; y++)
        for (int x = HALF - 2; x <= HALF + 2; x++)
            best = fmaxf(best, recon_shi_tomasi_at(win, WIN, WIN, x, y));
    return best;
}

int recon_find_corners(const vec2 *contour, int n, const int *approx_idx, int n_approx, vec2 mean, vec2 axis_up,
                       int corner_idx[CORNER_COUNT])
{
    for (int q = 0; q < CORNER_COUNT; q++)
        corner_idx[q] = -1;
    if (n < 8 || n_approx < 3)
        return 0;
    int m = n_approx;
    vec2 *poly = malloc((size_t)m * sizeof *poly);
    float *resp = malloc((size_t)m * sizeof *resp);
    if (!poly || !resp) {
        free(poly);
        free(resp);
        return 0;
    }
    for (int k = 0; k < m; k++)
        poly[k] = contour[approx_idx[k]];
    float rmax = 0;
    for (int k = 0; k < m; k++)
        rmax = fmaxf(rmax, resp[k] = vertex_response(poly, m, k));
    int found = 0;
    if (rmax <= 0)
        goto done;

    vec2 right = v2(-axis_up.y, axis_up.x);
    /* Orientation of the contour (shoelace sign): convex turns have its sign. */
    double area2 = 0;
    for (int i = 0; i < n; i++)
        area2 += v2_cross(contour[i], contour[(i + 1) % n]);
    double orient = area2 >= 0 ? 1 : -1;
    double amin = INFINITY, amax = -INFINITY;
    for (int i = 0; i < n; i++) {
        double a = v2_dot(v2_sub(contour[i], mean), axis_up);
        amin = fmin(amin, a);
        amax = fmax(amax, a);
    }
    const double tie = fmax(3.0, 0.02 * (amax - amin));
    /* Quadrant signs (up, right) in the order of the CORNER_ enum. */
    int at_q[CORNER_COUNT] = {-1, -1, -1, -1};
    const int SU[CORNER_COUNT] = {1, 1, -1, -1}, SR[CORNER_COUNT] = {-1, 1, -1, 1};
    for (int q = 0; q < CORNER_COUNT; q++) {
        /* The rim (base) corners end the outline at the top (bottom). A
         * candidate has a Shi–Tomasi response of 5% of the strongest and is a
         * convex turn of 20° or more between chords of 8 contour points
         * (rejects the pixel staircase and the vertices of smooth arcs) and
         * still 15° over 24 points (rejects small steps in the outline).
         * Among the quadrant's candidates: the highest (lowest), and within
         * 2% of the object's height of it the outermost (the end of the rim
         * or base line, or of its ellipse arc in a perspective view). */
        double top = -INFINITY;
        for (int pass = 0; pass < 2; pass++) {
            double best = -1;
            for (int k = 0; k < m; k++) {
                if (resp[k] < 0.05f * rmax || orient * turning(contour, n, approx_idx[k], 8) < 20 * M_PI / 180 ||
                    orient * turning(contour, n, approx_idx[k], 24) < 15 * M_PI / 180)
                    continue;
                vec2 d = v2_sub(poly[k], mean);
                double a = SU[q] * v2_dot(d, axis_up), b = SR[q] * v2_dot(d, right);
                if (a <= 0 || b <= 0)
                    continue;
                if (pass == 0)
                    top = fmax(top, a);
                else if (a >= top - tie && b > best) {
                    best = b;
                    at_q[q] = k;
                }
            }
        }
    }
    for (int q = 0; q < CORNER_COUNT; q++) {
        int at = at_q[q];
        if (at < 0)
            continue;
        /* Snap to the contour point of sharpest turn near the vertex. */
        int i0 = approx_idx[at], bi = i0;
        double bt = -1;
        for (int di = -6; di <= 6; di++) {
            int i = ((i0 + di) % n + n) % n;
            double t = orient * turning(contour, n, i, 4);
            if (t > bt + 1e-9) {
                bt = t;
                bi = i;
            }
        }
        corner_idx[q] = bi;
        found |= 1 << q;
    }
done:
    free(poly);
    free(resp);
    return found;
}
