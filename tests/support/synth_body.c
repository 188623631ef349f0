/* A solid of revolution's exact image: see synth_body.h. */
#include "synth_body.h"

#include <math.h>

static const double PI = 3.14159265358979323846;

static double radians(double deg) { return deg * PI / 180; }

int synth_body_valid(const synth_body *b)
{
    return (unsigned)b->profile < SYNTH_PROFILE_COUNT && isfinite(b->height_px) && b->height_px > 0 &&
           isfinite(b->radius_scale) && b->radius_scale > 0 && isfinite(b->base_center.x) &&
           isfinite(b->base_center.y) && b->elevation_deg >= 0 && b->elevation_deg < 60 && fabs(b->tilt_deg) < 45 &&
           !(b->tilt_deg != 0 && b->elevation_deg != 0);
}

double synth_body_radius(const synth_body *b, double h)
{
    return b->height_px * b->radius_scale * synth_profile_radius(b->profile, h / b->height_px);
}

vec2 synth_body_axis(const synth_body *b)
{
    double t = radians(b->tilt_deg);
    return v2(sin(t), -cos(t));
}

vec2 synth_body_rim_center(const synth_body *b)
{
    return v2_add(b->base_center, v2_scale(synth_body_axis(b), b->height_px * cos(radians(b->elevation_deg))));
}

/* An upper bound of r over [0, H], px: the sampled maximum with a margin for
 * what falls between the samples. The sampled maxima are computed once. */
static double radius_bound(const synth_body *b)
{
    static double unit_max[SYNTH_PROFILE_COUNT];
    if (unit_max[b->profile] == 0)
        unit_max[b->profile] = synth_profile_max_radius(b->profile);
    return 1.01 * b->height_px * b->radius_scale * unit_max[b->profile] + 1;
}

typedef double (*height_fn)(const synth_body *b, double h, double w);

/* Maximum of f(h) over [lo, hi] (lo <= hi): sampled every ~step, and each
 * local maximum of the samples polished by golden section to 1e-7 in h. */
static double grid_max(height_fn f, const synth_body *b, double w, double lo, double hi, double step)
{
    const double invphi = 0.61803398874989485;
    int n = (int)fmax(1, ceil((hi - lo) / step));
    double dh = (hi - lo) / n, best = -INFINITY;
    double prev = -INFINITY, cur = f(b, lo, w);
    for (int i = 0; i <= n; i++) {
        double next = i < n ? f(b, lo + (i + 1) * dh, w) : -INFINITY;
        if (cur >= prev && cur >= next) {
            best = fmax(best, cur);
            double a = lo + fmax(0, i - 1) * dh, c = lo + fmin(n, i + 1) * dh;
            double x1 = c - invphi * (c - a), x2 = a + invphi * (c - a), f1 = f(b, x1, w), f2 = f(b, x2, w);
            while (c - a > 1e-7) {
                if (f1 < f2)
                    a = x1, x1 = x2, f1 = f2, x2 = a + invphi * (c - a), f2 = f(b, x2, w);
                else
                    c = x2, x2 = x1, f2 = f1, x1 = c - invphi * (c - a), f1 = f(b, x1, w);
            }
            best = fmax(best, fmax(f1, f2));
        }
        prev = cur;
        cur = next;
    }
    return best;
}

/* r(h)² - ((w - h cos e) / sin e)²: the squared half-width on line w of the
 * ellipse of the disc at height h (negative: the ellipse misses the line). */
static double ellipse_half_width_sq(const synth_body *b, double h, double w)
{
    double e = radians(b->elevation_deg), r = synth_body_radius(b, h), u = (w - h * cos(e)) / sin(e);
    return r * r - u * u;
}

double synth_body_half_width(const synth_body *b, double w)
{
    double H = b->height_px;
    if (b->elevation_deg == 0)
        return w < 0 || w > H ? -1 : synth_body_radius(b, w);
    /* Only discs within R sin e of the line along the axis can reach it. */
    double e = radians(b->elevation_deg), reach = radius_bound(b) * sin(e);
    double lo = fmax(0, (w - reach) / cos(e)), hi = fmin(H, (w + reach) / cos(e));
    if (lo > hi)
        return -1;
    double k = grid_max(ellipse_half_width_sq, b, w, lo, hi, 1.0);
    return k < 0 ? -1 : sqrt(k);
}

static double ellipse_top(const synth_body *b, double h, double w)
{
    (void)w;
    double e = radians(b->elevation_deg);
    return h * cos(e) + synth_body_radius(b, h) * sin(e);
}

static double ellipse_bottom_negated(const synth_body *b, double h, double w)
{
    (void)w;
    double e = radians(b->elevation_deg);
    return synth_body_radius(b, h) * sin(e) - h * cos(e);
}

void synth_body_axis_extent(const synth_body *b, double *w_bottom, double *w_top)
{
    double H = b->height_px;
    if (b->elevation_deg == 0) {
        *w_bottom = 0;
        *w_top = H;
        return;
    }
    *w_bottom = -grid_max(ellipse_bottom_negated, b, 0, 0, H, 1.0);
    *w_top = grid_max(ellipse_top, b, 0, 0, H, 1.0);
}

/* Signed inside-ness for a level camera: positive inside, zero on the
 * outline, continuous (the minimum of the three constraints). */
static double inside_level(const synth_body *b, vec2 d, vec2 q)
{
    vec2 n = v2(-d.y, d.x), rel = v2_sub(q, b->base_center);
    double s = v2_dot(rel, n), h = v2_dot(rel, d), H = b->height_px;
    double hc = fmin(fmax(h, 0), H);
    return fmin(synth_body_radius(b, hc) - fabs(s), fmin(h, H - h));
}

