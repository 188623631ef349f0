/* profile.json: exact round trip, and a one-line reason for each kind of
 * malformed file (made by editing a good file with jansson); the optional
 * camera and meridian blocks of a perspective reconstruction likewise, and
 * `celadon mesh` revolving the meridian when there is one (profile_shape),
 * the B-spline otherwise. */
#include <criterion/criterion.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/profile.h"
#include "support/cli_run.h"
#include "test_curve_shapes.h"

static char dir[64], path[128];

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/celadon-test-profile-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/profile.json", dir);
}

static void teardown(void)
{
    remove(path);
    rmdir(dir);
}

/* A profile with every field set to something recognisable. */
static profile_t sample_profile(void)
{
    profile_t p;
    memset(&p, 0, sizeof p);
    snprintf(p.source_path, sizeof p.source_path, "photos/vase \"1\".jpg");
    p.source_width = 900;
    p.source_height = 1200;
    p.axis_origin = v2(451.2, 1103.0);
    p.axis_direction = v2_norm(v2(0.001, -1.0));
    p.tilt_deg = 0.0573;
    for (int k = 0; k < CORNER_COUNT; k++)
        p.corners[k] = v2(100.5 + k, 200.25 * k);
    snprintf(p.side, sizeof p.side, "right");
    p.n_polyline = 50;
    p.polyline = malloc(50 * sizeof *p.polyline);
    for (int i = 0; i < 50; i++)
        p.polyline[i] = v2(30 + sin(i * 0.1) / 3.0, i * 140.0 / 49);
    p.curve = test_vase_curve();
    p.n_domains = 7;
    p.domains = malloc(7 * sizeof *p.domains);
    const double d[] = {0, 0.1, 0.2, 1.0 / 3, 0.35, 0.7, 1};
    memcpy(p.domains, d, sizeof d);
    p.err_curve_to_polyline = 0.8;
    p.err_polyline_to_curve = 0.9;
    p.contour_points = 812;
    p.ms_image_processing = 3.1;
    p.ms_bspline = 0.9;
    p.ms_texture = 1.2;
    p.ms_mesh = 4.0;
    return p;
}

Test(profile_json, round_trip_is_exact, .init = setup, .fini = teardown)
{
    profile_t a = sample_profile(), b;
    char err[256];
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), 0, "%s", err);
    cr_assert_str_eq(b.source_path, a.source_path);
    cr_assert_eq(b.source_width, 900);
    cr_assert_eq(b.source_height, 1200);
    cr_assert(b.axis_origin.x == a.axis_origin.x && b.axis_origin.y == a.axis_origin.y);
    cr_assert(b.axis_direction.x == a.axis_direction.x && b.axis_direction.y == a.axis_direction.y);
    cr_assert_eq(b.tilt_deg, a.tilt_deg);
    for (int k = 0; k < CORNER_COUNT; k++)
        cr_assert(b.corners[k].x == a.corners[k].x && b.corners[k].y == a.corners[k].y);
    cr_assert_str_eq(b.side, "right");
    cr_assert_eq(b.n_polyline, a.n_polyline);
    for (int i = 0; i < a.n_polyline; i++)
        cr_assert(b.polyline[i].x == a.polyline[i].x && b.polyline[i].y == a.polyline[i].y, "polyline[%d]", i);
    cr_assert_eq(b.curve.degree, 3);
    cr_assert_eq(b.curve.n_ctrl, a.curve.n_ctrl);
    for (int i = 0; i < bspline_n_knots(&a.curve); i++)
        cr_assert_eq(b.curve.knots[i], a.curve.knots[i]);
    for (int i = 0; i < a.curve.n_ctrl; i++)
        cr_assert(b.curve.ctrl[i].x == a.curve.ctrl[i].x && b.curve.ctrl[i].y == a.curve.ctrl[i].y);
    cr_assert_eq(b.n_domains, a.n_domains);
    for (int i = 0; i < a.n_domains; i++)
        cr_assert_eq(b.domains[i], a.domains[i]);
    cr_assert_eq(b.err_curve_to_polyline, 0.8);
    cr_assert_eq(b.err_polyline_to_curve, 0.9);
    cr_assert_eq(b.contour_points, 812);
    cr_assert(b.ms_image_processing == 3.1 && b.ms_bspline == 0.9 && b.ms_texture == 1.2 && b.ms_mesh == 4.0);

    /* The stats block says what it describes. */
    json_t *root = json_load_file(path, 0, NULL);
    json_t *st = json_object_get(root, "stats");
    cr_assert_eq(json_integer_value(json_object_get(st, "control_points")), 8);
    cr_assert_eq(json_integer_value(json_object_get(st, "domains")), 7);
    cr_assert_eq(json_integer_value(json_object_get(root, "version")), 1);
    json_decref(root);
    profile_free(&a);
    profile_free(&b);
}

