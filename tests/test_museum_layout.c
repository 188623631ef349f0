/* The museum's floor plan (src/museum/layout.c) for 1, 8 and 50 vessels of
 * mixed sizes: every vessel fits its case, no footprint overlaps another or
 * a wall, every aisle is at least LAYOUT_AISLE wide, and the room grows with
 * the collection. */
#include <criterion/criterion.h>
#include <math.h>

#include "museum/layout.h"

/* Sizes from a 10 cm cup to a 60 cm jar, radii from a slender bottle to a bowl. */
static layout_vessel vessel(int i)
{
    return (layout_vessel){0.10 + 0.05 * (i % 11), 0.04 + 0.03 * ((i * 7) % 9)};
}

/* Free distance between two axis-aligned squares on the floor (0 when they
 * touch or overlap): the larger of the gaps along x and z. */
static double gap(const layout_exhibit *a, const layout_exhibit *b)
{
    double gx = fabs(a->centre.x - b->centre.x) - (a->width + b->width) / 2;
    double gz = fabs(a->centre.z - b->centre.z) - (a->width + b->width) / 2;
    return fmax(fmax(gx, gz), 0.0);
}

static void check(int n, layout_t *l)
{
    layout_vessel v[64];
    for (int i = 0; i < n; i++)
        v[i] = vessel(i);
    cr_assert_eq(layout_make(v, n, l), 0);
    cr_assert_eq(l->n_exhibits, n);
    const double eps = 1e-9;
    for (int i = 0; i < n; i++) {
        const layout_exhibit *e = &l->exhibits[i];
        /* The vessel fits its case: its widest circle inside the footprint, its top under the lid. */
        cr_expect_leq(v[i].radius + layout_clearance(&v[i]), e->width / 2 + eps);
        cr_expect_leq(v[i].height, e->case_height - layout_clearance(&v[i]) + eps);
        cr_expect(fabs(e->vessel_base.y - e->pedestal_height) < eps && fabs(e->vessel_base.x - e->centre.x) < eps &&
                      fabs(e->vessel_base.z - e->centre.z) < eps,
                  "the vessel stands on its pedestal, in the middle");
        /* The case light is inside the case, above the vessel. */
        cr_expect(e->light.y < e->pedestal_height + e->case_height && e->light.y > e->vessel_base.y + v[i].height);
        /* The label is on the pedestal's front face, within it. */
        cr_expect_leq(e->label_width, e->width);
        cr_expect(e->label_centre.y + e->label_height / 2 < e->pedestal_height);
        cr_expect(e->label_centre.y - e->label_height / 2 > 0);
        /* The title sign, when there is room for one, is on the same face
         * under the label and above the floor, within the face: under the
         * pedestal's top, so it hides no vessel. */
        if (e->sign_lines > 0) {
            cr_expect_leq(e->sign_lines, LAYOUT_SIGN_LINES);
            cr_expect_leq(e->sign_width, e->width);
            cr_expect_lt(e->sign_centre.y + e->sign_height / 2, e->label_centre.y - e->label_height / 2);
            cr_expect_gt(e->sign_centre.y - e->sign_height / 2, 0);
            cr_expect(fabs(e->sign_centre.z - e->label_centre.z) < eps && fabs(e->sign_centre.x - e->centre.x) < eps);
        }
        /* Aisles along the walls: LAYOUT_AISLE from the side and back walls,
         * LAYOUT_AISLE + LAYOUT_ENTRANCE from the entrance wall. */
        cr_expect_geq(l->width / 2 - (fabs(e->centre.x) + e->width / 2), LAYOUT_AISLE - eps, "side wall aisle");
        cr_expect_geq(e->centre.z - e->width / 2 + l->depth / 2, LAYOUT_AISLE - eps, "back wall aisle");
        cr_expect_geq(l->depth / 2 - (e->centre.z + e->width / 2), LAYOUT_AISLE + LAYOUT_ENTRANCE - eps,
                      "entrance zone");
        cr_expect_gt(l->height, e->pedestal_height + e->case_height, "the ceiling clears the case");
        for (int j = 0; j < i; j++)
            cr_expect_geq(gap(e, &l->exhibits[j]), LAYOUT_AISLE - eps, "aisle between exhibits %d and %d", i, j);
    }
    /* The camera stands in the entrance zone at eye height, inside the room,
     * looking into it. */
    cr_expect(fabs(l->camera_position.x) < l->width / 2 && l->camera_position.z < l->depth / 2 &&
              l->camera_position.z > l->depth / 2 - LAYOUT_ENTRANCE);
    cr_expect(fabs(l->camera_position.y - LAYOUT_EYE_HEIGHT) < eps);
    cr_expect_lt(l->camera_target.z, l->camera_position.z);
    /* Ceiling lights under the ceiling, at most LAYOUT_CEILING_LIGHT_SPACING apart in a grid covering the room. */
    cr_expect_geq(l->n_ceiling_lights, 1);
    for (int k = 0; k < l->n_ceiling_lights; k++)
        cr_expect(fabs(l->ceiling_lights[k].x) < l->width / 2 && fabs(l->ceiling_lights[k].z) < l->depth / 2 &&
                  l->ceiling_lights[k].y < l->height);
}

