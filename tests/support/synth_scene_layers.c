/* The layers of a synthetic scene: see synth_scene_layers.h. Lengths that
 * scale with the vessel are fractions of the subject's height H. */
#include "synth_scene_layers.h"

#include <math.h>
#include <stdlib.h>

#include "synth_noise.h"
#include "synth_raster.h"

typedef void (*colour_fn)(const void *ctx, double x, double y, float rgb[3]);

/* The key light, from the upper left and in front (object frame: x right,
 * y up the axis, z toward a level camera). */
static const vec3 KEY = {-0.55, 0.62, 0.56};

static double clamp01(double t) { return fmin(1.0, fmax(0.0, t)); }
static double smoothstep01(double t)
{
    t = clamp01(t);
    return t * t * (3 - 2 * t);
}

/* Paints colour over the canvas where cov > 0 ("over" with coverage as alpha). */
static void composite(scene_canvas *c, const float *cov, colour_fn colour, const void *ctx)
{
    for (int j = 0; j < c->height; j++)
        for (int i = 0; i < c->width; i++) {
            size_t k = (size_t)j * c->width + i;
            float a = cov[k], col[3];
            if (a <= 0)
                continue;
            colour(ctx, i + 0.5, j + 0.5, col);
            for (int q = 0; q < 3; q++)
                c->rgb[3 * k + q] = a * col[q] + (1 - a) * c->rgb[3 * k + q];
        }
}

static void darken(scene_canvas *c, const float *weight)
{
    for (size_t k = 0; k < (size_t)c->width * c->height; k++)
        for (int q = 0; q < 3; q++)
            c->rgb[3 * k + q] *= 1 - weight[k];
}

static const synth_body *subject(const synth_scene_params *p) { return &p->vessels[0].body; }

/* The image point of axis-frame (s, w) of a body. */
static vec2 axis_point(const synth_body *b, double s, double w)
{
    vec2 d = synth_body_axis(b), n = v2(-d.y, d.x);
    return v2_add(b->base_center, v2_add(v2_scale(n, s), v2_scale(d, w)));
}

double scene_foot_y(const synth_scene_params *p)
{
    const synth_body *b = subject(p);
    double y_top, y_bottom;
    if (b->tilt_deg == 0) {
        synth_body_y_extent(b, &y_top, &y_bottom);
        return y_bottom;
    }
    vec2 c[CORNER_COUNT];
    synth_body_corners(b, c);
    return fmax(c[CORNER_BASE_LEFT].y, c[CORNER_BASE_RIGHT].y);
}

/* ------------------------------------------------------------------ backdrop */

void scene_backdrop(const synth_scene_params *p, scene_canvas *c)
{
    const synth_backdrop *b = &p->backdrop;
    int W = c->width, H = c->height;
    for (int j = 0; j < H; j++) {
        double y = j + 0.5, t = 0;
        if (b->kind == SYNTH_BACKDROP_SWEEP)
            t = 0.5 * (1 + tanh(0.5 * (y - b->horizon * H) / fmax(1e-6, b->softness * H)));
        for (int i = 0; i < W; i++) {
            double x = i + 0.5, f = 1;
            if (b->vignette > 0) {
                double dx = (x - 0.5 * W) / (0.5 * W), dy = (y - 0.5 * H) / (0.5 * H);
                f *= 1 - b->vignette * 0.5 * (dx * dx + dy * dy);
            }
            if (b->grain > 0)
                f *= 1 + b->grain * synth_noise_fractal(p->seed, x, y, b->grain_px, 4);
            float *px = c->rgb + 3 * ((size_t)j * W + i);
            for (int q = 0; q < 3; q++)
                px[q] = (float)(f * (b->wall[q] + t * (b->floor[q] - b->wall[q])));
        }
    }
}

/* ------------------------------------------------------------------ shadows */

/* Signed distance to the capsule of radius rad around segment ab; *u is the
 * position of the nearest axis point along ab, in [0, 1]. */