/* Writes the profile a (and frees it), applies edit to its JSON, and
 * expects the reader to refuse it with a one-line reason containing want. */
static void expect_refused_from(profile_t a, void (*edit)(json_t *root), const char *want)
{
    profile_t b;
    char err[512] = "";
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    json_t *root = json_load_file(path, 0, NULL);
    edit(root);
    cr_assert_eq(json_dump_file(root, path, 0), 0);
    json_decref(root);
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), -1, "accepted a file edited for '%s'", want);
    cr_assert_not_null(strstr(err, want), "reason '%s' lacks '%s'", err, want);
    cr_assert_null(strchr(err, '\n'));
    cr_assert_null(b.polyline);
    cr_assert_null(b.curve.knots);
    cr_assert_null(b.meridian.knots);
    cr_assert_null(b.meridian_domains);
    profile_free(&a);
}

static void expect_refused(void (*edit)(json_t *root), const char *want)
{
    expect_refused_from(sample_profile(), edit, want);
}

static json_t *bs(json_t *root) { return json_object_get(root, "bspline"); }
static void no_version(json_t *r) { json_object_del(r, "version"); }
static void version_2(json_t *r) { json_object_set_new(r, "version", json_integer(2)); }
static void no_bspline(json_t *r) { json_object_del(r, "bspline"); }
static void knots_string(json_t *r) { json_object_set_new(bs(r), "knots", json_string("0 0 0 0 1 1 1 1")); }
static void knot_string(json_t *r) { json_array_set_new(json_object_get(bs(r), "knots"), 5, json_string("0.3")); }
static void knots_decreasing(json_t *r) { json_array_set_new(json_object_get(bs(r), "knots"), 5, json_real(0.05)); }
static void knots_unclamped(json_t *r) { json_array_set_new(json_object_get(bs(r), "knots"), 3, json_real(0.01)); }
static void knots_start_five_times(json_t *r) { json_array_set_new(json_object_get(bs(r), "knots"), 4, json_real(0.0)); }
static void knots_short(json_t *r) { json_array_remove(json_object_get(bs(r), "knots"), 5); }
static void degree_2(json_t *r) { json_object_set_new(bs(r), "degree", json_integer(2)); }
static void ctrl_triple(json_t *r)
{
    json_array_append_new(json_array_get(json_object_get(bs(r), "control_points"), 3), json_real(1));
}
static void domains_repeat(json_t *r) { json_array_set_new(json_object_get(r, "domains"), 2, json_real(0.1)); }
static void domains_start(json_t *r) { json_array_set_new(json_object_get(r, "domains"), 0, json_real(0.01)); }
static void side_up(json_t *r) { json_object_set_new(r, "side", json_string("up")); }
static void axis_long(json_t *r) { json_object_set_new(json_object_get(r, "axis"), "direction", json_pack("[f,f]", 0.0, -2.0)); }
static void no_corner(json_t *r) { json_object_del(json_object_get(r, "corners"), "base_left"); }
static void polyline_null(json_t *r) { json_array_set_new(json_object_get(r, "polyline"), 7, json_null()); }
static void error_negative(json_t *r)
{
    json_object_set_new(json_object_get(r, "error_px"), "curve_to_polyline", json_real(-1));
}
static void timings_partial(json_t *r) { json_object_del(json_object_get(r, "timings_ms"), "mesh"); }
static void width_real(json_t *r) { json_object_set_new(json_object_get(r, "source"), "width", json_real(9.5)); }

