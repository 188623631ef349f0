/* Draws the bundled sample "catalogue photo" (scenes/demo/photo.png): a
 * celadon-glazed vase with white and black inlay (sanggam) on a soft studio
 * background. The outline comes from tests/support/synth_vessel (exact,
 * anti-aliased coverage); glaze, shading and inlay are painted here from the
 * same analytic geometry. Run by `make demo-photo`.
 *
 *   draw_demo_photo OUT.png */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../support/synth_vessel.h"

typedef struct { double r, g, b; } rgb;

static const rgb glaze = {0.52, 0.66, 0.57}, white_inlay = {0.92, 0.91, 0.84}, black_inlay = {0.16, 0.17, 0.15};

static rgb mix(rgb a, rgb b, double t) { return (rgb){a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)}; }

/* Smooth 0..1 step of width w around edge (anti-aliases painted shapes). */
static double smooth_in(double d, double w) { return fmin(1.0, fmax(0.0, 0.5 - d / w)); }

/* Inlay at angle phi (radians around the axis, 0 = facing the camera) and
 * relative height t: two white bands with black borders, a ring of
 * medallions (white ring, black crane-dot) on the belly, and petals above
 * the foot. Returns the glaze colour with the inlay painted in. */
static rgb inlay(double phi, double t, double r_px, double H, double px)
{
    rgb c = glaze;
    double y = t * H;
    /* Bands: (centre height fraction, half width px). */
    static const double bands[][2] = {{0.80, 5.0}, {0.20, 4.0}};
    for (int i = 0; i < 2; i++) {
        double d = fabs(y - bands[i][0] * H);
        c = mix(c, black_inlay, smooth_in(d - bands[i][1] - 2.5, px));
        c = mix(c, white_inlay, smooth_in(d - bands[i][1], px));
    }
    /* Medallions every 45 degrees on the belly, in arc-length units. */
    double step = M_PI / 4, k = round(phi / step);
    double du = (phi - k * step) * r_px, dv = y - 0.43 * H;
    double d = hypot(du, dv), R = 0.062 * H;
    c = mix(c, white_inlay, smooth_in(fabs(d - R) - 3.0, px));
    c = mix(c, black_inlay, smooth_in(d - 0.28 * R, px));
    /* Petals above the foot band: pointed arches every 30 degrees. */
    double pstep = M_PI / 6, pk = round(phi / pstep);
    double a = fabs(phi - pk * pstep) * r_px / (0.5 * pstep * r_px); /* 0 at the petal's middle, 1 at its edge */
    double top = 0.27 * H + 0.07 * H * (1.0 - a * a);
    if (y > 0.245 * H)
        c = mix(c, white_inlay, smooth_in(fabs(y - top) - 1.6, px));
    return c;
}

/* Studio background: warm light gray, lighter at the top, a soft vignette. */
static rgb background(double x, double y, int W, int Hi)
{
    double t = y / Hi, vx = (x / W - 0.5) * 1.6, vy = (t - 0.45) * 1.2;
    double v = 0.93 - 0.08 * t - 0.05 * (vx * vx + vy * vy);
    return (rgb){v, v * 0.985, v * 0.955};
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: draw_demo_photo OUT.png\n");
        return 2;
    }
    synth_params p = synth_defaults(SYNTH_VASE, 900, 1200);
    p.tilt_deg = 1.0;
    p.rgba = 1; /* alpha = exact coverage of the outline */
    image_t cov;
    if (synth_draw(&p, &cov) != 0) {
        fprintf(stderr, "draw_demo_photo: cannot draw\n");
        return 1;
    }
    synth_truth t = synth_truth_of(&p);
    vec2 d = t.axis_direction, n = v2(-d.y, d.x);
    double H = t.height_px;
    /* Light from the upper left, in front; a camera looking along -z. */
    const double L[3] = {-0.45, 0.45, 0.77};
    image_t out = image_alloc(p.width, p.height, 3);
    if (!out.data)
        return 1;
    for (int j = 0; j < p.height; j++)
        for (int i = 0; i < p.width; i++) {
            size_t px = (size_t)j * p.width + i;
            double alpha = cov.data[4 * px + 3];
            rgb c = background(i + 0.5, j + 0.5, p.width, p.height);
            if (alpha > 0) {
                vec2 rel = v2_sub(v2(i + 0.5, j + 0.5), t.axis_origin);
                double h = fmin(fmax(v2_dot(rel, d), 0.0), H), s = v2_dot(rel, n);
                double r = synth_radius(&p, h);
                double x = fmax(-1.0, fmin(1.0, s / r)), phi = asin(x);
                /* Surface normal: around the axis by phi, tilted by the profile slope dr/dh. */
                double slope = (synth_radius(&p, fmin(H, h + 0.5)) - synth_radius(&p, fmax(0.0, h - 0.5))) /
                               (fmin(H, h + 0.5) - fmax(0.0, h - 0.5));
                double nx = sin(phi), nz = cos(phi), ny = -slope, len = sqrt(nx * nx + ny * ny + nz * nz);
                nx /= len, ny /= len, nz /= len;
                double diffuse = fmax(0.0, nx * L[0] + ny * L[1] + nz * L[2]);
                /* Blinn-Phong highlight of the glaze (half vector between light and view). */
                double hx = L[0], hy = L[1], hz = L[2] + 1.0, hl = sqrt(hx * hx + hy * hy + hz * hz);
                double spec = pow(fmax(0.0, (nx * hx + ny * hy + nz * hz) / hl), 60.0);
                rgb base = inlay(phi, h / H, r, H, 1.0);
                double shade = 0.45 + 0.6 * diffuse;
                rgb lit = {base.r * shade + 0.35 * spec, base.g * shade + 0.35 * spec, base.b * shade + 0.35 * spec};
                c = mix(c, lit, alpha);
            }
            out.data[3 * px] = (float)c.r, out.data[3 * px + 1] = (float)c.g, out.data[3 * px + 2] = (float)c.b;
        }
    char err[256];
    int rc = synth_write(argv[1], &out, 8, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "draw_demo_photo: %s: %s\n", argv[1], err);
    image_free(&out);
    image_free(&cov);
    return rc ? 1 : 0;
}
