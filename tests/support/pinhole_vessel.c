/* Pinhole photographs of a solid of revolution (pinhole_vessel.h). */
#include "pinhole_vessel.h"
#include "synthdev_truth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon.h"

enum { HEIGHT_SCAN = 2048, BISECTIONS = 48, COLOUR_RAYS = 2, MARCH_STEPS = 32 };
static const double PI = 3.14159265358979323846;

typedef struct {
    vec3 loc, right, up, fwd;
    double f, cx, cy;
} camera;

static camera camera_of(const pinhole_params *p)
{
    camera c;
    double e = p->elevation_deg * PI / 180, roll = p->roll_deg * PI / 180;
    c.loc = v3_add(v3(0, p->look_at_height, 0), v3_scale(v3(0, sin(e), -cos(e)), p->distance));
    c.fwd = v3_norm(v3_sub(v3(p->look_at_side, p->look_at_height, 0), c.loc));
    vec3 r = v3_norm(v3_cross(v3(0, 1, 0), c.fwd)), u = v3_cross(c.fwd, r);
    c.right = v3_add(v3_scale(r, cos(roll)), v3_scale(u, sin(roll)));
    c.up = v3_sub(v3_scale(u, cos(roll)), v3_scale(r, sin(roll)));
    c.f = p->focal_px;
    c.cx = 0.5 * p->width;
    c.cy = 0.5 * p->height;
    return c;
}

double pinhole_radius(const pinhole_params *p, double t)
{
    if (p->radius)
        return p->radius(t);
    synth_params unit = {.shape = p->shape, .height_px = 1}; /* synth_radius reads these two */
    return synth_radius(&unit, t);
}

static vec2 project(const camera *c, vec3 q)
{
    vec3 v = v3_sub(q, c->loc);
    double zc = v3_dot(v, c->fwd);
    return v2(c->cx + c->f * v3_dot(v, c->right) / zc, c->cy - c->f * v3_dot(v, c->up) / zc);
}

vec2 pinhole_project(const pinhole_params *p, vec3 q)
{
    camera c = camera_of(p);
    return project(&c, q);
}

vec3 pinhole_camera_location(const pinhole_params *p)
{
    return camera_of(p).loc;
}

double pinhole_elevation(const pinhole_params *p)
{
    camera c = camera_of(p);
    return -asin(c.fwd.y) * 180 / PI;
}

void pinhole_frame(pinhole_params *p)
{
    double rmax = 0;
    for (int k = 0; k <= 200; k++)
        rmax = fmax(rmax, pinhole_radius(p, k / 200.0));
    p->distance = fmax(p->focal_px / (0.7 * p->height), 2 * rmax * p->focal_px / (0.7 * p->width));
}

void pinhole_profile_error(const pinhole_params *p, const bspline_t *curve, double *mean, double *max)
{
    synthdev_truth t = {.n = 2001, .height = 1};
    t.z = malloc(t.n * sizeof *t.z);
    t.r = malloc(t.n * sizeof *t.r);
    if (!t.z || !t.r) {
        *mean = *max = NAN;
        synthdev_truth_free(&t);
        return;
    }
    for (int i = 0; i < t.n; i++) {
        t.z[i] = i / 2000.0;
        t.r[i] = pinhole_radius(p, t.z[i]);
    }
    synthdev_profile_error(&t, curve, 0.03, 0.97, mean, max);
    synthdev_truth_free(&t);
}

pinhole_params pinhole_defaults(synth_shape shape, double elevation_deg)
{
    pinhole_params p;
    memset(&p, 0, sizeof p);
    p.shape = shape;
    p.width = 600;
    p.height = 800;
    p.focal_px = 2000;
    p.elevation_deg = elevation_deg;
    p.look_at_height = 0.5;
    pinhole_frame(&p);
    const float fg[3] = {0.25f, 0.42f, 0.33f}, fg2[3] = {0.80f, 0.78f, 0.62f}, bg[3] = {0.94f, 0.94f, 0.93f};
    const float mouth[3] = {0.45f, 0.60f, 0.50f};
    memcpy(p.mouth, mouth, sizeof mouth);
    memcpy(p.fg, fg, sizeof fg);
    memcpy(p.fg2, fg2, sizeof fg2);
    memcpy(p.bg, bg, sizeof bg);
    return p;
}