/* Every control point's coordinates times f (r too when r_too). */
static void scale_ctrl(json_t *r, double f, int r_too)
{
    json_t *ctrl = json_object_get(bs(r), "control_points");
    for (size_t i = 0; i < json_array_size(ctrl); i++) {
        json_t *pt = json_array_get(ctrl, i);
        for (size_t k = r_too ? 0 : 1; k < 2; k++)
            json_array_set_new(pt, k, json_real(json_number_value(json_array_get(pt, k)) * f));
    }
}
static void ctrl_negative_r(json_t *r)
{
    json_t *ctrl = json_object_get(bs(r), "control_points");
    for (size_t i = 0; i < json_array_size(ctrl); i++) {
        json_t *pt = json_array_get(ctrl, i);
        json_array_set_new(pt, 0, json_real(-json_number_value(json_array_get(pt, 0))));
    }
}
static void ctrl_huge(json_t *r) { scale_ctrl(r, 1e300, 1); }
static void ctrl_tiny(json_t *r) { scale_ctrl(r, 1e-300, 1); }
static void ctrl_over_the_cap(json_t *r)
{
    json_t *ctrl = json_array();
    for (int i = 0; i <= PROFILE_MAX_POINTS; i++)
        json_array_append_new(ctrl, json_pack("[f, f]", 10.0, (double)i));
    json_object_set_new(bs(r), "control_points", ctrl);
}

Test(profile_json, malformed_files_are_refused_with_a_reason, .init = setup, .fini = teardown)
{
    /* What the SOR cannot revolve (sor_profile_check), and the size cap. */
    expect_refused(ctrl_negative_r, "the profile cannot be revolved: r < 0");
    expect_refused(ctrl_huge, "the profile cannot be revolved: a control point lies beyond 1e9 px");
    expect_refused(ctrl_tiny, "the profile cannot be revolved: the profile is less than 1e-6 px high");
    expect_refused(ctrl_over_the_cap, "'bspline.control_points' has 100001 elements, more than the 100000");
    expect_refused(no_version, "missing field 'version'");
    expect_refused(version_2, "unsupported version");
    expect_refused(no_bspline, "missing field 'bspline'");
    expect_refused(knots_string, "'bspline.knots' must be an array");
    expect_refused(knot_string, "'bspline.knots[5]' must be a number");
    expect_refused(knots_decreasing, "invalid B-spline: knots are not non-decreasing");
    expect_refused(knots_unclamped, "invalid B-spline: knot vector is not clamped");
    expect_refused(knots_start_five_times, "invalid B-spline: end knot multiplicity exceeds the degree + 1");
    expect_refused(knots_short, "control points need");
    expect_refused(degree_2, "'bspline.degree' must be 3");
    expect_refused(ctrl_triple, "'bspline.control_points[3]' must be an array of 2 numbers");
    expect_refused(domains_repeat, "'domains' must be strictly increasing");
    expect_refused(domains_start, "'domains' must start at 0");
    expect_refused(side_up, "'side' must be");
    expect_refused(axis_long, "'axis.direction' must be a unit vector");
    expect_refused(no_corner, "missing field 'corners.base_left'");
    expect_refused(polyline_null, "'polyline[7]' must be an array of 2 numbers");
    expect_refused(error_negative, "must not be negative");
    expect_refused(timings_partial, "missing field 'timings_ms.mesh'");
    expect_refused(width_real, "'source.width' must be a non-negative integer");
}

