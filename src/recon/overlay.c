/* The diagnostic overlay (what it shows is in overlay.h). Shapes are drawn
 * anti-aliased: each layer first accumulates per-pixel coverage (the maximum
 * over its shapes, so joints of a polyline are not blended twice), then is
 * blended over the picture in its colour. */
#include "celadon/overlay.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon.h"

/* Okabe–Ito colours, distinguishable with colour-blindness; black for the axis. */
const uint8_t overlay_colours[OVERLAY_LAYER_COUNT][3] = {
    [OVERLAY_CONTOUR] = {0, 114, 178}, [OVERLAY_PCA] = {230, 159, 0}, [OVERLAY_AXIS] = {0, 0, 0},
    [OVERLAY_CURVE] = {204, 0, 153},   [OVERLAY_CORNERS] = {213, 94, 0},
};

static const char *const layer_labels[OVERLAY_LAYER_COUNT] = {
    [OVERLAY_CONTOUR] = "CONTOUR", [OVERLAY_PCA] = "PCA AXES", [OVERLAY_AXIS] = "AXIS",
    [OVERLAY_CURVE] = "B-SPLINE", [OVERLAY_CORNERS] = "CORNERS",
};

typedef struct {
    int w, h;
    uint8_t *rgb;
    float *cov;
    int x0, y0, x1, y1; /* pixels with coverage lie in [x0, x1] x [y0, y1] (empty when x0 > x1) */
} canvas;

double overlay_line_width(int width, int height)
{
    int m = width < height ? width : height;
    return fmax(2.0, m / 300.0);
}

/* Coverage of a segment of the given width with round ends: 1 within
 * width/2 of it, falling linearly to 0 over one pixel. */
static void cover_segment(canvas *cv, vec2 a, vec2 b, double width)
{
    double reach = 0.5 * width + 0.5;
    int x0 = (int)fmax(0, floor(fmin(a.x, b.x) - reach)), x1 = (int)fmin(cv->w - 1, ceil(fmax(a.x, b.x) + reach));
    int y0 = (int)fmax(0, floor(fmin(a.y, b.y) - reach)), y1 = (int)fmin(cv->h - 1, ceil(fmax(a.y, b.y) + reach));
    if (x0 > x1 || y0 > y1)
        return;
    cv->x0 = x0 < cv->x0 ? x0 : cv->x0, cv->x1 = x1 > cv->x1 ? x1 : cv->x1;
    cv->y0 = y0 < cv->y0 ? y0 : cv->y0, cv->y1 = y1 > cv->y1 ? y1 : cv->y1;
    vec2 ab = v2_sub(b, a);
    double len2 = v2_dot(ab, ab);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            vec2 p = v2(x + 0.5, y + 0.5), ap = v2_sub(p, a);
            double t = len2 > 0 ? fmin(1.0, fmax(0.0, v2_dot(ap, ab) / len2)) : 0.0;
            double d = v2_len(v2_sub(ap, v2_scale(ab, t)));
            float c = (float)fmin(1.0, reach - d);
            float *q = cv->cov + (size_t)y * cv->w + x;
            if (c > *q)
                *q = c;
        }
}

static void cover_disc(canvas *cv, vec2 c, double radius) { cover_segment(cv, c, c, 2.0 * radius); }

static void cover_polyline(canvas *cv, const vec2 *p, int n, int closed, double width)
{
    for (int i = 0; i + 1 < n; i++)
        cover_segment(cv, p[i], p[i + 1], width);
    if (closed && n > 2)
        cover_segment(cv, p[n - 1], p[0], width);
}

static void cover_arrow(canvas *cv, vec2 from, vec2 to, double width)
{
    cover_segment(cv, from, to, width);
    vec2 back = v2_sub(from, to);
    double len = v2_len(back);
    if (!(len > 0))
        return;
    double head = fmin(0.3 * len, 6.0 * width);
    back = v2_scale(back, head / len);
    double c = cos(0.45), s = sin(0.45);
    cover_segment(cv, to, v2_add(to, v2(c * back.x - s * back.y, s * back.x + c * back.y)), width);
    cover_segment(cv, to, v2_add(to, v2(c * back.x + s * back.y, -s * back.x + c * back.y)), width);
}

