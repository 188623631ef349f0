/* The scene drawer of synthetic museum photographs (tests/support/
 * synth_scene) against independent truth: coverage integrates to the
 * analytic areas (profiles level, cylinders elevated), the elevated outline
 * is the brute-force union of the discs' ellipses, the caps have half-height
 * r sin e in the drawn pixels, the truth outline sits where the drawn pixels
 * put the edge, parts show where and on the side the truth says, the named
 * cases draw and only the cut one touches the border, and drawing is
 * deterministic. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "support/synth_jpeg.h"
#include "support/synth_raster.h"
#include "support/synth_scene.h"

/* One flat-coloured vessel on a flat backdrop, the widest point within 80%
 * of the width, the base at 85% of the height, the axis through the middle
 * of a pixel column. */
static synth_scene_params flat_scene(synth_profile profile, double elevation_deg, int width, int height)
{
    synth_scene_params p;
    memset(&p, 0, sizeof p);
    p.width = width;
    p.height = height;
    p.backdrop.kind = SYNTH_BACKDROP_FLAT;
    p.backdrop.wall[0] = p.backdrop.wall[1] = p.backdrop.wall[2] = 0.9f;
    p.vessel_count = 1;
    synth_scene_vessel *v = &p.vessels[0];
    v->glaze[0] = 0.2f, v->glaze[1] = 0.3f, v->glaze[2] = 0.25f;
    double H = fmin(0.7 * height, 0.8 * width / (2 * synth_profile_max_radius(profile)));
    v->body = (synth_body){profile, H, 1, v2(floor(0.5 * width) + 0.5, 0.85 * height), 0, elevation_deg};
    return p;
}

static double mask_sum(const image_t *m)
{
    double a = 0;
    for (int i = 0; i < m->width * m->height; i++)
        a += m->data[i];
    return a;
}

/* The named case drawn at width x height (the image is the caller's). */
static void draw_case(const char *name, int width, int height, synth_scene_params *p, synth_scene_truth *t,
                      image_t *img)
{
    cr_assert_eq(synth_scene_case(name, width, height, p), 0, "%s", name);
    cr_assert_eq(synth_scene_draw(p, img, NULL, t), 0, "%s", name);
}

/* ∫ 2 r(h) dh over [0, H] by Simpson's rule. */
static double level_area(const synth_body *b)
{
    const int n = 4000;
    double H = b->height_px, s = 0;
    for (int k = 0; k <= n; k++)
        s += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * 2 * synth_body_radius(b, H * k / n);
    return s * H / n / 3;
}

Test(synth_scene, level_coverage_integrates_to_profile_area)
{
    for (int prof = 0; prof < SYNTH_PROFILE_COUNT; prof++) {
        synth_scene_params p = flat_scene(prof, 0, 200, 260);
        image_t img, mask;
        cr_assert_eq(synth_scene_draw(&p, &img, &mask, NULL), 0);
        double a = mask_sum(&mask), ref = level_area(&p.vessels[0].body);
        cr_expect_float_eq(a, ref, 2e-4 * ref, "%s: drawn area %.3f, analytic %.3f", synth_profile_name(prof), a, ref);
        image_free(&img);
        image_free(&mask);
    }
}

Test(synth_scene, elevated_cylinder_area_is_rectangle_plus_two_half_ellipses)
{
    const double elevations[] = {4, 12, 25, 40};
    for (int k = 0; k < 4; k++) {
        synth_scene_params p = flat_scene(SYNTH_PROFILE_CYLINDER, elevations[k], 220, 400);
        const synth_body *b = &p.vessels[0].body;
        double e = elevations[k] * M_PI / 180, R = synth_body_radius(b, 0), H = b->height_px;
        image_t img, mask;
        cr_assert_eq(synth_scene_draw(&p, &img, &mask, NULL), 0);
        double a = mask_sum(&mask), ref = 2 * R * H * cos(e) + M_PI * R * R * sin(e);
        cr_expect_float_eq(a, ref, 2e-4 * ref, "e = %g: drawn %.3f, analytic %.3f", elevations[k], a, ref);
        image_free(&img);
        image_free(&mask);
    }
}