static void expect_text_refused(const char *text, const char *want)
{
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
    profile_t b;
    char err[512] = "";
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, want), "reason '%s' lacks '%s'", err, want);
    cr_assert_null(strchr(err, '\n'));
}

Test(profile_json, unreadable_files_are_refused, .init = setup, .fini = teardown)
{
    expect_text_refused("", "not valid JSON");
    expect_text_refused("{\"version\": 1,", "not valid JSON");
    expect_text_refused("[1, 2, 3]", "the top level must be an object");
    expect_text_refused("{\"version\": 1e999}", "not valid JSON"); /* overflows: not finite */
    expect_text_refused("{\"version\": NaN}", "not valid JSON");
    profile_t b;
    char err[512];
    cr_assert_eq(profile_read_json("/nonexistent/profile.json", &b, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, "cannot open"));
}

Test(profile_json, writer_refuses_what_it_cannot_write, .init = setup, .fini = teardown)
{
    profile_t a = sample_profile();
    char err[512];
    a.polyline[3].x = NAN;
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), -1);
    cr_assert_neq(access(path, F_OK), 0, "no file after a refused write");
    a.polyline[3].x = 1;
    a.curve.knots[5] = 0.05;
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, "invalid B-spline"));
    cr_assert_neq(access(path, F_OK), 0);
    profile_free(&a);
}

/* A clamped cubic through (r0, 0) .. (r1, 1) with one interior knot. */
static bspline_t cone(double r0, double r1)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 5), 0);
    const double U[] = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
    memcpy(c.knots, U, sizeof U);
    for (int i = 0; i < 5; i++)
        c.ctrl[i] = v2(r0 + (r1 - r0) * i / 4.0, i / 4.0);
    return c;
}

/* The sample profile with a camera and a meridian. */
static profile_t perspective_profile(void)
{
    profile_t p = sample_profile();
    p.has_camera = 1;
    p.camera = (profile_camera){.elevation_deg = 5.03, .focal_px = 2855.5, .roll_deg = 0.51,
                                .principal_point = v2(450, 600)};
    snprintf(p.camera.method, sizeof p.camera.method, "ellipses");
    p.camera.conics[0] = (profile_conic){v2(448.25, 790.5), {102.5, 15.7}, 0.09, 0.34, 191, 188};
    p.camera.conics[1] = (profile_conic){v2(451.5, 409.75), {364.9, 7.8}, 0.06, 0.25, 690, 652};
    p.has_meridian = 1;
    p.meridian = cone(0.27, 0.93);
    p.n_meridian_domains = 3;
    p.meridian_domains = malloc(3 * sizeof *p.meridian_domains);
    p.meridian_domains[0] = 0, p.meridian_domains[1] = 0.5, p.meridian_domains[2] = 1;
    return p;
}

