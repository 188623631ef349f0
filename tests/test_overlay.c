/* Overlay: each layer must be drawn where the geometry it shows is, in its
 * colour, on the right side, and the photo must show through elsewhere. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "celadon/overlay.h"
#include "support/synth_vessel.h"

typedef struct {
    synth_params p;
    image_t img;
    recon_result res;
    bspline_t curve;
} scene;

enum { CONTOUR_SHIFT = 8 };

/* A drawn vase and a hand-made extraction result from its true geometry:
 * the contour is the outline (left side down, right side up), the curve
 * a cubic B-spline whose 40 control points lie on the true profile (so it
 * follows the outline to a fraction of a pixel). */
static void make_scene(scene *s, double tilt_deg, recon_side side)
{
    /* Large enough for 3 px lines: the pixel holding any point of a line is then
     * fully covered (its centre is within 0.71 px of the line). */
    s->p = synth_defaults(SYNTH_VASE, 900, 1200);
    s->p.tilt_deg = tilt_deg;
    s->p.subrows = 1;
    cr_assert_eq(synth_draw(&s->p, &s->img), 0);
    synth_truth t = synth_truth_of(&s->p);
    recon_result *r = &s->res;
    *r = (recon_result){0};
    r->axis_origin = t.axis_origin;
    r->axis_direction = t.axis_direction;
    r->tilt_deg = t.tilt_deg;
    r->side_used = side;
    for (int k = 0; k < CORNER_COUNT; k++)
        r->corners[k] = t.corners[k];
    int rows = s->p.height;
    cr_assert_not_null(r->contour = malloc(2 * (size_t)rows * sizeof(vec2)));
    double xl[rows], xr[rows];
    int ys[rows], n = 0;
    for (int y = 0; y < rows; y++)
        if (synth_silhouette_x(&s->p, y + 0.5, &xl[n], &xr[n]))
            ys[n++] = y;
    /* On the side not chosen the contour runs CONTOUR_SHIFT px outside the
     * outline, clear of the curve drawn mirrored over it. */
    double shift_l = side == RECON_SIDE_LEFT ? 0 : CONTOUR_SHIFT, shift_r = side == RECON_SIDE_LEFT ? CONTOUR_SHIFT : 0;
    for (int i = 0; i < n; i++)
        r->contour[r->n_contour++] = v2(xl[i] - shift_l, ys[i] + 0.5);
    for (int i = n - 1; i >= 0; i--)
        r->contour[r->n_contour++] = v2(xr[i] + shift_r, ys[i] + 0.5);
    r->pca_mean = v2_add(t.axis_origin, v2_scale(t.axis_direction, 0.45 * t.height_px));
    r->pca_axes[0] = t.axis_direction;
    r->pca_axes[1] = v2(-t.axis_direction.y, t.axis_direction.x);
    r->pca_eigenvalues[0] = pow(0.25 * t.height_px, 2);
    r->pca_eigenvalues[1] = pow(0.08 * t.height_px, 2);
    r->n_polyline = 2;
    cr_assert_not_null(r->polyline = malloc(2 * sizeof(vec2)));
    r->polyline[0] = v2(synth_radius(&s->p, 0), 0);
    r->polyline[1] = v2(synth_radius(&s->p, t.height_px), t.height_px);

    const int nc = 40;
    cr_assert_eq(bspline_init(&s->curve, 3, nc), 0);
    for (int i = 0; i < nc + 4; i++)
        s->curve.knots[i] = i < 4 ? 0.0 : i >= nc ? 1.0 : (i - 3.0) / (nc - 3.0);
    for (int i = 0; i < nc; i++) {
        double h = t.height_px * i / (nc - 1.0);
        s->curve.ctrl[i] = v2(synth_radius(&s->p, h), h);
    }
}

static void free_scene(scene *s)
{
    free(s->res.contour);
    free(s->res.polyline);
    bspline_free(&s->curve);
    image_free(&s->img);
}

static const uint8_t *pixel(const uint8_t *rgb, int w, vec2 p)
{
    return rgb + 3 * ((size_t)floor(p.y) * w + (size_t)floor(p.x));
}

static int has_colour(const uint8_t *px, overlay_layer layer)
{
    for (int k = 0; k < 3; k++)
        if (abs(px[k] - overlay_colours[layer][k]) > 2)
            return 0;
    return 1;
}

/* Within a third of the way from the layer's colour to black or white. */
static int mostly_colour(const uint8_t *px, overlay_layer layer)
{
    for (int k = 0; k < 3; k++)
        if (abs(px[k] - overlay_colours[layer][k]) > 85)
            return 0;
    return 1;
}

