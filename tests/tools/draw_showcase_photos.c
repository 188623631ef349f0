/* Draws the four catalogue photos of the showcase scene (scenes/showcase/
 * photos/): a celadon plum vase (maebyeong) with inlaid cranes' medallions,
 * a white porcelain bowl with a cobalt rim band and lotus petals, a tenmoku
 * bottle with rust streaks, and a blue-and-white jar with a scroll band. The
 * outlines and coverage come from tests/support/synth_vessel (exact,
 * anti-aliased); glaze, soft catalogue lighting and patterns are painted here
 * from the same analytic geometry, so `celadon reconstruct` has real photos
 * to work from. Run by hand (scenes/showcase/README.md):
 *
 *   draw_showcase_photos OUTDIR   ->  OUTDIR/{maebyeong,bowl,bottle,jar}.png */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../support/synth_vessel.h"

typedef struct { double r, g, b; } rgb3;

static rgb3 mix(rgb3 a, rgb3 b, double t) { return (rgb3){a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)}; }

/* 1 inside (d < 0), 0 outside, a one-pixel ramp between: anti-aliased shapes. */
static double inside(double d) { return fmin(1.0, fmax(0.0, 0.5 - d)); }

/* A point of the visible surface: angle phi around the axis (0 faces the
 * camera), height h (px, from the base), radius r (px); H the height. All
 * pattern distances are in photo pixels (arc length r * dphi along a row). */
typedef struct { double phi, h, r, H; } surf_pt;

/* Distance (px of arc) from phi to the nearest of count equally spaced meridians. */
static double meridian_dist(const surf_pt *s, int count, double offset)
{
    double step = 2.0 * M_PI / count, a = s->phi - offset;
    return fabs(a - step * round(a / step)) * s->r;
}

static rgb3 paint_maebyeong(const surf_pt *s)
{
    const rgb3 glaze = {0.50, 0.64, 0.55}, white = {0.93, 0.92, 0.85}, black = {0.15, 0.16, 0.14};
    rgb3 c = glaze;
    double t = s->h / s->H;
    /* Double lines under the shoulder and above the foot. */
    for (int i = 0; i < 2; i++) {
        double d = fabs(s->h - (i ? 0.12 : 0.78) * s->H);
        c = mix(c, white, inside(fabs(d - 6.0) - 1.8));
        c = mix(c, black, inside(fabs(d - 11.0) - 1.2));
    }
    /* Medallions (white ring, black crane dot) on two staggered rows. */
    for (int row = 0; row < 2; row++) {
        double off = row ? M_PI / 6 : 0.0, hc = (row ? 0.34 : 0.56) * s->H, R = 0.07 * s->H;
        double du = meridian_dist(s, 6, off), dv = s->h - hc, d = hypot(du, dv);
        c = mix(c, white, inside(fabs(d - R) - 3.0));
        c = mix(c, black, inside(d - 0.3 * R));
    }
    /* Cloud dots between them. */
    if (t > 0.2 && t < 0.7) {
        double du = meridian_dist(s, 12, M_PI / 12), dv = fmod(s->h, 0.11 * s->H) - 0.055 * s->H;
        c = mix(c, white, 0.7 * inside(hypot(du, dv) - 3.5));
    }
    return c;
}

static rgb3 paint_bowl(const surf_pt *s)
{
    const rgb3 porcelain = {0.86, 0.87, 0.85}, cobalt = {0.13, 0.22, 0.55};
    rgb3 c = porcelain;
    /* A band under the white lip. */
    c = mix(c, cobalt, inside(fabs(s->h - 0.88 * s->H) - 0.035 * s->H));
    c = mix(c, porcelain, inside(fabs(s->h - 0.88 * s->H) - 1.5));
    c = mix(c, cobalt, inside(fabs(s->h - 0.10 * s->H) - 2.0)); /* foot line */
    /* Lotus petals: pointed arches between the foot line and mid height. */
    double a = meridian_dist(s, 10, 0.0) / (M_PI / 10 * s->r); /* 0 mid petal, 1 edge */
    double top = (0.18 + 0.35 * (1.0 - a * a)) * s->H;
    if (s->h > 0.12 * s->H)
        c = mix(c, cobalt, inside(fabs(s->h - top) - 2.2));
    return c;
}

static rgb3 paint_bottle(const surf_pt *s)
{
    const rgb3 tenmoku = {0.10, 0.06, 0.04}, rust = {0.55, 0.27, 0.10};
    double t = s->h / s->H;
    /* Rust streaks running down from the shoulder, thinning toward the foot. */
    double w = 6.0 * fmax(0.0, t - 0.15);
    double streak = inside(meridian_dist(s, 16, 0.1 * sin(9.0 * t)) - w);
    rgb3 c = mix(tenmoku, rust, 0.85 * streak * fmin(1.0, fmax(0.0, 3.0 * (t - 0.15))));
    /* The glaze stops above the foot: bare stoneware. */
    return mix(c, (rgb3){0.62, 0.50, 0.38}, inside(s->h - 0.07 * s->H));
}