Test(profile_json, camera_and_meridian_round_trip_exactly, .init = setup, .fini = teardown)
{
    profile_t a = perspective_profile(), b;
    char err[256];
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), 0, "%s", err);
    cr_assert(b.has_camera && b.has_meridian);
    cr_assert_str_eq(b.camera.method, "ellipses");
    cr_assert(b.camera.elevation_deg == 5.03 && b.camera.focal_px == 2855.5 && b.camera.roll_deg == 0.51);
    cr_assert(b.camera.principal_point.x == 450 && b.camera.principal_point.y == 600);
    cr_assert_str_eq(b.camera.note, "");
    for (int k = 0; k < 2; k++) {
        const profile_conic *x = &a.camera.conics[k], *y = &b.camera.conics[k];
        cr_assert(x->center_px.x == y->center_px.x && x->center_px.y == y->center_px.y);
        cr_assert(x->semi_axes_px[0] == y->semi_axes_px[0] && x->semi_axes_px[1] == y->semi_axes_px[1]);
        cr_assert(x->rms_px == y->rms_px && x->max_px == y->max_px && x->points == y->points &&
                  x->inliers == y->inliers);
    }
    cr_assert_eq(b.meridian.n_ctrl, 5);
    for (int i = 0; i < 9; i++)
        cr_assert_eq(b.meridian.knots[i], a.meridian.knots[i]);
    for (int i = 0; i < 5; i++)
        cr_assert(b.meridian.ctrl[i].x == a.meridian.ctrl[i].x && b.meridian.ctrl[i].y == a.meridian.ctrl[i].y);
    cr_assert_eq(b.n_meridian_domains, 3);
    cr_assert_eq(b.meridian_domains[1], 0.5);
    /* Every image-space field stays what it was. */
    cr_assert_eq(b.curve.n_ctrl, a.curve.n_ctrl);
    cr_assert_eq(b.n_polyline, a.n_polyline);
    cr_assert_str_eq(b.side, "right");
    /* The rule: the meridian when there is one. */
    const double *dom;
    int nd;
    cr_assert_eq(profile_shape(&b, &dom, &nd), &b.meridian);
    cr_assert(dom == b.meridian_domains && nd == 3);
    profile_free(&a);
    profile_free(&b);
}

Test(profile_json, without_the_blocks_the_bspline_is_the_shape, .init = setup, .fini = teardown)
{
    profile_t a = perspective_profile(), b;
    a.has_camera = a.has_meridian = 0;
    char err[256];
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    json_t *root = json_load_file(path, 0, NULL);
    cr_assert_null(json_object_get(root, "camera"));
    cr_assert_null(json_object_get(root, "meridian"));
    json_decref(root);
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), 0, "%s", err);
    cr_assert(!b.has_camera && !b.has_meridian);
    const double *dom;
    int nd;
    cr_assert_eq(profile_shape(&b, &dom, &nd), &b.curve);
    cr_assert(dom == b.domains && nd == b.n_domains);
    a.has_meridian = 1; /* frees the meridian too */
    profile_free(&a);
    profile_free(&b);
}

static json_t *mer(json_t *r) { return json_object_get(r, "meridian"); }
static json_t *cam(json_t *r) { return json_object_get(r, "camera"); }
static void rim_not_at_1(json_t *r)
{
    json_t *last = json_array_get(json_object_get(mer(r), "control_points"), 4);
    json_array_set_new(last, 1, json_real(0.98));
}
static void negative_radius(json_t *r)
{
    json_array_set_new(json_array_get(json_object_get(mer(r), "control_points"), 2), 0, json_real(-0.1));
}
static void domains_backwards(json_t *r) { json_array_set_new(json_object_get(mer(r), "domains"), 1, json_real(0)); }
static void no_meridian_knots(json_t *r) { json_object_del(mer(r), "knots"); }
static void meridian_not_object(json_t *r) { json_object_set_new(r, "meridian", json_integer(3)); }
static void unknown_method(json_t *r) { json_object_set_new(cam(r), "method", json_string("guess")); }
static void no_focal_for_ellipses(json_t *r) { json_object_set_new(cam(r), "focal_px", json_real(0)); }
static void no_rim_conic(json_t *r) { json_object_del(json_object_get(cam(r), "conics"), "rim"); }
static void elevation_string(json_t *r) { json_object_set_new(cam(r), "elevation_deg", json_string("5")); }

Test(profile_json, refuses_malformed_blocks, .init = setup, .fini = teardown)
{
    expect_refused_from(perspective_profile(), rim_not_at_1, "h = 1");
    expect_refused_from(perspective_profile(), negative_radius, "negative radius");
    expect_refused_from(perspective_profile(), domains_backwards, "meridian.domains");
    expect_refused_from(perspective_profile(), no_meridian_knots, "meridian.knots");
    expect_refused_from(perspective_profile(), meridian_not_object, "'meridian' must be an object");
    expect_refused_from(perspective_profile(), unknown_method, "camera.method");
    expect_refused_from(perspective_profile(), no_focal_for_ellipses, "camera.focal_px");
    expect_refused_from(perspective_profile(), no_rim_conic, "camera.conics.rim");
    expect_refused_from(perspective_profile(), elevation_string, "camera.elevation_deg");
}