static double capsule_sdf(vec2 q, vec2 a, vec2 b, double rad, double *u)
{
    vec2 ab = v2_sub(b, a);
    *u = clamp01(v2_dot(v2_sub(q, a), ab) / v2_dot(ab, ab));
    return v2_len(v2_sub(q, v2_add(a, v2_scale(ab, *u)))) - rad;
}

/* Elliptical distance bound: negative inside, 1-Lipschitz. */
static double ellipse_sdf(double dx, double dy, double a, double b)
{
    return (hypot(dx / a, dy / b) - 1) * fmin(a, b);
}

void scene_cast_shadow(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    const synth_cast_shadow *s = &p->shadow;
    const synth_body *b = subject(p);
    double H = b->height_px, rad = 0.5 * s->breadth * H, soft = fmax(1.0, s->softness * H);
    double rise = s->rise_deg * M_PI / 180;
    /* It starts beside the axis, far enough that its soft end stays on its
     * side (under the foot, or just beyond a narrow one). */
    double start = fmax(0.5 * synth_body_radius(b, 0), rad + 0.5 * soft + 1);
    vec2 a = v2(b->base_center.x + s->side * start, scene_foot_y(p) - rad);
    vec2 e = v2_add(a, v2_scale(v2(s->side * cos(rise), -sin(rise)), s->length * H));
    double pad = rad + soft;
    int i0 = (int)fmax(0, floor(fmin(a.x, e.x) - pad)), i1 = (int)fmin(c->width - 1, ceil(fmax(a.x, e.x) + pad));
    int j0 = (int)fmax(0, floor(fmin(a.y, e.y) - pad)), j1 = (int)fmin(c->height - 1, ceil(fmax(a.y, e.y) + pad));
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) {
            double u, d = capsule_sdf(v2(i + 0.5, j + 0.5), a, e, rad, &u);
            /* Soft edge over `soft` px; fainter toward its far end. */
            weight[(size_t)j * c->width + i] = (float)(s->strength * smoothstep01(0.5 - d / soft) * (1 - 0.5 * u));
        }
    darken(c, weight);
}

void scene_contact_shadow(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    const synth_body *b = subject(p);
    double H = b->height_px, r0 = synth_body_radius(b, 0), se = sin(b->elevation_deg * M_PI / 180);
    double a = 1.05 * r0 + 0.01 * H, bb = 1.05 * r0 * se + 0.012 * H, soft = fmax(1.0, 0.015 * H);
    vec2 o = b->base_center;
    int i0 = (int)fmax(0, floor(o.x - a - soft)), i1 = (int)fmin(c->width - 1, ceil(o.x + a + soft));
    int j0 = (int)fmax(0, floor(o.y - bb - soft)), j1 = (int)fmin(c->height - 1, ceil(o.y + bb + soft));
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) {
            double d = ellipse_sdf(i + 0.5 - o.x, j + 0.5 - o.y, a, bb);
            weight[(size_t)j * c->width + i] = (float)(p->contact_shadow * smoothstep01(0.5 - d / soft));
        }
    darken(c, weight);
}

/* ------------------------------------------------------------------ vessels */

static int body_span(const void *body, double y, double *x_left, double *x_right)
{
    return synth_body_outline_x(body, y, x_left, x_right);
}

/* Coverage of a body into weight, over the rows it can touch. */
static int cover_body(const synth_scene_params *p, const synth_body *b, int width, int height, float *weight)
{
    double y_top, y_bottom;
    synth_body_y_extent(b, &y_top, &y_bottom);
    return synth_cover_spans(weight, width, height, (int)floor(y_top), (int)floor(y_bottom), y_top, y_bottom,
                             p->subrows > 0 ? p->subrows : 16, body_span, b);
}

/* Fraction of a pixel-wide anti-aliased feature at signed distance d (px). */
static double feature(double d) { return clamp01(0.5 - d); }