Test(synth_scene, elevated_outline_is_brute_force_union_of_disc_ellipses)
{
    const synth_profile profs[] = {SYNTH_PROFILE_MAEBYEONG, SYNTH_PROFILE_LIDDED_JAR, SYNTH_PROFILE_EWER};
    for (int k = 0; k < 3; k++) {
        synth_body b = {profs[k], 300, 1, v2(200, 380), 0, 5 + 5 * k};
        double e = b.elevation_deg * M_PI / 180, wb, wt, reach = 1.1 * 300 * synth_profile_max_radius(profs[k]) + 2;
        synth_body_axis_extent(&b, &wb, &wt);
        for (int i = 1; i < 25; i++) {
            double w = wb + (wt - wb) * i / 25, best = -1;
            /* Every disc within reach of the line, one per 0.001 px of
             * height: the maximum is exact to ~1e-6 px. */
            double h0 = fmax(0, (w - reach * sin(e)) / cos(e)), h1 = fmin(b.height_px, (w + reach * sin(e)) / cos(e));
            for (double h = h0; h <= h1; h += 0.001) {
                double r = synth_body_radius(&b, h), u = (w - h * cos(e)) / sin(e);
                if (r * r >= u * u)
                    best = fmax(best, sqrt(r * r - u * u));
            }
            double x = synth_body_half_width(&b, w);
            cr_expect(fabs(x - best) < 2e-5, "%s e=%g w=%.2f: X = %.7f, brute force %.7f", synth_profile_name(profs[k]),
                      b.elevation_deg, w, x, best);
        }
    }
}

Test(synth_scene, corners_lie_on_the_outline)
{
    for (int prof = 0; prof < SYNTH_PROFILE_COUNT; prof++)
        for (int elev = 0; elev <= 14; elev += 7) {
            synth_body b = {prof, 250, 1, v2(300, 400), 0, elev};
            vec2 c[CORNER_COUNT];
            synth_body_corners(&b, c);
            for (int k = 0; k < CORNER_COUNT; k++) {
                double xl, xr;
                cr_assert(synth_body_outline_x(&b, c[k].y, &xl, &xr));
                double x = k == CORNER_RIM_LEFT || k == CORNER_BASE_LEFT ? xl : xr;
                cr_expect(fabs(x - c[k].x) < 1e-5, "%s e=%d corner %d: (%.6f, %.6f), outline x %.6f",
                          synth_profile_name(prof), elev, k, c[k].x, c[k].y, x);
            }
        }
}

/* Image y of the lowest (or highest) drawn point in column i: the last
 * partly covered pixel below (above) a run of covered ones. */
static double column_end(const image_t *mask, int i, int down)
{
    int j = down ? mask->height - 1 : 0, step = down ? -1 : 1;
    while (mask->data[(size_t)j * mask->width + i] == 0)
        j += step;
    double c = mask->data[(size_t)j * mask->width + i];
    return down ? j + c : j + 1 - c;
}

Test(synth_scene, caps_have_half_height_r_sin_e_in_the_pixels)
{
    const synth_profile profs[] = {SYNTH_PROFILE_CYLINDER, SYNTH_PROFILE_LIDDED_JAR, SYNTH_PROFILE_MAEBYEONG};
    for (int k = 0; k < 3; k++)
        for (int elev = 6; elev <= 18; elev += 12) {
            synth_scene_params p = flat_scene(profs[k], elev, 240, 300);
            image_t img, mask;
            synth_scene_truth t;
            cr_assert_eq(synth_scene_draw(&p, &img, &mask, &t), 0);
            const synth_body *b = &t.body;
            double e = elev * M_PI / 180, H = b->height_px;
            cr_expect_float_eq(t.base_half_height, synth_body_radius(b, 0) * sin(e), 1e-9);
            cr_expect_float_eq(t.rim_half_height, synth_body_radius(b, H) * sin(e), 1e-9);
            cr_expect_float_eq(t.rim_center.y, b->base_center.y - H * cos(e), 1e-9);
            /* The axis column (centred on the axis): its ends are the caps'
             * ellipses' lowest and highest points. */
            int i = (int)floor(b->base_center.x);
            cr_assert_float_eq(b->base_center.x, i + 0.5, 1e-9);
            double bottom = column_end(&mask, i, 1), top = column_end(&mask, i, 0);
            const char *name = synth_profile_name(profs[k]);
            cr_expect(fabs(bottom - (t.base_center.y + t.base_half_height)) < 0.02,
                      "%s e=%d: bottom %.4f, base %.4f + %.4f", name, elev, bottom, t.base_center.y,
                      t.base_half_height);
            cr_expect(fabs(top - (t.rim_center.y - t.rim_half_height)) < 0.02, "%s e=%d: top %.4f, rim %.4f - %.4f",
                      name, elev, top, t.rim_center.y, t.rim_half_height);
            cr_expect_float_eq(t.outline_bottom_y, t.base_center.y + t.base_half_height, 1e-6);
            image_free(&img);
            image_free(&mask);
        }
}