static rgb3 paint_jar(const surf_pt *s)
{
    const rgb3 white = {0.87, 0.87, 0.84}, blue = {0.12, 0.20, 0.50};
    rgb3 c = white;
    for (int i = 0; i < 4; i++) /* framing lines */
        c = mix(c, blue, inside(fabs(s->h - (i < 2 ? 0.30 + 0.03 * i : 0.70 + 0.03 * (i - 2)) * s->H) - 1.5));
    /* A scroll band: a sine wave of arc-length period 0.25 H with curls. */
    double hc = 0.5 * s->H, amp = 0.09 * s->H, x = s->phi * s->r / (0.25 * s->H) * 2.0 * M_PI;
    c = mix(c, blue, inside(fabs(s->h - hc - amp * sin(x)) - 2.5));
    double du = meridian_dist(s, 12, 0.0), dv = s->h - hc - 0.6 * amp;
    c = mix(c, blue, inside(fabs(hypot(du, dv) - 0.04 * s->H) - 2.0));
    c = mix(c, blue, inside(fabs(s->h - 0.12 * s->H) - 0.03 * s->H)); /* bands above the foot */
    return mix(c, blue, inside(fabs(s->h - 0.88 * s->H) - 0.03 * s->H)); /* and under the rim */
}

typedef struct {
    const char *name;
    synth_shape shape;
    rgb3 (*paint)(const surf_pt *);
    double gloss; /* highlight strength */
    int white_backdrop; /* white wares on a paper-white sweep, so they stay darker than it */
} vessel;

static const vessel vessels[] = {
    {"maebyeong", SYNTH_VASE, paint_maebyeong, 0.30, 0},
    {"bowl", SYNTH_BOWL, paint_bowl, 0.08, 1},
    {"bottle", SYNTH_BOTTLE, paint_bottle, 0.45, 0},
    {"jar", SYNTH_JAR, paint_jar, 0.08, 1},
};

/* Catalogue backdrop: a smooth light gray sweep, or paper white. */
static rgb3 backdrop(double x, double y, int W, int Hi, int white)
{
    double t = y / Hi, v = white ? 1.0 : 0.95 - 0.06 * t - 0.03 * pow((x / W - 0.5) * 2.0, 2.0);
    return (rgb3){v, v * 0.99, v * 0.97};
}

static int draw(const vessel *v, const char *path)
{
    synth_params p = synth_defaults(v->shape, 600, 800);
    if (v->shape == SYNTH_BOWL) /* wider than tall: a landscape photo */
        p = synth_defaults(v->shape, 900, 600);
    p.rgba = 1;
    image_t cov;
    if (synth_draw(&p, &cov) != 0)
        return -1;
    synth_truth tr = synth_truth_of(&p);
    vec2 d = tr.axis_direction, n = v2(-d.y, d.x);
    double H = tr.height_px;
    const double L[3] = {-0.35, 0.5, 0.79}; /* a large soft key light, upper left front */
    image_t out = image_alloc(p.width, p.height, 3);
    if (!out.data) {
        image_free(&cov);
        return -1;
    }
    for (int j = 0; j < p.height; j++)
        for (int i = 0; i < p.width; i++) {
            size_t k = (size_t)j * p.width + i;
            double alpha = cov.data[4 * k + 3];
            rgb3 c = backdrop(i + 0.5, j + 0.5, p.width, p.height, v->white_backdrop);
            if (alpha > 0) {
                vec2 rel = v2_sub(v2(i + 0.5, j + 0.5), tr.axis_origin);
                double h = fmin(fmax(v2_dot(rel, d), 0.0), H), r = synth_radius(&p, h);
                double phi = asin(fmax(-1.0, fmin(1.0, v2_dot(rel, n) / r)));
                double h0 = fmax(0.0, h - 0.5), h1 = fmin(H, h + 0.5);
                double slope = (synth_radius(&p, h1) - synth_radius(&p, h0)) / (h1 - h0);
                double nx = sin(phi), ny = -slope, nz = cos(phi);
                double len = sqrt(nx * nx + ny * ny + nz * nz);
                nx /= len, ny /= len, nz /= len;
                double diff = fmax(0.0, nx * L[0] + ny * L[1] + nz * L[2]);
                double hx = L[0], hy = L[1], hz = L[2] + 1.0, hl = sqrt(hx * hx + hy * hy + hz * hz);
                double spec = pow(fmax(0.0, (nx * hx + ny * hy + nz * hz) / hl), 80.0);
                surf_pt sp = {phi, h, r, H};
                rgb3 base = v->paint(&sp), lit;
                double shade = 0.72 + 0.32 * diff;
                lit.r = base.r * shade + v->gloss * spec;
                lit.g = base.g * shade + v->gloss * spec;
                lit.b = base.b * shade + v->gloss * spec;
                c = mix(c, lit, alpha);
            }
            out.data[3 * k] = (float)fmin(1.0, c.r);
            out.data[3 * k + 1] = (float)fmin(1.0, c.g);
            out.data[3 * k + 2] = (float)fmin(1.0, c.b);
        }
    char err[256];
    int rc = synth_write(path, &out, 8, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "draw_showcase_photos: %s: %s\n", path, err);
    image_free(&out);
    image_free(&cov);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: draw_showcase_photos OUTDIR\n");
        return 2;
    }
    for (size_t i = 0; i < sizeof vessels / sizeof *vessels; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.png", argv[1], vessels[i].name);
        if (draw(&vessels[i], path) != 0)
            return 1;
        printf("%s\n", path);
    }
    return 0;
}