/* ---- outline: the union of the cross-sections' images on a line */

/* The image conic of the circle at height t: C = H^-T diag(1, 1, -R^2) H^-1
 * with H the homography from the plane's (x, z, 1) to the image. */
static void circle_conic(const camera *c, double t, double R, double C[9])
{
    vec3 col[3] = {v3(1, 0, 0), v3(0, 0, 1), v3_sub(v3(0, t, 0), c->loc)};
    double H[9];
    for (int j = 0; j < 3; j++) {
        double xc = v3_dot(col[j], c->right), yc = v3_dot(col[j], c->up), zc = v3_dot(col[j], c->fwd);
        H[j] = c->f * xc + c->cx * zc;
        H[3 + j] = -c->f * yc + c->cy * zc;
        H[6 + j] = zc;
    }
    double I[9] = {H[4] * H[8] - H[5] * H[7], H[2] * H[7] - H[1] * H[8], H[1] * H[5] - H[2] * H[4],
                   H[5] * H[6] - H[3] * H[8], H[0] * H[8] - H[2] * H[6], H[2] * H[3] - H[0] * H[5],
                   H[3] * H[7] - H[4] * H[6], H[1] * H[6] - H[0] * H[7], H[0] * H[4] - H[1] * H[3]};
    double q[3] = {1, 1, -R * R}; /* the adjugate's scale does not matter */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = I[i] * q[0] * I[j] + I[3 + i] * q[1] * I[3 + j] + I[6 + i] * q[2] * I[6 + j];
}

/* The span [x0, x1] of the conic C (a filled ellipse) on the line y; 0 when
 * it misses. */
static int conic_span(const double C[9], double y, double *x0, double *x1)
{
    double a = C[0], b = C[1] * y + C[2], k = C[4] * y * y + 2 * C[5] * y + C[8];
    if (a < 0)
        a = -a, b = -b, k = -k;
    double disc = b * b - a * k;
    if (!(disc > 0) || !(a > 0))
        return 0;
    double s = sqrt(disc);
    *x0 = (-b - s) / a;
    *x1 = (-b + s) / a;
    return 1;
}

/* The wall's contour generator at height t: the two points of the circle
 * where the surface normal, (cos phi, -R'(t), sin phi), is perpendicular to
 * the line of sight: C_x cos(phi) + C_z sin(phi) = R - R' (t - C_y), C the
 * camera. Their images, left then right; 0 when there are none. */
static int generator(const pinhole_params *p, const camera *c, double t, vec2 out[2])
{
    const double h = 1e-6;
    double t0 = fmax(0, t - h), t1 = fmin(1, t + h);
    double R = pinhole_radius(p, t), dR = (pinhole_radius(p, t1) - pinhole_radius(p, t0)) / (t1 - t0);
    double rho = hypot(c->loc.x, c->loc.z), psi = atan2(c->loc.z, c->loc.x);
    double q = (R - dR * (t - c->loc.y)) / rho;
    if (!(fabs(q) <= 1))
        return 0;
    for (int k = 0; k < 2; k++) {
        double phi = psi + (k ? 1 : -1) * acos(q);
        out[k] = project(c, v3(R * cos(phi), t, R * sin(phi)));
    }
    if (out[0].x > out[1].x) {
        vec2 tmp = out[0];
        out[0] = out[1], out[1] = tmp;
    }
    return 1;
}

/* The solid's extent on the line y. Over the discs, the image's reach on a
 * line is greatest either at a cap or where a disc's image touches the
 * envelope, i.e. on the wall's apparent contour (the generator's image,
 * tabulated at the scanned heights in gen); its crossings of the line are
 * refined by bisection in t. 0 when the line misses the solid. */