/* Along row j of a flat case, the coverage c = (v - bg) / (fg - bg) in the
 * channel of largest contrast; its sum left (right) of an inside pixel puts
 * the area-equivalent edge, where a step of the same coverage would cross
 * 0.5, at a sub-pixel position to compare with the truth. */
static void check_row_edges(const image_t *img, const synth_scene_params *p, const synth_scene_truth *t, int j,
                            int *checked)
{
    const float *fg = p->vessels[0].glaze, *bg = p->backdrop.wall;
    int q = 0;
    for (int k = 1; k < 3; k++)
        q = fabsf(fg[k] - bg[k]) > fabsf(fg[q] - bg[q]) ? k : q;
    double y = j + 0.5, xl, xr, xl0, xr0, xl1, xr1;
    if (!synth_scene_outline_x(t, y, &xl, &xr) || !synth_scene_outline_x(t, y - 0.5, &xl0, &xr0) ||
        !synth_scene_outline_x(t, y + 0.5, &xl1, &xr1) || xr - xl < 4)
        return;
    /* Only rows where the outline is steep and straight within the row: the
     * edge averaged over the row is then its value at the centre. */
    if (fabs(xl1 - xl0) > 1.5 || fabs(xl1 - 2 * xl + xl0) > 0.1 || fabs(xr1 - xr0) > 1.5 ||
        fabs(xr1 - 2 * xr + xr0) > 0.1)
        return;
    int mid = (int)floor(0.5 * (xl + xr));
    double left = 0, right = 0;
    for (int i = 0; i < img->width; i++) {
        double c = (img->data[((size_t)j * img->width + i) * 3 + q] - bg[q]) / (fg[q] - bg[q]);
        if (i < mid)
            left += c;
        else
            right += c;
    }
    cr_expect(fabs((mid - left) - xl) < 0.05, "row %d: left edge %.4f drawn, %.4f true", j, mid - left, xl);
    cr_expect(fabs((mid + right) - xr) < 0.05, "row %d: right edge %.4f drawn, %.4f true", j, mid + right, xr);
    (*checked)++;
}

Test(synth_scene, truth_outline_agrees_with_drawn_pixels)
{
    const char *cases[] = {"maebyeong_flat", "lidded_jar_flat_high"};
    for (int k = 0; k < 2; k++) {
        synth_scene_params p;
        synth_scene_truth t;
        image_t img;
        draw_case(cases[k], 300, 400, &p, &t, &img);
        int checked = 0;
        for (int j = 0; j < img.height; j++)
            check_row_edges(&img, &p, &t, j, &checked);
        cr_expect_gt(checked, 150, "%s: only %d rows checked", cases[k], checked);
        image_free(&img);
    }
}

Test(synth_scene, backdrop_only_case_has_no_vessel)
{
    synth_scene_params p;
    synth_scene_truth t;
    image_t bare, mask, with, mask2;
    cr_assert_eq(synth_scene_case("backdrop_only", 150, 200, &p), 0);
    cr_assert_eq(synth_scene_draw(&p, &bare, &mask, &t), 0);
    cr_expect_eq(t.vessel_count, 0);
    cr_expect_eq(t.part_count, 0);
    cr_expect_eq(mask_sum(&mask), 0);
    /* The same backdrop with a vessel: identical wherever the vessel is not. */
    p.vessel_count = 1;
    p.vessels[0] = flat_scene(SYNTH_PROFILE_VASE, 0, 150, 200).vessels[0];
    cr_assert_eq(synth_scene_draw(&p, &with, &mask2, NULL), 0);
    int differ_outside = 0, differ_inside = 0;
    for (int i = 0; i < 150 * 200; i++) {
        int differs = memcmp(&bare.data[3 * i], &with.data[3 * i], 3 * sizeof(float)) != 0;
        differ_outside += differs && mask2.data[i] == 0;
        differ_inside += differs && mask2.data[i] == 1;
    }
    cr_expect_eq(differ_outside, 0);
    cr_expect_gt(differ_inside, 1000);
    image_free(&bare), image_free(&mask), image_free(&with), image_free(&mask2);
}

