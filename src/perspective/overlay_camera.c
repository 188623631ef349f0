/* The perspective layers of the overlay (recon_camera.h), drawn with
 * cairo on a copy of the picture. */
#include "celadon/recon_camera.h"

#include <cairo.h>
#include <math.h>
#include <string.h>

#include "celadon/overlay.h"
#include "perspective/perspective_internal.h"

enum { CURVE_STEPS = 360 };

const uint8_t overlay_camera_colours[OVERLAY_CAMERA_LAYER_COUNT][3] = {
    [OVERLAY_CAMERA_ELLIPSES] = {0, 158, 115},
    [OVERLAY_CAMERA_SECTIONS] = {86, 180, 233},
};

static void set_colour(cairo_t *cr, overlay_camera_layer layer)
{
    const uint8_t *c = overlay_camera_colours[layer];
    cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

/* A fitted ellipse (a line when b = 0), through the camera frame. */
static void path_ellipse(cairo_t *cr, const recon_camera *cam, const recon_ellipse *e)
{
    for (int k = 0; k <= CURVE_STEPS; k++) {
        double t = 2 * M_PI * k / CURVE_STEPS;
        vec2 p = recon_camera_to_image(cam, v2(e->a * cos(t), e->w0 + e->b * sin(t)));
        if (k == 0)
            cairo_move_to(cr, p.x, p.y);
        else
            cairo_line_to(cr, p.x, p.y);
    }
}

/* The meridian's radius at height h, from its samples (increasing h). */
static double radius_at(const recon_meridian *mer, double h)
{
    const vec2 *s = mer->points;
    int i = 0;
    while (i + 2 < mer->n_points && s[i + 1].y < h)
        i++;
    double t = s[i + 1].y > s[i].y ? (h - s[i].y) / (s[i + 1].y - s[i].y) : 0;
    return s[i].x + fmin(fmax(t, 0), 1) * (s[i + 1].x - s[i].x);
}

/* Half a cross-section: phi from phi0 to phi0 + pi. */
static void path_section(cairo_t *cr, const recon_camera *cam, const recon_meridian *mer, double h, double phi0)
{
    double r = radius_at(mer, h);
    for (int k = 0; k <= CURVE_STEPS / 2; k++) {
        vec2 p = recon_camera_project(cam, mer, r, h, phi0 + M_PI * k / (CURVE_STEPS / 2));
        if (k == 0)
            cairo_move_to(cr, p.x, p.y);
        else
            cairo_line_to(cr, p.x, p.y);
    }
}

int overlay_draw_camera(uint8_t *rgb, int width, int height, const recon_camera *cam, const recon_meridian *mer,
                        int n_sections)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(s);
        return -1;
    }
    cairo_surface_flush(s);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int j = 0; j < height; j++) { /* RGB24 is one native-endian 0xXXRRGGBB word per pixel */
        uint32_t *row = (uint32_t *)(data + (size_t)j * stride);
        const uint8_t *in = rgb + (size_t)j * width * 3;
        for (int i = 0; i < width; i++)
            row[i] = (uint32_t)in[3 * i] << 16 | (uint32_t)in[3 * i + 1] << 8 | in[3 * i + 2];
    }
    cairo_surface_mark_dirty(s);
    cairo_t *cr = cairo_create(s);
    double lw = overlay_line_width(width, height), dash[1] = {4 * lw};
    cairo_set_line_width(cr, lw);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    set_colour(cr, OVERLAY_CAMERA_ELLIPSES);
    path_ellipse(cr, cam, &cam->base);
    cairo_stroke(cr);
    path_ellipse(cr, cam, &cam->rim);
    cairo_stroke(cr);
    set_colour(cr, OVERLAY_CAMERA_SECTIONS);
    for (int k = 1; k <= n_sections; k++) {
        double h = (double)k / (n_sections + 1);
        cairo_set_dash(cr, NULL, 0, 0);
        path_section(cr, cam, mer, h, 0); /* the near half: phi in [0, pi], pi/2 facing the camera */
        cairo_stroke(cr);
        cairo_set_dash(cr, dash, 1, 0);
        path_section(cr, cam, mer, h, M_PI);
        cairo_stroke(cr);
    }
    cairo_destroy(cr);
    cairo_surface_flush(s);
    for (int j = 0; j < height; j++) {
        const uint32_t *row = (const uint32_t *)(data + (size_t)j * stride);
        uint8_t *out = rgb + (size_t)j * width * 3;
        for (int i = 0; i < width; i++) {
            out[3 * i] = (uint8_t)(row[i] >> 16);
            out[3 * i + 1] = (uint8_t)(row[i] >> 8);
            out[3 * i + 2] = (uint8_t)row[i];
        }
    }
    cairo_surface_destroy(s);
    return 0;
}
