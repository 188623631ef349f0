/* profile.json's perspective blocks: the camera and the meridian round trip
 * exactly, files without them read as before, malformed blocks are refused
 * with a one-line reason, and `celadon mesh` revolves the meridian when
 * there is one (profile_shape), the B-spline otherwise. */
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
    snprintf(dir, sizeof dir, "/tmp/celadon-test-meridian-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/profile.json", dir);
}

static void teardown(void)
{
    char cmd[200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
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

/* The image-space profile of test_vase_curve, a camera and a meridian. */
static profile_t perspective_profile(void)
{
    profile_t p;
    memset(&p, 0, sizeof p);
    snprintf(p.source_path, sizeof p.source_path, "bowl.jpg");
    p.source_width = 900, p.source_height = 1200;
    p.axis_origin = v2(450, 1000), p.axis_direction = v2(0, -1);
    snprintf(p.side, sizeof p.side, "left");
    p.n_polyline = 3;
    p.polyline = malloc(3 * sizeof *p.polyline);
    p.polyline[0] = v2(30, 0), p.polyline[1] = v2(20, 70), p.polyline[2] = v2(33, 140);
    p.curve = test_vase_curve();
    p.n_domains = 2;
    p.domains = malloc(2 * sizeof *p.domains);
    p.domains[0] = 0, p.domains[1] = 1;
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

Test(profile_json_meridian, round_trip_is_exact, .init = setup, .fini = teardown)
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
    cr_assert_eq(b.n_polyline, 3);
    cr_assert_str_eq(b.side, "left");
    /* The rule: the meridian when there is one. */
    const double *dom;
    int nd;
    cr_assert_eq(profile_shape(&b, &dom, &nd), &b.meridian);
    cr_assert(dom == b.meridian_domains && nd == 3);
    profile_free(&a);
    profile_free(&b);
}

Test(profile_json_meridian, without_the_blocks_the_bspline_is_the_shape, .init = setup, .fini = teardown)
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

/* Writes the perspective profile, edits its JSON, expects a refusal naming want. */
static void expect_refused(void (*edit)(json_t *root), const char *want)
{
    profile_t a = perspective_profile(), b;
    char err[512] = "";
    cr_assert_eq(profile_write_json(path, &a, err, sizeof err), 0, "%s", err);
    json_t *root = json_load_file(path, 0, NULL);
    edit(root);
    cr_assert_eq(json_dump_file(root, path, 0), 0);
    json_decref(root);
    cr_assert_eq(profile_read_json(path, &b, err, sizeof err), -1, "accepted a file edited for '%s'", want);
    cr_assert_not_null(strstr(err, want), "reason '%s' lacks '%s'", err, want);
    cr_assert_null(strchr(err, '\n'));
    cr_assert_null(b.meridian.knots);
    cr_assert_null(b.meridian_domains);
    profile_free(&a);
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

Test(profile_json_meridian, refuses_malformed_blocks, .init = setup, .fini = teardown)
{
    expect_refused(rim_not_at_1, "h = 1");
    expect_refused(negative_radius, "negative radius");
    expect_refused(domains_backwards, "meridian.domains");
    expect_refused(no_meridian_knots, "meridian.knots");
    expect_refused(meridian_not_object, "'meridian' must be an object");
    expect_refused(unknown_method, "camera.method");
    expect_refused(no_focal_for_ellipses, "camera.focal_px");
    expect_refused(no_rim_conic, "camera.conics.rim");
    expect_refused(elevation_string, "camera.elevation_deg");
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

Test(profile_json_meridian, mesh_revolves_the_meridian, .init = setup, .fini = teardown)
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
    cli_result_free(&r);
    profile_free(&a);
}