Test(museum_layout, one_vessel)
{
    layout_t l;
    check(1, &l);
    cr_expect_eq(l.columns, 1);
    cr_expect_eq(l.rows, 1);
    cr_expect(fabs(l.exhibits[0].centre.x) < 1e-12, "a single exhibit is centred");
    layout_free(&l);
}

Test(museum_layout, eight_and_fifty_vessels_grow_the_room)
{
    layout_t one, eight, fifty;
    check(1, &one);
    check(8, &eight);
    check(50, &fifty);
    cr_expect_eq(eight.columns * eight.rows >= 8 && fifty.columns * fifty.rows >= 50, 1);
    cr_expect_gt(eight.width * eight.depth, one.width * one.depth);
    cr_expect_gt(fifty.width * fifty.depth, eight.width * eight.depth);
    /* Near-square: the grid never has more rows than columns, nor an empty row. */
    cr_expect_leq(fifty.rows, fifty.columns);
    cr_expect_gt(50, (fifty.rows - 1) * fifty.columns);
    /* Floor area per vessel stays bounded: the room grows with the count, not faster. */
    cr_expect_lt(fifty.width * fifty.depth / 50, one.width * one.depth);
    layout_free(&one);
    layout_free(&eight);
    layout_free(&fifty);
}

Test(museum_layout, refuses_bad_sizes)
{
    layout_t l;
    layout_vessel bad[2] = {{0.3, 0.1}, {NAN, 0.1}};
    cr_expect_eq(layout_make(bad, 2, &l), -1);
    bad[1] = (layout_vessel){0.3, 0};
    cr_expect_eq(layout_make(bad, 2, &l), -1);
    cr_expect_eq(layout_make(bad, 0, &l), -1);
}