static int line_extent(const pinhole_params *p, const camera *c, const double cap[2][9], const vec2 (*gen)[2],
                       const int *ok, double y, double *xl, double *xr)
{
    *xl = INFINITY, *xr = -INFINITY;
    for (int k = 0; k < 2; k++) {
        double x0, x1;
        if (conic_span(cap[k], y, &x0, &x1))
            *xl = fmin(*xl, x0), *xr = fmax(*xr, x1);
    }
    for (int k = 0; k < HEIGHT_SCAN; k++) {
        if (!ok[k] || !ok[k + 1])
            continue;
        for (int side = 0; side < 2; side++) {
            double ya = gen[k][side].y - y, yb = gen[k + 1][side].y - y;
            if (ya * yb > 0)
                continue;
            double a = (double)k / HEIGHT_SCAN, b = (k + 1.0) / HEIGHT_SCAN, x = gen[k][side].x;
            for (int it = 0; it < BISECTIONS; it++) {
                double m = 0.5 * (a + b);
                vec2 g[2];
                if (!generator(p, c, m, g))
                    break;
                x = g[side].x;
                if ((g[side].y - y) * ya > 0)
                    a = m, ya = g[side].y - y;
                else
                    b = m;
            }
            *xl = fmin(*xl, x), *xr = fmax(*xr, x);
        }
    }
    return *xl < *xr;
}

/* ---- colour: ray casting */

/* The colour of the solid seen along the ray through image point (x, y); 0
 * when the ray misses. */
static int ray_colour(const pinhole_params *p, const camera *c, double p_rmax, double x, double y, float out[3])
{
    vec3 d = v3_add(c->fwd, v3_add(v3_scale(c->right, (x - c->cx) / c->f), v3_scale(c->up, -(y - c->cy) / c->f)));
    vec3 o = c->loc;
    double best = INFINITY;
    int part = 0; /* 0 base, 1 mouth, 2 wall */
    for (int cap = 0; cap < 2; cap++) { /* the base (y = 0) and mouth (y = 1) discs */
        double s = (cap - o.y) / d.y;
        vec3 q = v3_add(o, v3_scale(d, s));
        if (s > 0 && hypot(q.x, q.z) <= pinhole_radius(p, cap) && s < best)
            best = s, part = cap;
    }
    /* The wall: g(s) = x^2 + z^2 - R(y)^2 changes sign where the ray enters
     * it; march through the part of the ray inside the bounding cylinder
     * and the slab 0 <= y <= 1, then bisect. */
    double s0 = (0 - o.y) / d.y, s1 = (1 - o.y) / d.y;
    if (s0 > s1) {
        double tmp = s0;
        s0 = s1, s1 = tmp;
    }
    double A = d.x * d.x + d.z * d.z, B = o.x * d.x + o.z * d.z, Cc = o.x * o.x + o.z * o.z - p_rmax * p_rmax;
    double disc = B * B - A * Cc;
    if (disc <= 0 || A <= 0)
        s1 = -1;
    else {
        s0 = fmax(s0, (-B - sqrt(disc)) / A);
        s1 = fmin(s1, (-B + sqrt(disc)) / A);
    }
    s0 = fmax(s0, 0);
    double prev_s = s0, prev_g = NAN;
    for (int k = 0; k <= MARCH_STEPS && s0 < s1; k++) {
        double s = s0 + (s1 - s0) * k / MARCH_STEPS;
        vec3 q = v3_add(o, v3_scale(d, s));
        double R = pinhole_radius(p, fmin(fmax(q.y, 0), 1)), g = q.x * q.x + q.z * q.z - R * R;
        if (k > 0 && prev_g > 0 && g <= 0) {
            double a = prev_s, b = s;
            for (int it = 0; it < 30; it++) {
                double m = 0.5 * (a + b);
                vec3 qm = v3_add(o, v3_scale(d, m));
                double Rm = pinhole_radius(p, fmin(fmax(qm.y, 0), 1));
                if (qm.x * qm.x + qm.z * qm.z - Rm * Rm > 0)
                    a = m;
                else
                    b = m;
            }
            if (b < best)
                best = b, part = 2;
            break;
        }
        prev_s = s, prev_g = g;
    }
    if (!isfinite(best))
        return 0;
    const float *col = part == 1 ? p->mouth : p->fg;
    if (part == 2 && p->checker_bands > 0 && p->checker_sectors > 0) {
        vec3 q = v3_add(o, v3_scale(d, best));
        double phi = atan2(-q.z, q.x);
        phi = phi < 0 ? phi + 2 * PI : phi;
        int band = (int)floor(fmin(fmax(q.y, 0), 0.999999) * p->checker_bands);
        int sector = (int)floor(phi / (2 * PI) * p->checker_sectors);
        col = (band + sector) % 2 ? p->fg2 : p->fg;
    }
    memcpy(out, col, 3 * sizeof *out);
    return 1;
}