/* Decoration painted on the glaze at surface point (h, phi). */
static void decorate(const synth_scene_vessel *v, double h, double phi, double col[3])
{
    double H = v->body.height_px, r = synth_body_radius(&v->body, h), a = 0;
    /* A thin line under the shoulder, and one over the foot but on LINES. */
    if (v->decor != SYNTH_DECOR_LINES)
        a = fmax(a, feature(fabs(h - 0.12 * H) - 0.008 * H));
    a = fmax(a, feature(fabs(h - 0.77 * H) - 0.008 * H));
    if (v->decor == SYNTH_DECOR_BANDS)
        a = fmax(a, feature(fabs(h - 0.41 * H) - 0.11 * H));
    else if (v->decor == SYNTH_DECOR_MEDALLIONS) {
        /* Roundels on every 60° meridian at mid height, in arc length. */
        double step = M_PI / 3, du = (phi - step * round(phi / step)) * r, dist = hypot(du, h - 0.45 * H);
        a = fmax(a, feature(fabs(dist - 0.085 * H) - 0.012 * H));
        a = fmax(a, feature(dist - 0.03 * H));
    }
    for (int q = 0; q < 3; q++)
        col[q] += a * (v->decor_colour[q] - col[q]);
}

/* Studio shading of a wall point: diffuse key light, darker where the wall
 * turns away from the camera, a soft specular and the highlight stripe
 * (added as light: c + (1 - c) s stays within [0, 1]). */
static void shade_wall(const synth_scene_vessel *v, double h, double phi, double col[3])
{
    const synth_body *b = &v->body;
    double e = b->elevation_deg * M_PI / 180, H = b->height_px;
    double h0 = fmax(0, h - 0.5), h1 = fmin(H, h + 0.5);
    double slope = (synth_body_radius(b, h1) - synth_body_radius(b, h0)) / (h1 - h0);
    vec3 n = v3_norm(v3(sin(phi), -slope, cos(phi))), view = v3(0, sin(e), cos(e)), key = v3_norm(KEY);
    double diffuse = fmax(0, v3_dot(n, key)), facing = fmax(0, v3_dot(n, view));
    double shade = 1.1 * (0.50 + 0.60 * diffuse) * (0.60 + 0.40 * facing);
    double spec = 0.18 * pow(fmax(0, v3_dot(n, v3_norm(v3_add(key, view)))), 30);
    double dphi = (phi - v->highlight_deg * M_PI / 180) / fmax(1e-3, v->highlight_width_deg * M_PI / 180);
    double light = fmin(1, spec + v->highlight * exp(-dphi * dphi));
    for (int q = 0; q < 3; q++) {
        double lit = fmin(1, col[q] * shade);
        col[q] = lit + (1 - lit) * light;
    }
}

/* The rim disc (the top face) under the pixel at (x, y): returns the share
 * of the pixel inside it, anti-aliasing the edge between disc and wall by a
 * one-pixel ramp on the ellipse's distance bound (0 when level), and sets
 * *depth, the point's distance toward the camera over the disc's radius
 * (+1 its front edge, -1 its back). */
static double rim_disc(const synth_body *b, double x, double y, double *depth)
{
    *depth = 0;
    if (b->elevation_deg == 0)
        return 0;
    vec2 d = synth_body_axis(b), n = v2(-d.y, d.x), rel = v2_sub(v2(x, y), b->base_center);
    double e = b->elevation_deg * M_PI / 180, H = b->height_px, rt = synth_body_radius(b, H);
    double u = v2_dot(rel, d) - H * cos(e);
    *depth = fmax(-1, fmin(1, -u / (rt * sin(e))));
    return feature(ellipse_sdf(v2_dot(rel, n), u, rt, rt * sin(e)));
}

/* The colour of a visible surface point (where: 1 wall, 2 rim disc, whose
 * point is `depth` toward the camera). */