Test(museum_layout, rows_follow_their_own_footprints)
{
    /* One vessel 2 m wide among seven small ones: only its own row and
     * column of floor grow for it, and the room is as small as the aisles
     * allow: neighbours in a row, consecutive rows, and the widest row and
     * the back row against the walls are exactly LAYOUT_AISLE apart. */
    layout_vessel v[8];
    for (int i = 0; i < 8; i++)
        v[i] = vessel(i);
    v[4] = (layout_vessel){0.3, 1.0};
    layout_t l;
    cr_assert_eq(layout_make(v, 8, &l), 0);
    const double eps = 1e-9;
    double widest = 0, big = l.exhibits[4].width, small = 0, rows_depth = 0;
    for (int i = 0; i < 8; i++)
        if (i != 4)
            small = fmax(small, l.exhibits[i].width);
    for (int r = 0; r < l.rows; r++) {
        double length = -LAYOUT_AISLE, depth = 0;
        for (int i = r * l.columns; i < 8 && i < (r + 1) * l.columns; i++) {
            length += l.exhibits[i].width + LAYOUT_AISLE, depth = fmax(depth, l.exhibits[i].width);
            if (i > r * l.columns)
                cr_expect(fabs(gap(&l.exhibits[i], &l.exhibits[i - 1]) - LAYOUT_AISLE) < eps, "neighbours %d, %d",
                          i - 1, i);
            cr_expect(fabs(l.exhibits[i].centre.z - l.exhibits[r * l.columns].centre.z) < eps, "one row, one line");
        }
        widest = fmax(widest, length);
        rows_depth += depth;
    }
    cr_expect(fabs(l.width - widest - 2 * LAYOUT_AISLE) < eps, "the widest row touches the side aisles");
    cr_expect(fabs(l.depth - rows_depth - (l.rows + 1) * LAYOUT_AISLE - LAYOUT_ENTRANCE) < eps);
    /* A grid of equal cells as large as the big exhibit would have been
     * columns x rows of them; the rows here hold one big and the rest small. */
    cr_expect_lt(l.width, l.columns * (big + LAYOUT_AISLE) + LAYOUT_AISLE - (l.columns - 1) * (big - small) + eps);
    cr_expect_lt(l.depth,
                 l.rows * (big + LAYOUT_AISLE) + LAYOUT_AISLE + LAYOUT_ENTRANCE - (l.rows - 1) * (big - small) + eps);
    layout_free(&l);
}

/* The title signs from the entrance (issue 30: labels readable from the
 * entrance, size and placement checked from its view): sixteen 30 cm
 * vessels like the real-dev museum's (no sizes in its catalogue). Every
 * sign of the first row has room for two lines; those in the entrance
 * camera's view at 960x540 (at least the middle two of the four) have
 * capitals, projected by that camera, at least 8 px tall (logged beside
 * the label's title capitals, 0.72 of its 7.5% of the plate's width: about
 * 3 px, which is why the signs are there). */
Test(museum_layout, title_signs_are_legible_from_the_entrance)
{
    layout_vessel v[16];
    for (int i = 0; i < 16; i++)
        v[i] = (layout_vessel){0.30, 0.06 + 0.01 * i};
    layout_t l;
    cr_assert_eq(layout_make(v, 16, &l), 0);
    const double W = 960, H = 540, focal = 0.5 * H / tan(0.5 * l.camera_yfov_deg * M_PI / 180);
    vec3 f = v3_norm(v3_sub(l.camera_target, l.camera_position)), right = v3_norm(v3_cross(f, v3(0, 1, 0)));
    vec3 up = v3_cross(right, f);
    double smallest = INFINITY, label_caps = 0;
    int in_view = 0;
    for (int i = 0; i < l.columns; i++) {
        const layout_exhibit *e = &l.exhibits[i];
        cr_expect_eq(e->sign_lines, LAYOUT_SIGN_LINES, "sign %d has room for %d lines", i, e->sign_lines);
        vec3 d = v3_sub(e->sign_centre, l.camera_position);
        double z = v3_dot(d, f), x = focal * v3_dot(d, right) / z, y = focal * v3_dot(d, up) / z;
        if (!(z > 0 && fabs(x) < W / 2 && fabs(y) < H / 2))
            continue;
        in_view++;
        /* A capital standing at the sign's centre, projected. */
        vec3 top = v3_sub(v3_add(e->sign_centre, v3(0, LAYOUT_SIGN_CAP / 2, 0)), l.camera_position);
        vec3 bottom = v3_sub(v3_sub(e->sign_centre, v3(0, LAYOUT_SIGN_CAP / 2, 0)), l.camera_position);
        double px = focal * (v3_dot(top, up) / v3_dot(top, f) - v3_dot(bottom, up) / v3_dot(bottom, f));
        smallest = fmin(smallest, px);
        label_caps = fmax(label_caps, focal * 0.72 * 0.075 * e->label_width / z);
    }
    cr_log_info("first row from the entrance at 960x540: %d signs in view, capitals at least %.1f px, label "
                "titles' at most %.1f px",
                in_view, smallest, label_caps);
    cr_expect_geq(in_view, 2);
    cr_expect_geq(smallest, 8.0, "the first row's sign capitals are %.1f px tall from the entrance", smallest);
    layout_free(&l);
}