Test(synth_scene, drawing_is_deterministic_and_seeded)
{
    synth_scene_params p;
    cr_assert_eq(synth_scene_case("bowl_paper", 120, 160, &p), 0);
    p.noise = 0.02;
    image_t a, b, c;
    cr_assert_eq(synth_scene_draw(&p, &a, NULL, NULL), 0);
    cr_assert_eq(synth_scene_draw(&p, &b, NULL, NULL), 0);
    p.seed += 1;
    cr_assert_eq(synth_scene_draw(&p, &c, NULL, NULL), 0);
    size_t n = (size_t)120 * 160 * 3;
    cr_expect_eq(memcmp(a.data, b.data, n * sizeof(float)), 0);
    cr_expect_neq(memcmp(a.data, c.data, n * sizeof(float)), 0);
    image_free(&a), image_free(&b), image_free(&c);
}

static const synth_part_truth *find_part(const synth_scene_truth *t, synth_part_kind kind, int side)
{
    for (int k = 0; k < t->part_count; k++)
        if (t->parts[k].kind == kind && (side == 0 || t->parts[k].side == side))
            return &t->parts[k];
    return NULL;
}

Test(synth_scene, every_case_draws_and_only_the_cut_one_touches_the_border)
{
    cr_expect_eq(synth_scene_case("no_such_case", 100, 100, &(synth_scene_params){0}), -1);
    for (int i = 0; i < synth_scene_case_count(); i++) {
        const char *name = synth_scene_case_name(i);
        for (int k = 0; k < i; k++)
            cr_expect_neq(strcmp(name, synth_scene_case_name(k)), 0, "%s twice", name);
        synth_scene_params p;
        synth_scene_truth t;
        image_t img;
        draw_case(name, 90, 120, &p, &t, &img);
        cr_expect_eq(img.channels, p.grayscale ? 1 : 3, "%s", name);
        cr_expect_eq(t.touches_border, strcmp(name, "vase_cut_bottom") == 0, "%s", name);
        for (int k = 0; k < t.part_count; k++)
            cr_expect_geq(t.parts[k].row0, 0, "%s: its %s does not show", name, synth_part_name(t.parts[k].kind));
        image_free(&img);
    }
}

Test(synth_scene, handles_stand_out_of_the_body_with_a_hole)
{
    synth_scene_params p, bare;
    synth_scene_truth t;
    image_t img, bg;
    cr_assert_eq(synth_scene_case("amphora_handles", 300, 400, &p), 0);
    p.noise = 0, p.jpeg_quality = 0; /* pixel for pixel against the bare backdrop */
    cr_assert_eq(synth_scene_draw(&p, &img, NULL, &t), 0);
    bare = p;
    bare.vessel_count = 0;
    memset(bare.attachments, 0, sizeof bare.attachments);
    bare.contact_shadow = 0;
    cr_assert_eq(synth_scene_draw(&bare, &bg, NULL, NULL), 0);
    for (int side = -1; side <= 1; side += 2) {
        const synth_part_truth *h = find_part(&t, SYNTH_PART_HANDLE, side);
        cr_assert(h, "no handle on side %d", side);
        /* Rows between its two ends, which are on the body's wall. */
        double H = t.body.height_px, y0 = t.base_center.y - p.attachments[side > 0].h1 * H;
        double y1 = t.base_center.y - p.attachments[side > 0].h0 * H;
        cr_expect(h->row0 > y0 - 0.06 * H && h->row1 < y1 + 0.06 * H, "rows %d..%d, ends at %.1f, %.1f", h->row0,
                  h->row1, y0, y1);
        /* On its middle row: body, then backdrop (the hole), then handle. */
        int j = (h->row0 + h->row1) / 2, W = img.width, run = 0, hole = 0;
        double xl, xr;
        cr_assert(synth_scene_outline_x(&t, j + 0.5, &xl, &xr));
        for (int i = side > 0 ? (int)ceil(xr) + 1 : (int)floor(xl) - 2; i >= 0 && i < W; i += side) {
            int backdrop = memcmp(&img.data[3 * ((size_t)j * W + i)], &bg.data[3 * ((size_t)j * W + i)], 12) == 0;
            if (!backdrop && run > 0) {
                hole = run;
                break;
            }
            run = backdrop ? run + 1 : 0;
        }
        cr_expect_geq(hole, 3, "side %d: no hole between handle and body on row %d", side, j);
        cr_expect(side > 0 ? h->col1 > xr + 0.05 * H : h->col0 < xl - 0.05 * H, "side %d: cols %d..%d", side, h->col0,
                  h->col1);
    }
    image_free(&img), image_free(&bg);
}

