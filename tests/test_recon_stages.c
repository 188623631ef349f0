/* The hand-written stages against independent truths: Suzuki–Abe border
 * following on hand-made masks (checked against a brute-force border set),
 * and the sub-pixel edge on rows whose pixels are the exact coverage of a
 * straight edge at a known fractional position (also behind a dark limb
 * with a band like the backdrop inside it); and the parts of outlines drawn
 * from a known body: a flaring neck above a tall handle is the body's. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/recon_internal.h"

/* Mask from rows of '#' (object) and '.' (background). */
static uint8_t *mask_from(const char **rows, int *w, int *h)
{
    *h = 0;
    while (rows[*h])
        (*h)++;
    *w = (int)strlen(rows[0]);
    uint8_t *m = malloc((size_t)*w * *h);
    for (int j = 0; j < *h; j++)
        for (int i = 0; i < *w; i++)
            m[j * *w + i] = rows[j][i] == '#';
    return m;
}

/* Brute force: label the background 4-components (outside the image counts
 * as the outer one, label 1), then a border of background component c is the
 * set of object pixels 4-adjacent to c. */
static int *bg_labels(const uint8_t *m, int w, int h)
{
    int *lab = calloc((size_t)w * h, sizeof *lab), *stack = malloc((size_t)w * h * sizeof *stack), next = 2;
    for (int s = 0; s < w * h; s++) {
        if (m[s] || lab[s])
            continue;
        int outer = 0, top = 0;
        /* flood fill, noting whether it reaches the frame */
        int cur = next++;
        lab[s] = cur;
        stack[top++] = s;
        int *members = malloc((size_t)w * h * sizeof *members), nm = 0;
        while (top) {
            int p = stack[--top], x = p % w, y = p / w;
            members[nm++] = p;
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1)
                outer = 1;
            const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
            for (int k = 0; k < 4; k++) {
                int u = x + dx[k], v = y + dy[k];
                if (u < 0 || v < 0 || u >= w || v >= h)
                    continue;
                int q = v * w + u;
                if (!m[q] && !lab[q]) {
                    lab[q] = cur;
                    stack[top++] = q;
                }
            }
        }
        if (outer)
            for (int k = 0; k < nm; k++)
                lab[members[k]] = 1;
        free(members);
    }
    free(stack);
    return lab;
}

/* 1 when pixel (x, y) (an object pixel) touches background label L. */
static int touches(const uint8_t *m, const int *lab, int w, int h, int x, int y, int L)
{
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; k++) {
        int u = x + dx[k], v = y + dy[k];
        if (u < 0 || v < 0 || u >= w || v >= h) {
            if (L == 1)
                return 1;
            continue;
        }
        if (!m[v * w + u] && lab[v * w + u] == L)
            return 1;
    }
    return 0;
}

/* Every traced border: consecutive points 8-adjacent (closed), and its point
 * set equals the brute-force border of the background it faces. */
static void check_borders(const uint8_t *m, int w, int h, const recon_border_set *bs)
{
    int *lab = bg_labels(m, w, h);
    for (int b = 0; b < bs->n_borders; b++) {
        const recon_border *B = &bs->borders[b];
        const int *p = bs->points + 2 * B->start;
        for (int k = 0; k < B->count; k++) {
            int k2 = (k + 1) % B->count;
            cr_assert_leq(abs(p[2 * k] - p[2 * k2]), 1, "border %d not 8-connected at %d", b, k);
            cr_assert_leq(abs(p[2 * k + 1] - p[2 * k2 + 1]), 1);
            cr_assert(m[p[2 * k + 1] * w + p[2 * k]], "border point on background");
        }
        /* The background it faces: the raster scan starts an outer border at
         * an object pixel whose left neighbour is background, a hole border
         * at one whose right neighbour is. */
        int x0 = p[0] + (B->is_hole ? 1 : -1), y0 = p[1];
        int L = (x0 < 0 || x0 >= w) ? 1 : lab[y0 * w + x0];
        cr_assert_geq(L, 1, "border %d faces no background", b);
        /* Set equality with the brute force, restricted to this object: the
         * brute-force pixels 8-connected to the border's first point. */
        uint8_t *in = calloc((size_t)w * h, 1);
        for (int k = 0; k < B->count; k++)
            in[p[2 * k + 1] * w + p[2 * k]] = 1;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                if (m[y * w + x] && touches(m, lab, w, h, x, y, L) && !in[y * w + x]) {
                    /* only pixels of the same object count: flood from p[0] */
                    uint8_t *obj = calloc((size_t)w * h, 1);
                    int *st = malloc((size_t)w * h * sizeof *st), top = 0;
                    obj[p[1] * w + p[0]] = 1;
                    st[top++] = p[1] * w + p[0];
                    while (top) {
                        int q = st[--top], qx = q % w, qy = q / w;
                        for (int dy = -1; dy <= 1; dy++)
                            for (int dx = -1; dx <= 1; dx++) {
                                int u = qx + dx, v = qy + dy;
                                if (u >= 0 && v >= 0 && u < w && v < h && m[v * w + u] && !obj[v * w + u]) {
                                    obj[v * w + u] = 1;
                                    st[top++] = v * w + u;
                                }
                            }
                    }
                    int same = obj[y * w + x];
                    free(obj);
                    free(st);
                    cr_assert(!same, "border %d misses pixel (%d,%d)", b, x, y);
                }
        free(in);
    }
    free(lab);
}