static void check_layers(double tilt_deg, recon_side side)
{
    scene s;
    make_scene(&s, tilt_deg, side);
    uint8_t *rgb = overlay_render(&s.img, &s.res, &s.curve);
    cr_assert_not_null(rgb);
    int W = s.img.width;
    synth_truth t = synth_truth_of(&s.p);

    /* Along the height, away from the corners: the curve on the true
     * outline of both sides (the profile revolved: mirrored across the
     * axis, thinner), the contour outside the other one, the axis on the
     * true axis. */
    for (double f = 0.15; f <= 0.85; f += 0.05) {
        vec2 on_axis = v2_add(t.axis_origin, v2_scale(t.axis_direction, f * t.height_px));
        double xl, xr;
        cr_assert(synth_silhouette_x(&s.p, floor(on_axis.y) + 0.5, &xl, &xr));
        vec2 left = v2(xl, floor(on_axis.y) + 0.5), right = v2(xr, left.y);
        vec2 chosen = side == RECON_SIDE_LEFT ? left : right, other = side == RECON_SIDE_LEFT ? right : left;
        cr_expect(has_colour(pixel(rgb, W, chosen), OVERLAY_CURVE), "curve missing at (%.1f, %.1f)", chosen.x,
                  chosen.y);
        /* drawn 1.5 px wide: no pixel need be covered whole, but the one
         * nearest the line is mostly the curve's colour */
        int near = 0;
        for (int dx = -1; dx <= 1; dx++)
            near |= mostly_colour(pixel(rgb, W, v2(other.x + dx, other.y)), OVERLAY_CURVE);
        cr_expect(near, "mirrored curve missing at (%.1f, %.1f)", other.x, other.y);
        vec2 beside = v2(other.x + (side == RECON_SIDE_LEFT ? CONTOUR_SHIFT : -CONTOUR_SHIFT), other.y);
        cr_expect(has_colour(pixel(rgb, W, beside), OVERLAY_CONTOUR), "contour missing at (%.1f, %.1f)", beside.x,
                  beside.y);
        /* The major PCA arrow covers the axis from the mean (0.45 H) to 0.70 H. */
        if (f < 0.42 || f > 0.78)
            cr_expect(has_colour(pixel(rgb, W, on_axis), OVERLAY_AXIS), "axis missing at (%.1f, %.1f)", on_axis.x,
                      on_axis.y);
    }
    /* Corners are drawn last and the legend keeps clear of the vessel. */
    for (int k = 0; k < CORNER_COUNT; k++)
        cr_expect(has_colour(pixel(rgb, W, t.corners[k]), OVERLAY_CORNERS), "corner %d missing", k);
    /* Both PCA arrows, halfway along them (drawn over the axis). */
    for (int k = 0; k < 2; k++) {
        vec2 pca = v2_add(s.res.pca_mean, v2_scale(s.res.pca_axes[k], 0.5 * sqrt(s.res.pca_eigenvalues[k])));
        cr_expect(has_colour(pixel(rgb, W, pca), OVERLAY_PCA), "PCA arrow %d missing", k);
    }

    /* Far from every shape (bottom corners of the photo): the lightened photo. */
    for (int k = 0; k < 2; k++) {
        int x = k ? W - 3 : 2, y = s.img.height - 3;
        const float *src = s.img.data + ((size_t)y * W + x) * 3;
        for (int c = 0; c < 3; c++) {
            double expect = OVERLAY_PHOTO_WEIGHT * lrintf(255.0f * src[c]) + (1 - OVERLAY_PHOTO_WEIGHT) * 255.0;
            cr_expect(fabs(rgb[3 * ((size_t)y * W + x) + c] - expect) <= 1.0);
        }
    }
    free(rgb);
    free_scene(&s);
}

Test(overlay, layers_on_the_right_side) { check_layers(0.0, RECON_SIDE_RIGHT); }

Test(overlay, layers_on_the_left_side_of_a_tilted_vessel) { check_layers(-6.0, RECON_SIDE_LEFT); }

Test(overlay, line_width_grows_with_the_photo)
{
    cr_expect_eq(overlay_line_width(300, 400), 2.0);
    cr_expect_eq(overlay_line_width(1200, 900), 3.0);
}

Test(overlay, transparent_background_shows_white)
{
    scene s;
    make_scene(&s, 0.0, RECON_SIDE_RIGHT);
    /* The same vessel as RGBA: colour black where transparent, alpha = coverage. */
    image_t rgba = image_alloc(s.img.width, s.img.height, 4);
    cr_assert_not_null(rgba.data);
    rgba.has_alpha = 1;
    size_t n = (size_t)s.img.width * s.img.height;
    for (size_t i = 0; i < n; i++)
        rgba.data[4 * i + 3] = 0.0f;
    uint8_t *rgb = overlay_render(&rgba, &s.res, &s.curve);
    cr_assert_not_null(rgb);
    /* Far from every shape: white, lightened (still white). */
    size_t far = (size_t)(s.img.height - 3) * s.img.width + 2;
    for (int c = 0; c < 3; c++)
        cr_expect_eq(rgb[3 * far + c], 255);
    free(rgb);
    image_free(&rgba);
    free_scene(&s);
}