Test(synth_scene, cast_shadow_darkens_one_side_only)
{
    synth_scene_params p, dark;
    synth_scene_truth t;
    image_t with, without;
    cr_assert_eq(synth_scene_case("maebyeong_shadow", 240, 320, &p), 0);
    p.noise = 0, p.jpeg_quality = 0; /* JPEG blocks would carry the shadow across the axis */
    dark = p;
    p.shadow.strength = 0;
    cr_assert_eq(synth_scene_draw(&dark, &with, NULL, &t), 0);
    cr_assert_eq(synth_scene_draw(&p, &without, NULL, NULL), 0);
    const synth_part_truth *s = find_part(&t, SYNTH_PART_CAST_SHADOW, 0);
    cr_assert(s);
    cr_expect_eq(s->side, 1);
    cr_expect(s->row0 <= t.foot_y && s->row1 >= t.foot_y - 2, "rows %d..%d, foot %.1f", s->row0, s->row1, t.foot_y);
    int left = 0, right = 0;
    for (int j = 0; j < 320; j++)
        for (int i = 0; i < 240; i++) {
            size_t k = 3 * ((size_t)j * 240 + i);
            int darker = with.data[k] < without.data[k];
            left += darker && i + 0.5 < t.axis_origin.x;
            right += darker && i + 0.5 > t.axis_origin.x;
        }
    cr_expect_eq(left, 0);
    cr_expect_gt(right, 500);
    image_free(&with), image_free(&without);
}

Test(synth_scene, stand_begins_at_the_foot)
{
    const char *cases[] = {"bottle_stand", "footed_bowl_stand", "vase_plinth"};
    for (int k = 0; k < 3; k++) {
        synth_scene_params p;
        synth_scene_truth t;
        image_t img;
        draw_case(cases[k], 240, 320, &p, &t, &img);
        const synth_part_truth *s = find_part(&t, SYNTH_PART_STAND, 0);
        cr_assert(s, "%s", cases[k]);
        cr_expect_eq(s->side, 0, "%s", cases[k]);
        cr_expect(fabs(t.foot_y - t.outline_bottom_y) < 1e-9, "%s", cases[k]);
        /* The stand shows from the foot's row (its top face, when elevated, a
         * little above it) down. */
        double top_face = t.base_half_height + p.stand.depth * p.stand.width * synth_scene_radius(&t, 0) *
                                                   sin(t.body.elevation_deg * M_PI / 180);
        cr_expect(s->row0 >= t.foot_y - top_face - 2 && s->row0 <= t.foot_y + 1, "%s: stand from row %d, foot %.2f",
                  cases[k], s->row0, t.foot_y);
        double r0 = synth_scene_radius(&t, 0), half = 0.5 * (s->col1 + 1 - s->col0);
        cr_expect(fabs(half - p.stand.width * r0) < 1.5, "%s: half-width %.1f, stand %.1f", cases[k], half,
                  p.stand.width * r0);
        image_free(&img);
    }
}

Test(synth_scene, lid_and_knob_are_in_the_profile)
{
    synth_scene_params p;
    synth_scene_truth t;
    image_t img;
    draw_case("lidded_jar", 240, 320, &p, &t, &img);
    double H = t.body.height_px;
    /* The knob's flat top is the topmost outline; under it the knob bulges
     * over its stem, and the lid's flange overhangs the neck. */
    cr_expect_float_eq(t.outline_top_y, t.rim_center.y, 1e-9);
    cr_expect_lt(synth_scene_radius(&t, H), 0.05 * H);
    cr_expect_gt(synth_scene_radius(&t, 0.975 * H), synth_scene_radius(&t, 0.93 * H) + 0.02 * H);
    cr_expect_gt(synth_scene_radius(&t, 0.75 * H), synth_scene_radius(&t, 0.72 * H) + 0.015 * H);
    cr_expect_eq(t.part_count, 2, "only the two shadows are parts");
    image_free(&img);
}