/* The tabulated apparent contour (HEIGHT_SCAN + 1 heights) and the caps'
 * conics. Returns 0, or -1 when out of memory. */
static int contour_table(const pinhole_params *p, const camera *c, vec2 (**gen)[2], int **ok, double cap[2][9])
{
    *gen = malloc((HEIGHT_SCAN + 1) * sizeof **gen);
    *ok = malloc((HEIGHT_SCAN + 1) * sizeof **ok);
    if (!*gen || !*ok) {
        free(*gen);
        free(*ok);
        return -1;
    }
    for (int k = 0; k < 2; k++)
        circle_conic(c, k, pinhole_radius(p, k), cap[k]);
    for (int k = 0; k <= HEIGHT_SCAN; k++)
        (*ok)[k] = generator(p, c, (double)k / HEIGHT_SCAN, (*gen)[k]);
    return 0;
}

int pinhole_line_extent(const pinhole_params *p, double y, double *x_left, double *x_right)
{
    camera c = camera_of(p);
    vec2(*gen)[2];
    int *ok;
    double cap[2][9];
    if (contour_table(p, &c, &gen, &ok, cap) != 0)
        return 0;
    int hit = line_extent(p, &c, (const double(*)[9])cap, (const vec2(*)[2])gen, ok, y, x_left, x_right);
    free(gen);
    free(ok);
    return hit;
}

/* Adds to cov the coverage of each pixel of a row by the interval [xl, xr]
 * on one of its sub-lines; widens [*lo, *hi] to the pixels touched. */
static void cover(float *cov, int W, double xl, double xr, int sub, int *lo, int *hi)
{
    for (int i = (int)fmax(0, floor(xl)); i <= (int)fmin(W - 1, floor(xr)); i++) {
        cov[i] += (float)((fmin(xr, i + 1.0) - fmax(xl, (double)i)) / sub);
        *lo = i < *lo ? i : *lo, *hi = i > *hi ? i : *hi;
    }
}

/* The average colour of the 2x2 rays of pixel (i, j) that hit the solid;
 * 0 when none does. */
static int pixel_colour(const pinhole_params *p, const camera *c, double rmax, int i, int j, float col[3])
{
    float sum[3] = {0, 0, 0}, one[3];
    int hits = 0;
    for (int a = 0; a < COLOUR_RAYS; a++)
        for (int b = 0; b < COLOUR_RAYS; b++)
            if (ray_colour(p, c, rmax, i + (a + 0.5) / COLOUR_RAYS, j + (b + 0.5) / COLOUR_RAYS, one)) {
                for (int k = 0; k < 3; k++)
                    sum[k] += one[k];
                hits++;
            }
    for (int k = 0; hits && k < 3; k++)
        col[k] = sum[k] / hits;
    return hits;
}

