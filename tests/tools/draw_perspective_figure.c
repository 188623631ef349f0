/* Draws docs/img/perspective-geometry.png, the figure of the "Perspective"
 * section of docs/algorithms-recon.md, from exact geometry: a flaring bowl
 * photographed through a pinhole (tests/support/pinhole_vessel) from 15
 * degrees above with a wide lens, so that the perspective shows.
 * Left: the image, with the base and rim ellipses, the vanishing line of
 * the cross-section planes, the principal point, imaged cross-sections, and
 * one outline point with the cross-section whose image touches the outline
 * there. Right: that cross-section seen from above, the camera, and the
 * viewing ray that grazes it at P, in front of the plane through the axis
 * parallel to the image. Run by `make perspective-figure`.
 *
 *   draw_perspective_figure OUT.png */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../support/pinhole_vessel.h"

enum { PANEL = 520, STEPS = 240 };

static double bowl(double t) { return 0.42 + 0.55 * t - 0.12 * t * t; }

static void rgb(cairo_t *cr, int r, int g, int b) { cairo_set_source_rgb(cr, r / 255.0, g / 255.0, b / 255.0); }

static void label(cairo_t *cr, double x, double y, const char *s)
{
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s);
    cairo_new_path(cr); /* text leaves a current point behind */
}

static void dot(cairo_t *cr, vec2 p, double r)
{
    cairo_new_path(cr);
    cairo_arc(cr, p.x, p.y, r, 0, 2 * M_PI);
    cairo_fill(cr);
}

/* The image of the circle at height t, radius R (heights); the near half
 * (phi in [0, pi], phi = pi/2 facing the camera) or the far half. */
static void circle_path(cairo_t *cr, const pinhole_params *p, double t, double R, int far, double s, vec2 o)
{
    for (int k = 0; k <= STEPS; k++) {
        double phi = (far ? M_PI : 0) + M_PI * k / STEPS;
        vec2 q = pinhole_project(p, v3(R * cos(phi), t, -R * sin(phi)));
        q = v2(o.x + s * q.x, o.y + s * q.y);
        if (k == 0)
            cairo_move_to(cr, q.x, q.y);
        else
            cairo_line_to(cr, q.x, q.y);
    }
}

/* Left panel: the photo's geometry. */
static void image_panel(cairo_t *cr, const pinhole_params *p)
{
    double s = (double)PANEL / p->height, x0 = 0.5 * (PANEL - s * p->width);
    vec2 o = v2(x0, 0);
    /* The vessel's outline, filled, from the exact extent on each row. */
    rgb(cr, 214, 226, 218);
    for (int j = 0; j < p->height; j++) {
        double xl, xr;
        if (pinhole_line_extent(p, j + 0.5, &xl, &xr))
            cairo_rectangle(cr, x0 + s * xl, s * j, s * (xr - xl), s + 0.2);
    }
    cairo_fill(cr);
    /* Cross-sections: the near half solid, the far half dashed. */
    double dash[1] = {4};
    cairo_set_line_width(cr, 1.0);
    rgb(cr, 86, 180, 233);
    for (int k = 1; k <= 4; k++) {
        double t = k / 5.0;
        for (int far = 0; far < 2; far++) {
            cairo_set_dash(cr, dash, far, 0);
            circle_path(cr, p, t, pinhole_radius(p, t), far, s, o);
            cairo_stroke(cr);
        }
    }
    cairo_set_dash(cr, NULL, 0, 0);
    /* Base and rim ellipses. */
    cairo_set_line_width(cr, 2.0);
    rgb(cr, 0, 158, 115);
    for (int t = 0; t <= 1; t++)
        for (int far = 0; far < 2; far++) {
            circle_path(cr, p, t, pinhole_radius(p, t), far, s, o);
            cairo_stroke(cr);
        }
    /* The imaged axis and the principal point. */
    vec2 a0 = pinhole_project(p, v3(0, -0.3, 0)), a1 = pinhole_project(p, v3(0, 1.6, 0));
    rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, x0 + s * a0.x, s * a0.y);
    cairo_line_to(cr, x0 + s * a1.x, s * a1.y);
    cairo_stroke(cr);
    double cx = x0 + s * 0.5 * p->width, cy = s * 0.5 * p->height;
    dot(cr, v2(cx, cy), 3);
    label(cr, cx + 6, cy + 14, "principal point");
    /* The vanishing line of the cross-section planes: w_h = f tan(e) above
     * the principal point (the camera is not rolled here). */
    double yh = s * (0.5 * p->height - p->focal_px * tan(p->elevation_deg * M_PI / 180));
    rgb(cr, 230, 159, 0);
    cairo_set_dash(cr, dash, 1, 0);
    cairo_move_to(cr, 4, yh);
    cairo_line_to(cr, PANEL - 4, yh);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    label(cr, 8, yh - 6, "vanishing line of the cross-section planes (horizon)");
    /* One outline point at mid-height and the cross-section touching it:
     * the one whose image reaches furthest on that row. */
    double yrow = pinhole_project(p, v3(0, 0.5, 0)).y, xl, xr, best_t = 0, best = -INFINITY;
    pinhole_line_extent(p, yrow, &xl, &xr);
    for (int k = 0; k <= 4000; k++) {
        double t = k / 4000.0, R = pinhole_radius(p, t);
        for (int q = 0; q < 720; q++) {
            double phi = M_PI * q / 720;
            vec2 im = pinhole_project(p, v3(R * cos(phi), t, -R * sin(phi)));
            if (fabs(im.y - yrow) < 0.5 && im.x > best)
                best = im.x, best_t = t;
        }
    }
    rgb(cr, 204, 0, 153);
    cairo_set_line_width(cr, 2.0);
    for (int far = 0; far < 2; far++) {
        cairo_set_dash(cr, dash, far, 0);
        circle_path(cr, p, best_t, pinhole_radius(p, best_t), far, s, o);
        cairo_stroke(cr);
    }
    cairo_set_dash(cr, NULL, 0, 0);
    dot(cr, v2(x0 + s * xr, s * yrow), 4);
    label(cr, x0 + s * xr + 10, s * yrow + 4, "the outline touches the");
    label(cr, x0 + s * xr + 10, s * yrow + 18, "image of one circle");
    rgb(cr, 0, 158, 115);
    label(cr, 8, PANEL - 34, "rim and base ellipses: the outline's top and bottom arcs");
    rgb(cr, 86, 180, 233);
    label(cr, 8, PANEL - 20, "imaged cross-sections (far half dashed)");
    rgb(cr, 0, 0, 0);
    label(cr, 8, 16, "the image");
}