static void surface_colour(const synth_scene_vessel *v, int where, double h, double phi, double depth, double col[3])
{
    for (int q = 0; q < 3; q++)
        col[q] = v->glaze[q];
    if (v->decor != SYNTH_DECOR_NONE && where != 2)
        decorate(v, h, phi, col);
    if (!v->lit)
        return;
    if (where == 2) {
        /* An open mouth shows the inner wall, lit at the back and dark at
         * the front; a lid's top is lit from above. */
        double shade = v->open_mouth ? 0.14 + 0.14 * (1 - depth) : 0.45 + 0.6 * v3_norm(KEY).y;
        for (int q = 0; q < 3; q++)
            col[q] *= shade;
    } else
        shade_wall(v, h, phi, col);
}

static void vessel_colour(const void *ctx, double x, double y, float rgb[3])
{
    const synth_scene_vessel *v = ctx;
    double col[3] = {v->glaze[0], v->glaze[1], v->glaze[2]};
    if (v->lit || v->decor != SYNTH_DECOR_NONE) {
        double h, phi, depth = 0, share = v->lit ? rim_disc(&v->body, x, y, &depth) : 0;
        int where = synth_body_surface(&v->body, v2(x, y), &h, &phi);
        surface_colour(v, where, h, phi, depth, col);
        if (share > 0 && share < 1) {
            /* Across the rim disc's edge: the disc's colour and the wall's
             * at the rim, mixed by the share of the pixel in the disc. */
            double other[3], H = v->body.height_px;
            surface_colour(v, where == 2 ? 1 : 2, H, phi, depth, other);
            double a = where == 2 ? 1 - share : share;
            for (int q = 0; q < 3; q++)
                col[q] += a * (other[q] - col[q]);
        }
    }
    for (int q = 0; q < 3; q++)
        rgb[q] = (float)col[q];
}

int scene_vessel(const synth_scene_params *p, int index, scene_canvas *c, float *weight)
{
    const synth_scene_vessel *v = &p->vessels[index];
    if (cover_body(p, &v->body, c->width, c->height, weight))
        return -1;
    composite(c, weight, vessel_colour, v);
    return 0;
}

/* ------------------------------------------------------------------ stand */

static synth_body stand_body(const synth_scene_params *p)
{
    const synth_body *b = subject(p);
    double Hs = p->stand.height * b->height_px, r = p->stand.width * synth_body_radius(b, 0);
    double drop = Hs * cos(b->elevation_deg * M_PI / 180);
    return (synth_body){SYNTH_PROFILE_CYLINDER, Hs, 2 * r / Hs, v2(b->base_center.x, b->base_center.y + drop), 0,
                        b->elevation_deg};
}

typedef struct {
    const synth_stand *stand;
    synth_body cylinder;
    double top_y, front_y, bottom_y; /* BOX: top face from top_y to front_y, front face to bottom_y */
} stand_look;

static void stand_colour(const void *ctx, double x, double y, float rgb[3])
{
    const stand_look *s = ctx;
    double shade;
    if (s->stand->kind == SYNTH_STAND_CYLINDER) {
        double h, phi, depth, top = rim_disc(&s->cylinder, x, y, &depth);
        synth_body_surface(&s->cylinder, v2(x, y), &h, &phi);
        double wall = 0.74 + 0.26 * fmax(0, v3_dot(v3(sin(phi), 0, cos(phi)), v3_norm(KEY)));
        shade = top + (1 - top) * wall;
    } else {
        /* The share of this pixel row above the edge between the faces. */
        double top = clamp01(s->front_y - floor(y));
        double front = 0.86 - 0.10 * clamp01((y - s->front_y) / fmax(1, s->bottom_y - s->front_y));
        shade = top + (1 - top) * front;
    }
    for (int q = 0; q < 3; q++)
        rgb[q] = (float)(shade * s->stand->colour[q]);
}