int pinhole_draw(const pinhole_params *p, image_t *img, uint8_t *mask)
{
    camera c = camera_of(p);
    int W = p->width, H = p->height, sub = p->subrows > 0 ? p->subrows : 24;
    int textured = p->checker_bands > 0 && p->checker_sectors > 0, mouth_seen = c.loc.y > 1;
    *img = image_alloc(W, H, 3);
    float *cov = calloc(2 * (size_t)W, sizeof *cov), *mcov = cov + W;
    vec2(*gen)[2] = NULL;
    int *ok = NULL;
    double cap[2][9], ymin = INFINITY, ymax = -INFINITY, rmax = 0;
    if (!img->data || !cov || contour_table(p, &c, &gen, &ok, cap) != 0) {
        image_free(img);
        free(cov);
        return -1;
    }
    /* The rows the vessel can reach: the images of the scanned circles. */
    for (int k = 0; k <= HEIGHT_SCAN; k += 8) {
        double t = (double)k / HEIGHT_SCAN, R = pinhole_radius(p, t);
        rmax = fmax(rmax, 1.001 * R);
        for (int q = 0; q < 64; q++) {
            vec2 im = project(&c, v3(R * cos(q * PI / 32), t, R * sin(q * PI / 32)));
            ymin = fmin(ymin, im.y), ymax = fmax(ymax, im.y);
        }
    }
    for (size_t i = 0; i < (size_t)W * H * 3; i++)
        img->data[i] = p->bg[i % 3];
    if (mask)
        memset(mask, 0, (size_t)W * H);
    for (int j = (int)fmax(0, floor(ymin) - 2); j < H && j <= ymax + 2; j++) {
        memset(cov, 0, 2 * (size_t)W * sizeof *cov);
        int lo = W, hi = -1, mlo = W, mhi = -1;
        for (int s = 0; s < sub; s++) {
            double xl, xr, y = j + (s + 0.5) / sub;
            if (line_extent(p, &c, (const double(*)[9])cap, (const vec2(*)[2])gen, ok, y, &xl, &xr))
                cover(cov, W, xl, xr, sub, &lo, &hi);
            if (mouth_seen && conic_span(cap[1], y, &xl, &xr))
                cover(mcov, W, xl, xr, sub, &mlo, &mhi);
        }
        for (int i = lo; i <= hi; i++) {
            float *px = img->data + 3 * ((size_t)j * W + i), col[3];
            float a = fminf(cov[i], 1.0f), m = fminf(mcov[i], a);
            if (textured && a > 0 && pixel_colour(p, &c, rmax, i, j, col)) {
                for (int k = 0; k < 3; k++)
                    px[k] = p->bg[k] + a * (col[k] - p->bg[k]);
            } else {
                /* One colour: the wall's and the mouth's by their coverage. */
                for (int k = 0; k < 3; k++)
                    px[k] = p->bg[k] + m * (p->mouth[k] - p->bg[k]) + (a - m) * (p->fg[k] - p->bg[k]);
            }
            if (mask)
                mask[(size_t)j * W + i] = a >= 0.5f;
        }
    }
    free(cov);
    free(gen);
    free(ok);
    return 0;
}

/* The sub-pixel outline of one side (-1 left, +1 right) on rows j0..j1. */
static int measure_side(const image_t *img, const uint8_t *mask, int j0, int j1, int side, double delta, vec2 *out)
{
    int W = img->width, H = img->height, n = 0, ext[3];
    for (int j = j0 < 1 ? 1 : j0; j <= j1 && j < H - 1; j++) {
        for (int k = 0; k < 3; k++) { /* the mask's outermost pixel on rows j-1, j, j+1 */
            const uint8_t *m = mask + (size_t)(j - 1 + k) * W;
            ext[k] = -1;
            for (int i = 0; i < W; i++)
                if (m[side > 0 ? W - 1 - i : i]) {
                    ext[k] = side > 0 ? W - 1 - i : i;
                    break;
                }
        }
        if (ext[1] < 0)
            continue;
        double slope = 0;
        for (int k = 0; k < 3; k += 2)
            if (ext[k] >= 0)
                slope = fmax(slope, fabs((double)(ext[k] - ext[1])));
        recon_signal row = {img->data + (size_t)j * W * 3, W, 3}; /* the drawn colours lie in [0, 1] */
        recon_edge e = recon_subpixel_edge(&row, ext[1], side, slope, delta);
        if (e.ok)
            out[n++] = v2(e.x, j + 0.5);
    }
    return n;
}