/* Bisection between an inside x (a) and an outside x (c) on line y. */
static double polish(const synth_body *b, vec2 d, double y, double a, double c)
{
    for (int k = 0; k < 60 && fabs(c - a) > 1e-10; k++) {
        double m = 0.5 * (a + c);
        if (inside_level(b, d, v2(m, y)) > 0)
            a = m;
        else
            c = m;
    }
    return 0.5 * (a + c);
}

int synth_body_outline_x(const synth_body *b, double y, double *x_left, double *x_right)
{
    if (b->tilt_deg == 0) {
        double half = synth_body_half_width(b, b->base_center.y - y);
        if (half < 0)
            return 0;
        *x_left = b->base_center.x - half;
        *x_right = b->base_center.x + half;
        return 1;
    }
    /* Tilted: the image lies within R of the axis segment; scan that x-range. */
    vec2 d = synth_body_axis(b), top = v2_add(b->base_center, v2_scale(d, b->height_px));
    double reach = radius_bound(b);
    double x0 = floor(fmin(b->base_center.x, top.x) - reach - 2), x1 = ceil(fmax(b->base_center.x, top.x) + reach + 2);
    const double step = 0.5;
    double first = NAN, last = NAN;
    for (double x = x0; x <= x1; x += step)
        if (inside_level(b, d, v2(x, y)) > 0) {
            if (isnan(first))
                first = x;
            last = x;
        }
    if (isnan(first))
        return 0;
    *x_left = polish(b, d, y, first, first - step);
    *x_right = polish(b, d, y, last, last + step);
    return 1;
}

void synth_body_y_extent(const synth_body *b, double *y_top, double *y_bottom)
{
    double wb, wt, reach = b->tilt_deg == 0 ? 0 : radius_bound(b);
    synth_body_axis_extent(b, &wb, &wt);
    vec2 d = synth_body_axis(b);
    /* |n.y| = |d.x|: the y-extent of the axis-frame box [-R, R] x [wb, wt]. */
    double y0 = b->base_center.y + wt * d.y - reach * fabs(d.x), y1 = b->base_center.y + wb * d.y + reach * fabs(d.x);
    *y_top = fmin(y0, y1);
    *y_bottom = fmax(y0, y1);
}

/* dr/dh at h in [0, H], by a second-order difference that stays inside. */
static double radius_slope(const synth_body *b, double h)
{
    double dh = 1e-4 * b->height_px, sgn = h < 0.5 * b->height_px ? 1 : -1;
    double r0 = synth_body_radius(b, h), r1 = synth_body_radius(b, h + sgn * dh);
    double r2 = synth_body_radius(b, h + 2 * sgn * dh);
    return sgn * (-3 * r0 + 4 * r1 - r2) / (2 * dh);
}

void synth_body_corners(const synth_body *b, vec2 corners[CORNER_COUNT])
{
    double e = radians(b->elevation_deg), H = b->height_px;
    vec2 d = synth_body_axis(b), n = v2(-d.y, d.x);
    for (int top = 0; top < 2; top++) {
        double h = top ? H : 0, r = synth_body_radius(b, h);
        /* Tangency of the contour with the cap ellipse: dK/dh = 0 at the end. */
        double slope_tan = b->elevation_deg == 0 ? 0 : radius_slope(b, h) * tan(e);
        double w = h * cos(e) - r * slope_tan * sin(e);
        double s = r * sqrt(fmax(0, 1 - slope_tan * slope_tan));
        vec2 c = v2_add(b->base_center, v2_scale(d, w));
        corners[top ? CORNER_RIM_LEFT : CORNER_BASE_LEFT] = v2_sub(c, v2_scale(n, s));
        corners[top ? CORNER_RIM_RIGHT : CORNER_BASE_RIGHT] = v2_add(c, v2_scale(n, s));
    }
}

int synth_body_surface(const synth_body *b, vec2 q, double *h, double *phi)
{
    vec2 d = synth_body_axis(b), n = v2(-d.y, d.x), rel = v2_sub(q, b->base_center);
    double s = v2_dot(rel, n), w = v2_dot(rel, d), H = b->height_px;
    double e = radians(b->elevation_deg), ce = cos(e), se = sin(e);
    *h = fmin(fmax(w / ce, 0), H);
    *phi = s < 0 ? -PI / 2 : PI / 2;
    if (b->elevation_deg == 0) {
        double r = synth_body_radius(b, *h);
        *phi = asin(fmax(-1.0, fmin(1.0, s / r)));
        return w >= 0 && w <= H && fabs(s) <= r;
    }
    /* Along the viewing ray through q, the point at height y has depth
     * Z = (y cos e - w) / sin e; it is inside the solid where
     * g(y) = (r(y)² - s²) sin² e - (w - y cos e)² >= 0, and the first point
     * the ray meets is the highest such y. */
    double rt = synth_body_radius(b, H), u = (w - H * ce) / se;
    if (s * s + u * u <= rt * rt) {
        *h = H;
        *phi = atan2(s, -u);
        return 2;
    }
    double reach = radius_bound(b) * se, lo = fmax(0, (w - reach) / ce), hi = fmin(H, (w + reach) / ce);
    const double step = 2.0;
    for (double y = hi; y >= lo; y -= step) {
        double r = synth_body_radius(b, y), g = (r * r - s * s) * se * se - (w - y * ce) * (w - y * ce);
        if (g < 0)
            continue;
        double in = y, out = fmin(hi, y + step);
        for (int k = 0; k < 20; k++) {
            double m = 0.5 * (in + out), rm = synth_body_radius(b, m);
            if ((rm * rm - s * s) * se * se - (w - m * ce) * (w - m * ce) >= 0)
                in = m;
            else
                out = m;
        }
        *h = in;
        *phi = atan2(s, (in * ce - w) / se);
        return 1;
    }
    return 0;
}