int scene_stand(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    stand_look look = {&p->stand, stand_body(p), 0, 0, 0};
    if (p->stand.kind == SYNTH_STAND_CYLINDER) {
        if (cover_body(p, &look.cylinder, c->width, c->height, weight))
            return -1;
    } else {
        const synth_body *b = subject(p);
        double e = b->elevation_deg * M_PI / 180, half = p->stand.width * synth_body_radius(b, 0);
        double depth = p->stand.depth * 2 * half;
        look.front_y = b->base_center.y + 0.5 * depth * sin(e);
        look.top_y = look.front_y - depth * sin(e);
        look.bottom_y = look.front_y + p->stand.height * b->height_px * cos(e);
        synth_cover_rect(weight, c->width, c->height, b->base_center.x - half, look.top_y, b->base_center.x + half,
                         look.bottom_y);
    }
    composite(c, weight, stand_colour, &look);
    return 0;
}

/* ------------------------------------------------------------------ attachments */

enum { STROKE_SEGMENTS = 64 };

/* A thick curve: a cubic Bézier flattened into segments, with a half-width
 * per vertex (round ends). */
typedef struct {
    vec2 pt[STROKE_SEGMENTS + 1];
    double half[STROKE_SEGMENTS + 1];
    const synth_scene_vessel *look;
    const synth_attachment *part;
} stroke;

/* Distance from q to the stroke's centreline and the half-width there. */
static void stroke_nearest(const stroke *s, vec2 q, double *dist, double *half)
{
    *dist = INFINITY;
    *half = s->half[0];
    double best = INFINITY;
    for (int k = 0; k < STROKE_SEGMENTS; k++) {
        double u, d = capsule_sdf(q, s->pt[k], s->pt[k + 1], 0, &u);
        double hw = s->half[k] + u * (s->half[k + 1] - s->half[k]);
        if (d - hw < best) {
            best = d - hw;
            *dist = d;
            *half = hw;
        }
    }
}

static double stroke_sdf(const void *ctx, double x, double y)
{
    double d, hw;
    stroke_nearest(ctx, v2(x, y), &d, &hw);
    return d - hw;
}

/* A tube lit across its width: brightest along the middle; in the
 * attachment's own colour, or the glaze's. */
static void tube_colour(const synth_scene_vessel *look, const synth_attachment *a, double across, float rgb[3])
{
    double shade = look->lit ? 0.40 + 0.55 * sqrt(fmax(0, 1 - across * across)) : 1.0;
    const float *c = a->colour[0] > 0 || a->colour[1] > 0 || a->colour[2] > 0 ? a->colour : look->glaze;
    for (int q = 0; q < 3; q++)
        rgb[q] = (float)(shade * c[q]);
}

static void stroke_colour(const void *ctx, double x, double y, float rgb[3])
{
    const stroke *s = ctx;
    double d, hw;
    stroke_nearest(s, v2(x, y), &d, &hw);
    tube_colour(s->look, s->part, fmin(1, d / hw), rgb);
}

/* Bézier centreline in the axis frame (s, w) of the body, drawn into st. */
static void build_stroke(const synth_scene_params *p, const synth_attachment *a, stroke *st)
{
    const synth_body *b = subject(p);
    double H = b->height_px, ce = cos(b->elevation_deg * M_PI / 180), t = a->thickness * H, side = a->side;
    double r0 = synth_body_radius(b, a->h0 * H), r1 = synth_body_radius(b, a->h1 * H);
    double out = fmax(r0, r1) + a->reach * H; /* the outer edge's (HANDLE) or the tip's (SPOUT) distance */
    double w0 = a->h0 * H * ce, w1 = a->h1 * H * ce;
    vec2 c[4];
    double half0 = 0.5 * t, half1 = 0.5 * t;
    if (a->kind == SYNTH_ATTACH_HANDLE) {
        /* Ends a thickness inside the wall; the middle of the curve, at
         * (c0 + 3 c1 + 3 c2 + c3) / 8, reaches `out` minus the half-width. */
        c[0] = v2(r0 - t, w0), c[3] = v2(r1 - t, w1);
        double sc = (8 * (out - half0) - c[0].x - c[3].x) / 6;
        c[1] = v2(sc, w0), c[2] = v2(sc, w1);
    } else {
        c[0] = v2(r0 - t, w0), c[3] = v2(out, w1);
        c[1] = v2(r0 + 0.45 * (out - r0), w0 + 0.10 * (w1 - w0));
        c[2] = v2(r0 + 0.80 * (out - r0), w0 + 0.55 * (w1 - w0));
        half1 = 0.25 * t;
    }
    for (int k = 0; k <= STROKE_SEGMENTS; k++) {
        double u = (double)k / STROKE_SEGMENTS, v = 1 - u;
        double s = v * v * v * c[0].x + 3 * v * v * u * c[1].x + 3 * v * u * u * c[2].x + u * u * u * c[3].x;
        double w = v * v * v * c[0].y + 3 * v * v * u * c[1].y + 3 * v * u * u * c[2].y + u * u * u * c[3].y;
        st->pt[k] = axis_point(b, side * s, w);
        st->half[k] = half0 + u * (half1 - half0);
    }
    st->look = &p->vessels[0];
    st->part = a;
}