/* Right panel: one cross-section from above. */
static void top_panel(cairo_t *cr, double x0)
{
    const double R = 70, D = 250; /* circle radius and camera distance, drawing units */
    vec2 O = v2(x0 + 0.45 * PANEL, 130), C = v2(O.x, O.y + D);
    /* The grazing point: OP perpendicular to CP, at the angle acos(R / D)
     * from OC; the ray leaves the camera at asin(R / D) from CO. */
    double a = asin(R / D), th = acos(R / D);
    vec2 P = v2(O.x + R * sin(th), O.y + R * cos(th));
    rgb(cr, 214, 226, 218);
    cairo_new_path(cr);
    cairo_arc(cr, O.x, O.y, R, 0, 2 * M_PI);
    cairo_fill_preserve(cr);
    rgb(cr, 204, 0, 153);
    cairo_set_line_width(cr, 2.0);
    cairo_stroke(cr);
    /* The plane through the axis parallel to the image, and the image line. */
    double dash[1] = {4};
    rgb(cr, 120, 120, 120);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, dash, 1, 0);
    cairo_move_to(cr, O.x - 170, O.y);
    cairo_line_to(cr, O.x + 170, O.y);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    label(cr, O.x - 200, O.y - 8, "plane of the axis");
    /* The two grazing rays and the ray through the axis. */
    rgb(cr, 0, 0, 0);
    for (int side = -1; side <= 1; side += 2) {
        vec2 Q = v2(O.x + side * (P.x - O.x), P.y), d = v2_norm(v2_sub(Q, C));
        cairo_move_to(cr, C.x, C.y);
        cairo_line_to(cr, C.x + 330 * d.x, C.y + 330 * d.y);
    }
    cairo_stroke(cr);
    dot(cr, O, 3);
    label(cr, O.x - 12, O.y + 18, "axis");
    dot(cr, C, 4);
    label(cr, C.x + 8, C.y + 4, "camera");
    /* P and the radius to it; the apparent half-width on the axis plane. */
    rgb(cr, 204, 0, 153);
    dot(cr, P, 4);
    cairo_move_to(cr, O.x, O.y);
    cairo_line_to(cr, P.x, P.y);
    cairo_stroke(cr);
    label(cr, P.x + 10, P.y + 16, "P: the ray grazes");
    label(cr, P.x + 10, P.y + 30, "the circle here");
    label(cr, 0.5 * (O.x + P.x) - 4, 0.5 * (O.y + P.y) + 16, "r");
    double w = D * tan(a); /* where the grazing ray crosses the axis plane */
    rgb(cr, 230, 159, 0);
    cairo_set_line_width(cr, 2.0);
    cairo_move_to(cr, O.x, O.y - 3);
    cairo_line_to(cr, O.x + w, O.y - 3);
    cairo_stroke(cr);
    label(cr, O.x + w + 8, O.y - 24, "the outline's half-width,");
    label(cr, O.x + w + 8, O.y - 10, "r D / sqrt(D^2 - r^2)");
    rgb(cr, 0, 0, 0);
    label(cr, x0 + 8, 16, "one cross-section, from above");
    label(cr, x0 + 8, PANEL - 48, "The grazing point P lies in front of the axis plane; with the");
    label(cr, x0 + 8, PANEL - 34, "height and slope of the wall the outline point fixes P, hence");
    label(cr, x0 + 8, PANEL - 20, "the circle's height and its radius r: the meridian r(h).");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: draw_perspective_figure OUT.png\n");
        return 2;
    }
    pinhole_params p = pinhole_defaults(SYNTH_BOWL, 15);
    p.radius = bowl;
    p.focal_px = 900; /* 37 degrees across: strong perspective */
    p.distance = 2.6;
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 2 * PANEL, PANEL);
    cairo_t *cr = cairo_create(s);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12);
    image_panel(cr, &p);
    top_panel(cr, PANEL);
    cairo_destroy(cr);
    int rc = cairo_surface_write_to_png(s, argv[1]) == CAIRO_STATUS_SUCCESS ? 0 : 1;
    cairo_surface_destroy(s);
    if (rc)
        fprintf(stderr, "draw_perspective_figure: cannot write %s\n", argv[1]);
    return rc;
}