/* The largest and smallest vertex radius of an OBJ at heights below and
 * above y_split. */
static void obj_radii(const char *obj, double y_split, double *r_low, double *r_high)
{
    FILE *f = fopen(obj, "r");
    cr_assert_not_null(f);
    char line[256];
    *r_low = *r_high = 0;
    double x, y, z;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3) {
            double r = hypot(x, z);
            if (y < y_split)
                *r_low = fmax(*r_low, r);
            else
                *r_high = fmax(*r_high, r);
        }
    fclose(f);
}

Test(profile_json, mesh_revolves_the_meridian, .init = setup, .fini = teardown)
{
    /* The B-spline is the vase; the meridian a cone from 0.27 to 0.93 of the
     * height: at height 1 the mesh must be a cone of those radii. */
    profile_t a = perspective_profile();
    char err[256], obj[160];
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    snprintf(obj, sizeof obj, "%s/m.obj", dir);
    const char *args[] = {"mesh", path, "-o", obj, "--segments", "64", NULL};
    cli_result r = cli_run(dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    double low, high;
    obj_radii(obj, 0.05, &low, &high);
    cr_expect_float_eq(low, 0.27, 1e-4, "radius at the base %.4f", low);
    cr_expect_float_eq(high, 0.93, 1e-4, "radius at the rim %.4f", high);
    remove(obj);
    snprintf(obj, sizeof obj, "%s/m.mtl", dir);
    remove(obj);
    cli_result_free(&r);
    profile_free(&a);
}

/* A researcher's own profile: the B-spline and nothing else. It reads, with
 * domains computed so that the polyline through them stays within the
 * documented 0.25 px of the curve; a report block counting domains rather
 * than boundaries is not an error (nothing reads it back). */
Test(profile_json, a_bspline_alone_is_a_profile, .init = setup, .fini = teardown)
{
    FILE *f = fopen(path, "w");
    fputs("{\"version\": 1, \"bspline\": {\"degree\": 3,\n"
          "  \"knots\": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],\n"
          "  \"control_points\": [[30, 0], [80, 40], [10, 120], [60, 200], [45, 260]]},\n"
          "  \"stats\": {\"contour_points\": 0, \"control_points\": 5, \"domains\": 3}}\n", f);
    fclose(f);
    profile_t p;
    char err[512];
    cr_assert_eq(profile_read_json(path, &p, err, sizeof err), 0, "%s", err);
    cr_assert_str_eq(p.side, "right");
    cr_assert_eq(p.n_polyline, 0);
    cr_assert_geq(p.n_domains, 3);
    cr_assert(p.domains[0] == 0.0 && p.domains[p.n_domains - 1] == 1.0);
    int has_knot = 0;
    for (int i = 0; i < p.n_domains; i++) {
        has_knot |= p.domains[i] == 0.5;
        if (i == 0)
            continue;
        cr_assert_gt(p.domains[i], p.domains[i - 1]);
        vec2 a = bspline_eval(&p.curve, p.domains[i - 1]), b = bspline_eval(&p.curve, p.domains[i]);
        for (int k = 1; k < 8; k++) { /* the curve's distance to the chord */
            vec2 c = bspline_eval(&p.curve, p.domains[i - 1] + (p.domains[i] - p.domains[i - 1]) * k / 8.0);
            vec2 d = v2_sub(b, a);
            double dist = fabs(d.x * (c.y - a.y) - d.y * (c.x - a.x)) / v2_len(d);
            cr_assert_leq(dist, 0.25 + 1e-9, "domain %d: %g px from its chord", i, dist);
        }
    }
    cr_assert(has_knot, "every knot is a boundary");
    profile_free(&p);
}