/* A solid lug: an ellipse centred on the wall's outline at h0. */
typedef struct {
    const synth_body *body;
    double s, w, a, b; /* centre and half-axes in the axis frame */
    const synth_scene_vessel *look;
    const synth_attachment *part;
} lug;

static double lug_sdf(const void *ctx, double x, double y)
{
    const lug *l = ctx;
    vec2 d = synth_body_axis(l->body), n = v2(-d.y, d.x), rel = v2_sub(v2(x, y), l->body->base_center);
    return ellipse_sdf(v2_dot(rel, n) - l->s, v2_dot(rel, d) - l->w, l->a, l->b);
}

static void lug_colour(const void *ctx, double x, double y, float rgb[3])
{
    const lug *l = ctx;
    double f = lug_sdf(ctx, x, y) / fmin(l->a, l->b); /* -1 at the centre, 0 on the edge */
    tube_colour(l->look, l->part, fmin(1, 1 + f), rgb);
}

int scene_attachment(const synth_scene_params *p, int index, scene_canvas *c, float *weight)
{
    const synth_attachment *a = &p->attachments[index];
    int n = p->supersample > 8 ? p->supersample : 8;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    if (a->kind == SYNTH_ATTACH_LUG) {
        const synth_body *b = subject(p);
        double H = b->height_px, w = a->h0 * H * cos(b->elevation_deg * M_PI / 180);
        lug l = {b, a->side * synth_body_radius(b, a->h0 * H), w, a->reach * H, 0.5 * a->thickness * H, &p->vessels[0], a};
        vec2 o = axis_point(b, l.s, l.w);
        double reach = fmax(l.a, l.b) + 2;
        synth_cover_sdf(weight, c->width, c->height, (int)(o.x - reach), (int)(o.y - reach), (int)(o.x + reach),
                        (int)(o.y + reach), n, 1.0, lug_sdf, &l);
        composite(c, weight, lug_colour, &l);
        return 0;
    }
    stroke *st = malloc(sizeof *st);
    if (!st)
        return -1;
    build_stroke(p, a, st);
    for (int k = 0; k <= STROKE_SEGMENTS; k++) {
        x0 = fmin(x0, st->pt[k].x - st->half[k]), x1 = fmax(x1, st->pt[k].x + st->half[k]);
        y0 = fmin(y0, st->pt[k].y - st->half[k]), y1 = fmax(y1, st->pt[k].y + st->half[k]);
    }
    /* A tapered stroke's distance bound stretches by its taper: 1.5 covers it. */
    synth_cover_sdf(weight, c->width, c->height, (int)x0 - 2, (int)y0 - 2, (int)x1 + 2, (int)y1 + 2, n, 1.5, stroke_sdf,
                    st);
    composite(c, weight, stroke_colour, st);
    free(st);
    return 0;
}

/* ------------------------------------------------------------------ caption, scale bar, frame */

enum { CAPTION_MAX_GLYPHS = 96 };