/* Blends the accumulated coverage in the given colour, then clears it. */
static void composite(canvas *cv, const uint8_t col[3])
{
    for (int y = cv->y0; y <= cv->y1; y++)
        for (int x = cv->x0; x <= cv->x1; x++) {
            size_t i = (size_t)y * cv->w + x;
            float c = cv->cov[i];
            if (c <= 0.0f)
                continue;
            for (int k = 0; k < 3; k++)
                cv->rgb[3 * i + k] = (uint8_t)lrintf(cv->rgb[3 * i + k] + c * (col[k] - cv->rgb[3 * i + k]));
            cv->cov[i] = 0.0f;
        }
    cv->x0 = cv->w, cv->y0 = cv->h, cv->x1 = -1, cv->y1 = -1;
}

static void fill_rect(canvas *cv, int x0, int y0, int x1, int y1, const uint8_t col[3], float opacity)
{
    for (int y = y0 < 0 ? 0 : y0; y < y1 && y < cv->h; y++)
        for (int x = x0 < 0 ? 0 : x0; x < x1 && x < cv->w; x++) {
            uint8_t *p = cv->rgb + 3 * ((size_t)y * cv->w + x);
            for (int k = 0; k < 3; k++)
                p[k] = (uint8_t)lrintf(p[k] + opacity * (col[k] - p[k]));
        }
}

/* Colours of the excluded parts, by kind (recon_part_kind). */
static const uint8_t part_colours[RECON_PART_KIND_COUNT][3] = {
    [RECON_PART_SHADOW] = {86, 180, 233}, [RECON_PART_STAND] = {0, 158, 115},
    [RECON_PART_HANDLE] = {240, 228, 66}, [RECON_PART_ASYMMETRY] = {213, 94, 0},
};

/* Tints an excluded part: its rows, on its side of the axis (both for side
 * 0). A part of the vessel's mask (a handle) tints the mask's pixels; a part
 * cut off the mask (a stand, a shadow) tints its rows faintly, within a
 * quarter of the vessel's width beside it. */
static void tint_part(canvas *cv, const recon_result *res, const recon_excluded *e)
{
    const uint8_t *col = part_colours[e->what];
    int cut_off = e->what == RECON_PART_STAND || e->what == RECON_PART_SHADOW;
    double bx0 = INFINITY, bx1 = -INFINITY;
    for (int i = 0; i < res->n_contour; i++)
        bx0 = fmin(bx0, res->contour[i].x), bx1 = fmax(bx1, res->contour[i].x);
    double margin = 0.25 * (bx1 - bx0);
    vec2 o = res->axis_origin, d = res->axis_direction, nrm = v2(-d.y, d.x);
    for (int y = e->row0 < 0 ? 0 : e->row0; y <= e->row1 && y < cv->h; y++)
        for (int x = 0; x < cv->w; x++) {
            double r = v2_dot(v2_sub(v2(x + 0.5, y + 0.5), o), nrm);
            if ((e->side < 0 && r > 0) || (e->side > 0 && r < 0))
                continue;
            int on_object = res->mask && res->mask[(size_t)y * cv->w + x];
            if (cut_off ? x < bx0 - margin || x > bx1 + margin : !on_object)
                continue;
            uint8_t *p = cv->rgb + 3 * ((size_t)y * cv->w + x);
            float a = cut_off ? 0.3f : 0.45f;
            for (int k = 0; k < 3; k++)
                p[k] = (uint8_t)lrintf(p[k] + a * (col[k] - p[k]));
        }
}