Test(synth_scene, two_vessels_and_caption_parts)
{
    synth_scene_params p;
    synth_scene_truth t;
    image_t img;
    draw_case("two_vessels", 300, 240, &p, &t, &img);
    const synth_part_truth *s = find_part(&t, SYNTH_PART_SECOND_VESSEL, 0);
    cr_assert(s);
    double xl, xr;
    cr_assert(synth_scene_outline_x(&t, t.base_center.y - 0.5 * t.body.height_px, &xl, &xr));
    cr_expect_eq(s->side, 1);
    cr_expect_gt(s->col0, t.base_center.x + synth_scene_radius(&t, 0));
    image_free(&img);
    draw_case("beaker_caption_bw", 200, 260, &p, &t, &img);
    cr_expect_eq(img.channels, 1);
    const synth_part_truth *cap = find_part(&t, SYNTH_PART_CAPTION, 0), *bar = find_part(&t, SYNTH_PART_SCALE_BAR, 0);
    cr_assert(cap && bar);
    cr_expect(cap->row1 >= 0.97 * 260 && bar->row1 >= 0.97 * 260, "caption to row %d, scale bar to %d", cap->row1,
              bar->row1);
    cr_expect_gt(cap->row0, t.outline_bottom_y);
    image_free(&img);
}

Test(synth_scene, invalid_parameters_are_refused)
{
    synth_scene_params p = flat_scene(SYNTH_PROFILE_VASE, 5, 100, 120);
    image_t img, mask;
    p.vessels[0].body.tilt_deg = 2; /* tilted and elevated */
    cr_expect_eq(synth_scene_draw(&p, &img, &mask, NULL), -1);
    cr_expect_null(img.data);
    cr_expect_null(mask.data);
    p = flat_scene(SYNTH_PROFILE_VASE, 0, 100, 120);
    p.vessels[0].body.tilt_deg = 2;
    p.stand.kind = SYNTH_STAND_BOX, p.stand.width = 1, p.stand.height = 0.2;
    cr_expect_eq(synth_scene_draw(&p, &img, NULL, NULL), -1, "a stand under a tilted camera");
    p = flat_scene(SYNTH_PROFILE_VASE, 0, 100, 120);
    p.vessel_count = 0;
    p.contact_shadow = 0.5;
    cr_expect_eq(synth_scene_draw(&p, &img, NULL, NULL), -1, "a shadow without a vessel");
}

static double disc_sdf(const void *ctx, double x, double y)
{
    const double *c = ctx; /* centre x, centre y, radius */
    return hypot(x - c[0], y - c[1]) - c[2];
}

Test(synth_scene, raster_coverage_is_exact_for_rectangles_and_close_for_discs)
{
    static float cov[64 * 64];
    synth_cover_rect(cov, 64, 64, 3.25, 7.5, 40.125, 20.75);
    double a = 0;
    for (int i = 0; i < 64 * 64; i++)
        a += cov[i];
    cr_expect_float_eq(a, (40.125 - 3.25) * (20.75 - 7.5), 1e-4);
    /* 16x16 samples: each boundary pixel errs by ~1/256 at most, over ~150. */
    const double disc[3] = {31.3, 30.8, 22.7};
    memset(cov, 0, sizeof cov);
    synth_cover_sdf(cov, 64, 64, 0, 0, 63, 63, 16, 1.0, disc_sdf, disc);
    a = 0;
    for (int i = 0; i < 64 * 64; i++)
        a += cov[i];
    cr_expect_float_eq(a, M_PI * disc[2] * disc[2], 0.3, "disc: %.3f drawn, %.3f true", a, M_PI * disc[2] * disc[2]);
}

Test(synth_scene, jpeg_quantisation_keeps_flat_blocks_and_rings_at_edges)
{
    image_t img = image_alloc(16, 16, 1);
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++)
            img.data[j * 16 + i] = i < 11 ? 0.2f : 0.8f;
    synth_jpeg_quantise(&img, 40);
    /* The flat left blocks move at most half a DC step (q0 = 20 at quality
     * 40: 2.5 levels); the block with the edge overshoots it. */
    double flat = 0, over = 0;
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 8; i++)
            flat = fmax(flat, fabs(img.data[j * 16 + i] - 0.2));
    for (int j = 0; j < 16; j++)
        for (int i = 8; i < 16; i++)
            over = fmax(over, fmax(0.2 - img.data[j * 16 + i], img.data[j * 16 + i] - 0.8));
    cr_expect_leq(flat, 1.25 / 255 + 1e-6, "flat block moved by %g", flat);
    cr_expect_gt(over, 2.0 / 255, "no ringing at the edge (%g)", over);
    image_free(&img);
}