/* A pale label with one line of dark blocks standing for text; every edge
 * lies on the pixel grid, so colour by pixel centre is exact. */
typedef struct {
    int x0, x1, y0, y1;    /* the label */
    int gy0, gy1;          /* the text line */
    int count;
    int gx0[CAPTION_MAX_GLYPHS], gx1[CAPTION_MAX_GLYPHS];
} caption_look;

static void caption_colour(const void *ctx, double x, double y, float rgb[3])
{
    const caption_look *c = ctx;
    float v = 0.93f;
    if (y > c->gy0 && y < c->gy1)
        for (int k = 0; k < c->count; k++)
            if (x > c->gx0[k] && x < c->gx1[k])
                v = 0.12f;
    rgb[0] = rgb[1] = rgb[2] = v;
}

void scene_caption(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    int W = c->width, H = c->height;
    caption_look look = {(int)lround(0.56 * W), (int)lround(0.94 * W), H - (int)lround(0.05 * H),
                         H - 1 - (int)lround(0.01 * H), 0, 0, 0, {0}, {0}};
    int lh = look.y1 - look.y0, unit = (int)fmax(1, lround(0.006 * W));
    look.gy0 = look.y0 + (int)lround(0.3 * lh);
    look.gy1 = look.y1 - (int)lround(0.3 * lh);
    int x = look.x0 + 2 * unit;
    for (int k = 0; look.count < CAPTION_MAX_GLYPHS; k++) {
        int glyph = 1 + (int)(3 * synth_noise_uniform(p->seed, k, 0, 7));
        int gap = synth_noise_uniform(p->seed, k, 1, 7) < 0.2 ? 3 : 1;
        if (x + glyph * unit > look.x1 - 2 * unit)
            break;
        look.gx0[look.count] = x;
        look.gx1[look.count++] = x + glyph * unit;
        x += (glyph + gap) * unit;
    }
    synth_cover_rect(weight, W, H, look.x0, look.y0, look.x1, look.y1);
    composite(c, weight, caption_colour, &look);
}

/* A ruler of alternating black and white cells inside a black border. */
typedef struct {
    int x0, x1, y0, y1, cells;
} scale_bar_look;

static void scale_bar_colour(const void *ctx, double x, double y, float rgb[3])
{
    const scale_bar_look *s = ctx;
    int border = x < s->x0 + 1 || x > s->x1 - 1 || y < s->y0 + 1 || y > s->y1 - 1;
    int cell = (int)floor((x - s->x0) * s->cells / (s->x1 - s->x0));
    rgb[0] = rgb[1] = rgb[2] = border || cell % 2 == 0 ? 0.05f : 0.95f;
}

void scene_scale_bar(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    (void)p;
    int W = c->width, H = c->height, cells = 8;
    int x0 = (int)lround(0.06 * W), width = cells * (int)fmax(2, lround(0.0375 * W));
    scale_bar_look s = {x0, x0 + width, H - (int)lround(0.045 * H), H - (int)lround(0.02 * H), cells};
    synth_cover_rect(weight, W, H, s.x0, s.y0, s.x1, s.y1);
    composite(c, weight, scale_bar_colour, &s);
}

static void frame_colour(const void *ctx, double x, double y, float rgb[3])
{
    (void)ctx, (void)x, (void)y;
    rgb[0] = rgb[1] = rgb[2] = 0.04f;
}

void scene_frame(const synth_scene_params *p, scene_canvas *c, float *weight)
{
    (void)p;
    int W = c->width, H = c->height, in = 2, line = (int)fmax(2, lround(0.003 * fmin(W, H)));
    synth_cover_rect(weight, W, H, in, in, W - in, in + line);
    synth_cover_rect(weight, W, H, in, H - in - line, W - in, H - in);
    synth_cover_rect(weight, W, H, in, in, in + line, H - in);
    synth_cover_rect(weight, W, H, W - in - line, in, W - in, H - in);
    composite(c, weight, frame_colour, NULL);
}
