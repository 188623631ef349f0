/* The C functions the Python package calls (docs/python.md, "The C side"),
 * against what they stand for: render_image against render_scene's film,
 * crosscheck_measure against crosscheck_run, reconstruct_image against
 * reconstruct_photo on the same pixels, profile_radius against a dense
 * sampling of the curve. */
#include <dirent.h>
#include <jansson.h>
#include <math.h>

#include "celadon/crosscheck.h"
#include "celadon/image.h"
#include "celadon/reconstruct.h"
#include "celadon/render_image.h"
#include "test_render_util.h"

static const char *scene_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"30\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 1.5, 3\" target=\"0, 0.45, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"20\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/></transform></shape>\n"
    "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.5\"/></emitter>\n"
    "</scene>\n";

/* An image of render_image_create equals render_scene's developed film, with
 * $spp given by the spp override as `celadon render --spp` gives it. */
Test(render_image, is_the_developed_film, .timeout = 60)
{
    render_fixture f;
    char scene[256], err[1024];
    render_fixture_with_scene(&f, "plum", scene_xml, scene, sizeof scene);
    scene_define spp = {"spp", "3", false};
    scene_options bo = scene_options_default();
    bo.seed = 7, bo.mesh_segments = 24;
    scene_t *s = scene_create_from_file(scene, &spp, 1, &bo, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    render_options ro = {.threads = 2, .aovs = RENDER_AOV_DEPTH};
    film_t film;
    cr_assert_eq(render_scene(s, &ro, &film, NULL, err, sizeof err), 0, "%s", err);
    float *want = malloc(sizeof *want * (size_t)film.width * film.height * film.nchannels);
    cr_assert_not_null(want);
    film_develop(&film, want);

    render_image_options o = {.spp = 3, .seed = 7, .mesh_segments = 24, .threads = 1, .aovs = RENDER_AOV_DEPTH};
    int status, w, h, c;
    render_image_t *im = render_image_create(scene, NULL, 0, &o, &status, err, sizeof err);
    cr_assert_not_null(im, "%s", err);
    render_image_size(im, &w, &h, &c);
    cr_assert(w == 24 && h == 20 && c == 4 && film.nchannels == 4);
    for (int k = 0; k < c; k++)
        cr_expect_str_eq(render_image_channel(im, k), film.names[k]);
    cr_expect_str_eq(render_image_channel(im, 3), "Z");
    cr_expect_eq(memcmp(render_image_pixels(im), want, sizeof *want * (size_t)w * h * c), 0);
    cr_expect_eq(render_image_stats(im)->interrupted, 0);
    render_image_destroy(im);
    free(want);
    film_free(&film);
    scene_destroy(s);
    render_fixture_close(&f);
}

/* A scene that cannot be built is bad input, with the scene's own message. */
Test(render_image, bad_scene_is_bad_input)
{
    render_fixture f;
    char scene[256], err[1024], want[1024];
    render_fixture_open(&f);
    render_write_file(&f, "scene.xml", "<scene version=\"3.0.0\"><shape type=\"nonsense\"/></scene>", scene,
                      sizeof scene);
    cr_assert_null(scene_create_from_file(scene, NULL, 0, NULL, want, sizeof want));
    render_image_options o = {.seed = -1};
    int status = 0;
    cr_assert_null(render_image_create(scene, NULL, 0, &o, &status, err, sizeof err));
    cr_expect_eq(status, 2);
    cr_expect_str_eq(err, want);
    render_fixture_close(&f);
}

/* crosscheck_measure's report is crosscheck_run's (to report.json's 10
 * digits), and it writes no file. */
Test(crosscheck_measure, is_crosscheck_run_without_files, .timeout = 120)
{
    render_fixture f;
    char scene[256], err[1024];
    render_fixture_with_scene(&f, "cylinder", scene_xml, scene, sizeof scene);
    int segments[] = {8, 16, 32};
    scene_define spp = {"spp", "2", false};
    render_image_options o = {.seed = 3, .threads = 2};
    crosscheck_params p = {.scene_path = scene, .defs = &spp, .ndefs = 1, .build = render_image_scene_options(&o),
                           .threads = 2, .segments = segments, .nsegments = 3, .geo_grid = 4};
    crosscheck_result res;
    cr_assert_eq(crosscheck_run(&p, NULL, &res, err, sizeof err), 0, "%s", err);
    char *text = NULL;
    cr_assert_eq(crosscheck_measure(scene, &spp, 1, &o, segments, 3, 0, &text, err, sizeof err), 0, "%s", err);
    json_t *rep = json_loads(text, 0, NULL);
    cr_assert_not_null(rep);
    json_t *rows = json_object_get(rep, "segments");
    cr_assert_eq(json_array_size(rows), 3);
    for (int i = 0; i < 3; i++) {
        json_t *row = json_array_get(rows, (size_t)i);
        cr_expect_eq(json_integer_value(json_object_get(row, "n")), segments[i]);
        double e = res.rows[i].mean_abs_diff;
        cr_expect_leq(fabs(json_real_value(json_object_get(row, "mean_abs_diff")) - e), 1e-9 * e);
        cr_expect_eq(json_integer_value(json_object_get(row, "coverage_rays")), res.rows[i].coverage_rays);
    }
    double slope = res.fits[CROSSCHECK_PRIMARY_METRIC].slope;
    cr_expect_leq(fabs(json_real_value(json_object_get(rep, "fitted_slope")) - slope), 1e-9 * fabs(slope));
    json_decref(rep);
    free(text);
    crosscheck_result_free(&res);
    DIR *d = opendir(f.dir);
    int files = 0;
    for (struct dirent *e; (e = readdir(d));)
        files += e->d_name[0] != '.';
    closedir(d);
    cr_expect_eq(files, 2, "only profile.json and scene.xml: %d files", files);
    render_fixture_close(&f);
}

static const char *const demo_photo = "scenes/demo/photo.png";

/* The demo photo's pixels in memory give the profile its file gives. */
Test(reconstruct_image, is_reconstruct_photo_on_the_same_pixels, .timeout = 60)
{
    char err[1024];
    reconstruct_options opt = reconstruct_options_default();
    reconstruction a, b;
    cr_assert_eq(reconstruct_photo(demo_photo, &opt, &a, err, sizeof err), 0, "%s", err);
    image_t img;
    cr_assert_eq(image_read(demo_photo, &img, err, sizeof err), 0, "%s", err);
    cr_assert_eq(reconstruct_image(&img, &opt, &b, err, sizeof err), 0, "%s", err);
    cr_assert_eq(a.curve.n_ctrl, b.curve.n_ctrl);
    cr_expect_eq(memcmp(a.curve.ctrl, b.curve.ctrl, sizeof *a.curve.ctrl * (size_t)a.curve.n_ctrl), 0);
    cr_expect_eq(a.quality.passed, b.quality.passed);
    image_free(&img);
    reconstruction_free(&a);
    reconstruction_free(&b);
}

/* Pixels the file reader would refuse are refused with its words. */
Test(reconstruct_image, refuses_what_the_reader_refuses)
{
    char err[1024];
    reconstruct_options opt = reconstruct_options_default();
    reconstruction r;
    image_t img = image_alloc(20, 40, 3);
    cr_expect_eq(reconstruct_image(&img, &opt, &r, err, sizeof err), 2);
    cr_expect_str_eq(err, "image too small (20x40; at least 32x32 needed)");
    reconstruction_free(&r);
    image_free(&img);
    img = image_alloc(40, 40, 3);
    img.data[5] = NAN;
    cr_expect_eq(reconstruct_image(&img, &opt, &r, err, sizeof err), 2);
    reconstruction_free(&r);
    image_free(&img);
}

Test(reconstruct_option_set, checks_as_the_command_line)
{
    char err[256];
    reconstruct_options o = reconstruct_options_default();
    cr_expect_eq(reconstruct_option_set(&o, "threshold", "120", err, sizeof err), 0);
    cr_expect_eq(o.recon.threshold, 120);
    cr_expect_eq(reconstruct_option_set(&o, "side", "left", err, sizeof err), 0);
    cr_expect_eq(o.recon.side, RECON_SIDE_LEFT);
    cr_expect_eq(reconstruct_option_set(&o, "force", "1", err, sizeof err), 0);
    cr_expect_eq(o.force, 1);
    cr_expect_eq(reconstruct_option_set(&o, "threshold", "256", err, sizeof err), -1);
    cr_expect_str_eq(err, "threshold wants an integer 0..255, not '256'");
    cr_expect_eq(reconstruct_option_set(&o, "threshold", "1.5", err, sizeof err), -1);
    cr_expect_eq(reconstruct_option_set(&o, "fov", "0.5", err, sizeof err), -1);
    cr_expect_eq(reconstruct_option_set(&o, "smoothing", "x", err, sizeof err), -1);
    cr_expect_eq(reconstruct_option_set(&o, "colour", "red", err, sizeof err), -1);
    cr_expect_eq(o.recon.threshold, 120, "a refused value leaves the option as it was");
}

/* The outermost crossing of height h found on a dense sampling of the
 * curve (linear between samples): the brute-force reference. */
enum { RADIUS_SAMPLES = 200000 };
static double sampled_radius(const vec2 *pts, double h_abs, int *found)
{
    double best = 0;
    *found = 0;
    for (int i = 1; i <= RADIUS_SAMPLES; i++) {
        vec2 prev = pts[i - 1], p = pts[i];
        if ((prev.y - h_abs) * (p.y - h_abs) <= 0 && prev.y != p.y) {
            double r = prev.x + (h_abs - prev.y) / (p.y - prev.y) * (p.x - prev.x);
            best = (*found)++ ? fmax(best, r) : r;
        }
    }
    return best;
}

/* On every test vessel (a gourd's waist, a bottle's shoulder, a bowl whose
 * wall turns back), at heights across the whole range. */
Test(profile_radius, is_the_outermost_crossing)
{
    vec2 *pts = malloc(sizeof *pts * (RADIUS_SAMPLES + 1));
    cr_assert_not_null(pts);
    for (int i = 0; i < sor_test_profile_count(); i++) {
        profile_t p;
        memset(&p, 0, sizeof p);
        sor_test_profile(i, &p.curve);
        for (int j = 0; j <= RADIUS_SAMPLES; j++)
            pts[j] = bspline_eval(&p.curve, (double)j / RADIUS_SAMPLES);
        double h_rim = bspline_eval(&p.curve, 1.0).y;
        for (int k = 0; k <= 20; k++) {
            double h = 0.025 + 0.95 * k / 20.0, r;
            int found;
            double want = sampled_radius(pts, h * h_rim, &found);
            int rc = profile_radius(&p, h, &r);
            cr_expect_eq(rc == 0, found > 0, "%s at h = %g", sor_test_profile_name(i), h);
            if (rc == 0 && found)
                cr_expect_leq(fabs(r - want / h_rim), 1e-6, "%s at h = %g: %.9g, sampled %.9g",
                              sor_test_profile_name(i), h, r, want / h_rim);
        }
        double r;
        cr_expect_eq(profile_radius(&p, 1.5, &r), -1, "above the rim");
        bspline_free(&p.curve);
    }
    free(pts);
}