int pinhole_extraction(const pinhole_params *p, const image_t *img, const uint8_t *mask, recon_result *res)
{
    memset(res, 0, sizeof *res);
    camera c = camera_of(p);
    int W = img->width, H = img->height;
    vec2 base[2], rim[2];
    generator(p, &c, 0, base);
    generator(p, &c, 1, rim);
    res->width = W, res->height = H;
    res->mask_mode = RECON_MASK_GRAPH_CUT;
    res->threshold_used = -1;
    res->corners[CORNER_BASE_LEFT] = base[0], res->corners[CORNER_BASE_RIGHT] = base[1];
    res->corners[CORNER_RIM_LEFT] = rim[0], res->corners[CORNER_RIM_RIGHT] = rim[1];
    res->axis_origin = project(&c, v3(0, 0, 0));
    res->axis_direction = v2_norm(v2_sub(project(&c, v3(0, 1, 0)), res->axis_origin));
    res->tilt_deg = atan2(res->axis_direction.x, -res->axis_direction.y) * 180 / PI;
    res->side_used = RECON_SIDE_RIGHT;
    res->mask = malloc((size_t)W * H);
    for (int s = 0; s < 2; s++)
        res->silhouette[s] = malloc((size_t)H * sizeof(vec2));
    res->polyline = malloc((size_t)(H + 2) * sizeof(vec2));
    if (!res->mask || !res->silhouette[0] || !res->silhouette[1] || !res->polyline) {
        recon_result_free(res);
        return -1;
    }
    memcpy(res->mask, mask, (size_t)W * H);
    double delta = 3.0 / 255; /* recon_extract's least noise delta: the drawing has no noise */
    for (int s = 0; s < 2; s++) {
        int j0 = (int)floor(fmin(rim[s].y, base[s].y)), j1 = (int)floor(fmax(rim[s].y, base[s].y));
        res->n_silhouette[s] = measure_side(img, mask, j0, j1, s ? 1 : -1, delta, res->silhouette[s]);
    }
    /* The right outline in the axis frame, base to rim, closed at both ends. */
    vec2 d = res->axis_direction, right = v2(-d.y, d.x);
    double Hpx = v2_dot(v2_sub(v2_scale(v2_add(rim[0], rim[1]), 0.5), res->axis_origin), d);
    int n = 0;
    for (int k = res->n_silhouette[1] - 1; k >= 0; k--) {
        vec2 q = v2_sub(res->silhouette[1][k], res->axis_origin);
        double r = v2_dot(q, right), h = v2_dot(q, d);
        if (h <= 0 || h >= Hpx || (n > 1 && h <= res->polyline[n - 1].y))
            continue;
        if (n == 0)
            res->polyline[n++] = v2(r, 0);
        res->polyline[n++] = v2(r, h);
    }
    res->polyline[n] = v2(n ? res->polyline[n - 1].x : 0, Hpx);
    res->n_polyline = n + 1;
    return 0;
}

int pinhole_photo(const pinhole_params *p, image_t *img, recon_result *res)
{
    uint8_t *mask = malloc((size_t)p->width * p->height);
    int rc = mask && pinhole_draw(p, img, mask) == 0 ? 0 : -1;
    if (rc == 0 && pinhole_extraction(p, img, mask, res) != 0) {
        image_free(img);
        rc = -1;
    }
    free(mask);
    return rc;
}

int pinhole_camera(const pinhole_params *p, pinhole_shot *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    if (pinhole_photo(p, &s->img, &s->res) != 0) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    return recon_camera_meridian(&s->img, &s->res, NULL, &s->cam, &s->mer, err, errlen);
}

void pinhole_shot_free(pinhole_shot *s)
{
    recon_meridian_free(&s->mer);
    recon_result_free(&s->res);
    image_free(&s->img);
}