/* A 5x7 pixel font for the legend: rows top to bottom, bit 4 = leftmost column. */
static const uint8_t *glyph(char ch)
{
    static const uint8_t letters[26][7] = {
        {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E},
        {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}, {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C},
        {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}, {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10},
        {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}, {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11},
        {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}, {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C},
        {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F},
        {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}, {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11},
        {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10},
        {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}, {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11},
        {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}, {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04},
        {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}, {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04},
        {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}, {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11},
        {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F},
    };
    static const uint8_t digits[10][7] = {
        {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
        {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
        {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
        {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
        {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
    };
    static const uint8_t minus[7] = {0, 0, 0, 0x1F, 0, 0, 0}, dot[7] = {0, 0, 0, 0, 0, 0x0C, 0x0C};
    if (ch >= 'A' && ch <= 'Z')
        return letters[ch - 'A'];
    if (ch >= '0' && ch <= '9')
        return digits[ch - '0'];
    if (ch == '-')
        return minus;
    if (ch == '.')
        return dot;
    return NULL; /* space */
}

static void draw_text(canvas *cv, int x, int y, int scale, const char *text, const uint8_t col[3])
{
    for (; *text; text++, x += 6 * scale) {
        const uint8_t *g = glyph(*text);
        for (int r = 0; g && r < 7; r++)
            for (int c = 0; c < 5; c++)
                if (g[r] & (0x10 >> c))
                    fill_rect(cv, x + c * scale, y + r * scale, x + (c + 1) * scale, y + (r + 1) * scale, col, 1.0f);
    }
}

/* Overlap of the rectangles [x0, x1) x [y0, y1), in pixels. */
static double overlap_area(double ax0, double ay0, double ax1, double ay1, double bx0, double by0, double bx1,
                           double by1)
{
    return fmax(0.0, fmin(ax1, bx1) - fmax(ax0, bx0)) * fmax(0.0, fmin(ay1, by1) - fmax(ay0, by0));
}

/* The legend box: one swatch and label per layer, then the axis tilt and the
 * side; in the photo corner where it hides least of the contour's bounding box
 * (top-left first). */
static void draw_legend(canvas *cv, const recon_result *res, double width)
{
    static const uint8_t white[3] = {255, 255, 255}, ink[3] = {40, 40, 40};
    int m = cv->w < cv->h ? cv->w : cv->h;
    int s = m >= 600 ? 2 : 1, line = 11 * s, pad = 6 * s, swatch = 16 * s;
    char info[2][32];
    snprintf(info[0], sizeof info[0], "TILT %.2f DEG", res->tilt_deg);
    snprintf(info[1], sizeof info[1], "SIDE %s", res->side_used == RECON_SIDE_LEFT ? "LEFT" : "RIGHT");
    int kinds[RECON_PART_KIND_COUNT], nk = 0;
    for (int k = 0; k < RECON_PART_KIND_COUNT; k++) {
        int present = 0;
        for (int i = 0; i < res->n_excluded; i++)
            present |= res->excluded[i].what == (recon_part_kind)k;
        if (present)
            kinds[nk++] = k;
    }
    int rows = OVERLAY_LAYER_COUNT + nk + 2;
    int box_w = pad * 3 + swatch + 14 * 6 * s, box_h = pad * 2 + rows * line;
    if (box_w > cv->w || box_h > cv->h)
        return; /* too small a photo for a legend */
    double bx0 = INFINITY, by0 = INFINITY, bx1 = -INFINITY, by1 = -INFINITY;
    for (int i = 0; i < res->n_contour; i++) {
        bx0 = fmin(bx0, res->contour[i].x), bx1 = fmax(bx1, res->contour[i].x);
        by0 = fmin(by0, res->contour[i].y), by1 = fmax(by1, res->contour[i].y);
    }
    int x0 = 0, y0 = 0;
    double least = INFINITY;
    for (int k = 0; k < 4; k++) {
        int cx = k & 1 ? cv->w - box_w : 0, cy = k & 2 ? cv->h - box_h : 0;
        double a = overlap_area(cx, cy, cx + box_w, cy + box_h, bx0, by0, bx1, by1);
        if (a < least)
            least = a, x0 = cx, y0 = cy;
    }
    fill_rect(cv, x0, y0, x0 + box_w, y0 + box_h, white, 0.85f);
    for (int i = 0; i < rows; i++) {
        int y = y0 + pad + i * line, tx = x0 + 2 * pad + swatch;
        if (i >= OVERLAY_LAYER_COUNT + nk) {
            draw_text(cv, tx, y + s, s, info[i - OVERLAY_LAYER_COUNT - nk], ink);
            continue;
        }
        if (i >= OVERLAY_LAYER_COUNT) { /* an excluded kind: a swatch of its tint */
            int k = kinds[i - OVERLAY_LAYER_COUNT];
            char name[32];
            snprintf(name, sizeof name, "%s", recon_part_name((recon_part_kind)k));
            for (char *c = name; *c; c++)
                *c = (char)(*c >= 'a' && *c <= 'z' ? *c - 32 : *c);
            fill_rect(cv, x0 + pad, y + s, x0 + pad + swatch, y + 8 * s, part_colours[k], 0.8f);
            draw_text(cv, tx, y + s, s, name, ink);
            continue;
        }
        vec2 mid = v2(x0 + pad + 0.5 * swatch, y + 4.5 * s);
        if (i == OVERLAY_CORNERS)
            cover_disc(cv, mid, 1.6 * width);
        else
            cover_segment(cv, v2(x0 + pad, mid.y), v2(x0 + pad + swatch, mid.y), width);
        composite(cv, overlay_colours[i]);
        draw_text(cv, tx, y + s, s, layer_labels[i], ink);
    }
}

uint8_t *overlay_render(const image_t *photo, const recon_result *res, const bspline_t *curve)
{
    canvas cv = {photo->width, photo->height, NULL, NULL, photo->width, photo->height, -1, -1};
    size_t n = (size_t)cv.w * cv.h;
    cv.rgb = malloc(n * 3);
    cv.cov = calloc(n, sizeof(float));
    if (!cv.rgb || !cv.cov) {
        free(cv.rgb);
        free(cv.cov);
        return NULL;
    }
    /* The photo faded toward white, by the 8-bit level each channel rounds to. */
    uint8_t faded[256];
    for (long q = 0; q < 256; q++)
        faded[q] = (uint8_t)lrint(OVERLAY_PHOTO_WEIGHT * q + (1.0 - OVERLAY_PHOTO_WEIGHT) * 255.0);
    int C = photo->channels, colour = C >= 3;
    for (size_t i = 0; i < n; i++) {
        /* over white: a transparent background shows as white (opaque: a * v + 0 is v) */
        const float *px = photo->data + i * C;
        float a = photo->has_alpha ? px[C - 1] : 1.0f, white = 1.0f - a;
        uint8_t *out = cv.rgb + 3 * i;
        out[0] = faded[recon_to_u8(a * px[0] + white)];
        out[1] = faded[recon_to_u8(a * px[colour] + white)];
        out[2] = faded[recon_to_u8(a * px[2 * colour] + white)];
    }
    double width = overlay_line_width(cv.w, cv.h);

    for (int i = 0; i < res->n_excluded; i++)
        tint_part(&cv, res, &res->excluded[i]);
    cover_polyline(&cv, res->contour, res->n_contour, 1, width);
    composite(&cv, overlay_colours[OVERLAY_CONTOUR]);

    double H = res->n_polyline > 0 ? res->polyline[res->n_polyline - 1].y : 0.0;
    vec2 base = v2_sub(res->axis_origin, v2_scale(res->axis_direction, 0.05 * H));
    vec2 rim = v2_add(res->axis_origin, v2_scale(res->axis_direction, 1.05 * H));
    cover_segment(&cv, base, rim, width);
    cover_disc(&cv, res->axis_origin, 1.2 * width);
    composite(&cv, overlay_colours[OVERLAY_AXIS]);

    for (int k = 0; k < 2; k++) {
        double len = sqrt(fmax(0.0, res->pca_eigenvalues[k]));
        cover_arrow(&cv, res->pca_mean, v2_add(res->pca_mean, v2_scale(res->pca_axes[k], len)), width);
    }
    composite(&cv, overlay_colours[OVERLAY_PCA]);

    /* The curve as a polyline of about two points per pixel of height, on
     * both sides: the outline the revolved profile has. */
    double lo = curve->knots[0], hi = curve->knots[bspline_n_knots(curve) - 1];
    int steps = 64 + 2 * (int)fmin(1e5, fmax(0.0, H));
    for (int side = -1; side <= 1; side += 2) {
        vec2 prev = {0, 0};
        for (int i = 0; i <= steps; i++) {
            vec2 rh = bspline_eval(curve, lo + (hi - lo) * i / steps);
            vec2 p = recon_profile_to_image(res->axis_origin, res->axis_direction, rh.x, rh.y, side);
            if (i > 0)
                cover_segment(&cv, prev, p, side == (res->side_used == RECON_SIDE_LEFT ? -1 : 1) ? width : 0.5 * width);
            prev = p;
        }
    }
    composite(&cv, overlay_colours[OVERLAY_CURVE]);

    for (int k = 0; k < CORNER_COUNT; k++)
        cover_disc(&cv, res->corners[k], 1.6 * width);
    composite(&cv, overlay_colours[OVERLAY_CORNERS]);

    draw_legend(&cv, res, width);
    free(cv.cov);
    return cv.rgb;
}