static recon_border_set trace(const char **rows, int *w, int *h, uint8_t **m)
{
    *m = mask_from(rows, w, h);
    recon_border_set bs;
    cr_assert_eq(recon_border_follow(*m, *w, *h, &bs), 0);
    check_borders(*m, *w, *h, &bs);
    return bs;
}

Test(recon_border, single_pixel)
{
    const char *rows[] = {"...", ".#.", "...", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    cr_assert_eq(bs.n_borders, 1);
    cr_assert_eq(bs.borders[0].count, 1);
    cr_assert_eq(bs.points[0], 1);
    cr_assert_eq(bs.points[1], 1);
    cr_assert_eq(bs.borders[0].is_hole, 0);
    cr_assert_eq(bs.borders[0].parent, -1);
    recon_border_set_free(&bs);
    free(m);
}

Test(recon_border, one_pixel_lines_go_there_and_back)
{
    const char *rows[] = {".....", ".###.", ".....", ".#...", ".#...", ".#...", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    cr_assert_eq(bs.n_borders, 2);
    /* A line of n pixels is traced out and back: 2n - 2 points. */
    cr_assert_eq(bs.borders[0].count, 4);
    cr_assert_eq(bs.borders[1].count, 4);
    recon_border_set_free(&bs);
    free(m);
}

Test(recon_border, diagonal_neighbours_are_one_object)
{
    const char *rows[] = {"......", ".#....", "..#...", "...#..", "....#.", "......", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    cr_assert_eq(bs.n_borders, 1, "8-connected diagonal: one border");
    cr_assert_eq(bs.borders[0].count, 6);
    recon_border_set_free(&bs);
    free(m);
}

Test(recon_border, holes_and_hierarchy)
{
    const char *rows[] = {"...........", ".#########.", ".#.......#.", ".#.##.##.#.", ".#.##.##.#.",
                          ".#.......#.", ".#########.", "...........", "..##.......", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    /* ring outer, ring hole, two inner blocks (inside the hole), one block outside */
    cr_assert_eq(bs.n_borders, 5);
    int outer = 0, holes = 0;
    for (int b = 0; b < bs.n_borders; b++) {
        const recon_border *B = &bs.borders[b];
        if (B->is_hole) {
            holes++;
            cr_assert_eq(B->parent, 0, "the hole belongs to the ring");
        } else if (B->parent == -1)
            outer++;
        else
            cr_assert(bs.borders[B->parent].is_hole, "blocks inside the hole have it as parent");
    }
    cr_assert_eq(holes, 1);
    cr_assert_eq(outer, 2);
    recon_border_set_free(&bs);
    free(m);
}

Test(recon_border, concave_shape_and_rectangle_count)
{
    const char *rows[] = {"..........", ".########.", ".########.", ".##....##.", ".##....##.",
                          ".##....##.", "..........", "...#####..", "...#####..", "...#####..", "..........", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    cr_assert_eq(bs.n_borders, 2);
    /* A filled 5x3 rectangle: 2(5+3) - 4 border pixels, each once. */
    cr_assert_eq(bs.borders[1].count, 12);
    recon_border_set_free(&bs);
    free(m);
}

Test(recon_border, object_on_image_frame)
{
    const char *rows[] = {"###", "###", NULL};
    int w, h;
    uint8_t *m;
    recon_border_set bs = trace(rows, &w, &h, &m);
    cr_assert_eq(bs.n_borders, 1);
    cr_assert_eq(bs.borders[0].count, 6);
    recon_border_set_free(&bs);
    free(m);
}

/* ---- Douglas–Peucker */

/* ---- the sub-pixel edge */

/* One row of colours crossed by the straight edge x = xe + slope (y - 0.5)
 * (y in [0, 1) over the row): each pixel is bg + a (fg - bg), a the
 * fraction of its area on the object's side (object left of the edge for
 * side +1, right of it for side -1), by 4000 sub-rows (exact in x). */
static void edge_row(float *row, int w, double xe, double slope, int side, const float fg[3], const float bg[3])
{
    for (int i = 0; i < w; i++) {
        double a = 0;
        for (int k = 0; k < 4000; k++) {
            double x = xe + slope * ((k + 0.5) / 4000 - 0.5) - i; /* the edge within pixel i */
            double left = x < 0 ? 0 : (x > 1 ? 1 : x);            /* the part of the pixel left of it */
            a += side > 0 ? left : 1 - left;
        }
        a /= 4000;
        for (int c = 0; c < 3; c++)
            row[3 * i + c] = (float)(bg[c] + a * (fg[c] - bg[c]));
    }
}

Test(recon_subpixel, known_fractional_edges)
{
    static const float fg[3] = {0.20f, 0.50f, 0.30f}, bg[3] = {0.90f, 0.90f, 0.85f};
    static const double xs[] = {20.0, 20.13, 20.5, 20.87, 21.0}, slopes[] = {0, 0.6, -1.7, 2.5};
    float row[3 * 48];
    double worst = 0;
    for (int side = -1; side <= 1; side += 2)
        for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++)
            for (size_t m = 0; m < sizeof slopes / sizeof slopes[0]; m++) {
                double xe = xs[k], sl = slopes[m];
                edge_row(row, 48, xe, sl, side, fg, bg);
                /* the mask's outermost object pixel: the last (first) one the
                 * object covers at all */
                int i0 = side > 0 ? (int)ceil(xe + 0.5 * fabs(sl)) - 1 : (int)floor(xe - 0.5 * fabs(sl));
                recon_edge e = recon_subpixel_edge(&(recon_signal){row, 48, 3}, i0, side, sl, 0.01);
                cr_assert(e.ok, "side %d edge %.2f slope %.1f: no edge", side, xe, sl);
                double err = fabs(e.x - xe);
                worst = fmax(worst, err);
                cr_expect_leq(err, 0.01, "side %d edge %.2f slope %.1f: found at %.4f", side, xe, sl, e.x);
            }
    cr_log_info("sub-pixel edge: worst error %.5f px over 40 rows", worst);
}

/* Every position within a pixel, not a few: the edge at xe = 20 + k/40
 * for k = 0..39 and slopes up to 2.5 px a row, each side. An edge computed
 * on whole pixels anywhere (in either pass: a window placed from a rounded
 * first estimate misses the pixel the edge's far end crosses) is off by a
 * tenth of a pixel or more somewhere in the sweep. */
Test(recon_subpixel, every_fraction_of_a_pixel)
{
    static const float fg[3] = {0.35f, 0.25f, 0.20f}, bg[3] = {0.95f, 0.95f, 0.97f};
    static const double slopes[] = {0, 0.3, 0.8, 1.4, -1.9, 2.5};
    float row[3 * 48];
    double worst = 0, worst_xe = 0, worst_sl = 0;
    for (int side = -1; side <= 1; side += 2)
        for (int k = 0; k < 40; k++)
            for (size_t m = 0; m < sizeof slopes / sizeof slopes[0]; m++) {
                double xe = 20.0 + k / 40.0, sl = slopes[m];
                edge_row(row, 48, xe, sl, side, fg, bg);
                int i0 = side > 0 ? (int)ceil(xe + 0.5 * fabs(sl)) - 1 : (int)floor(xe - 0.5 * fabs(sl));
                recon_edge e = recon_subpixel_edge(&(recon_signal){row, 48, 3}, i0, side, sl, 0.01);
                cr_assert(e.ok, "side %d edge %.3f slope %.1f: no edge", side, xe, sl);
                if (fabs(e.x - xe) > worst)
                    worst = fabs(e.x - xe), worst_xe = xe, worst_sl = sl;
            }
    cr_log_info("sub-pixel edge over 480 positions: worst error %.5f px (edge %.3f, slope %.1f)", worst, worst_xe,
                worst_sl);
    cr_expect_leq(worst, 0.01, "off by %.4f px at edge %.3f, slope %.1f", worst, worst_xe, worst_sl);
}

/* A dark limb with a band just inside it as light as the backdrop, or
 * lighter (a glaze's shaded edge under a painted ring): the pixel inside
 * the ramp is no longer the colour the edge mixes with the backdrop. The
 * outline is still the dark limb's: every pixel the edge does not touch is
 * the band's colour, and the slope given is the mask's (a notch makes it
 * 2 px more than the edge's). */
Test(recon_subpixel, dark_limb_before_a_band_like_the_backdrop)
{
    static const float limb[3] = {0.26f, 0.32f, 0.28f}, bg[3] = {0.53f, 0.53f, 0.54f};
    static const float bands[2][3] = {{0.49f, 0.52f, 0.46f}, {0.60f, 0.61f, 0.59f}};
    static const double xs[] = {20.0, 20.3, 20.57, 20.9}, slopes[] = {0, 0.6, 1.0};
    float row[3 * 48];
    double worst = 0;
    for (int side = -1; side <= 1; side += 2)
        for (int b = 0; b < 2; b++)
            for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++)
                for (size_t m = 0; m < sizeof slopes / sizeof slopes[0]; m++) {
                    double xe = xs[k], sl = slopes[m], half = 0.5 * sl;
                    edge_row(row, 48, xe, sl, side, limb, bg);
                    for (int i = 0; i < 48; i++) {
                        /* the pixels the edge does not cross, on the object's side */
                        int inside = side > 0 ? i + 1 <= xe - half - 1 : i >= xe + half + 1;
                        if (inside)
                            memcpy(row + 3 * i, bands[b], sizeof bands[b]);
                    }
                    int i0 = side > 0 ? (int)ceil(xe + half) - 1 : (int)floor(xe - half);
                    recon_edge e = recon_subpixel_edge(&(recon_signal){row, 48, 3}, i0, side, sl + 2, 0.01);
                    cr_assert(e.ok, "side %d band %d edge %.2f slope %.1f: no edge", side, b, xe, sl);
                    double err = fabs(e.x - xe);
                    worst = fmax(worst, err);
                    cr_expect_leq(err, 0.01, "side %d band %d edge %.2f slope %.1f: found at %.4f", side, b, xe, sl,
                                  e.x);
                }
    cr_log_info("sub-pixel edge, dark limb before a light band: worst error %.5f px over 48 rows", worst);
}

/* ---- parts: a tall handle's zone ends where its attachment does */

/* The body: a belly narrowing to a neck at h = 330 that flares to the rim
 * at h = 499. */
static double flared_body(double h) { return 50 + 0.0004 * (h - 330) * (h - 330); }

/* Two symmetric loop handles: the body seen through their windows over
 * h in [100, 300) (200 rows), their outer edges 40 px out of it at the
 * window's ends, back on the body 30 rows beyond (the attachments). Above
 * the upper attachment the flaring neck is the body's on both sides: it may
 * not be taken for a handle (a zone as long as the window, reaching the
 * neck, left it to an extrapolation that it flares out of, and bridged it:
 * 11 px off at the drawn amphora's rim). */
Test(recon_parts, a_flaring_neck_above_a_tall_handle_is_the_body)
{
    enum { N = 500 };
    recon_outline_point side[2][N];
    for (int s = 0; s < 2; s++)
        for (int i = 0; i < N; i++) {
            double h = i, r = flared_body(h);
            if (h >= 300 && h < 330)
                r += 40 * (330 - h) / 30;
            else if (h >= 70 && h < 100)
                r += 40 * (h - 70) / 30;
            side[s][i] = (recon_outline_point){h, r, 600 - h, h >= 100 && h < 300};
        }
    recon_excluded parts[16];
    int n_parts = 0;
    double lr, excluded;
    cr_assert_eq(recon_resolve_parts(side[0], N, side[1], N, 0, 2.0, parts, 16, &n_parts, &lr, &excluded), 0);
    double worst = 0;
    for (int i = 340; i < N; i++) /* a bridged row (NAN) is off */
        worst = isnan(side[0][i].r) ? INFINITY : fmax(worst, fabs(side[0][i].r - flared_body(i)));
    for (int k = 0; k < n_parts; k++)
        cr_expect_gt(parts[k].row0, 600 - 340, "a part over rows %d..%d reaches the neck (h > 340: rows < 260)",
                     parts[k].row0, parts[k].row1);
    cr_expect_leq(worst, 1e-9, "the neck's profile is %.3f px off the body", worst);
    cr_log_info("flaring neck above a tall handle: %d parts, the neck within %.2g px, %.0f%% of rows excluded", n_parts,
                worst, 100 * excluded);
}
