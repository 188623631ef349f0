/* celadon crosscheck end to end on a tiny scene: a near-cylinder vessel whose
 * profile the revolved mesh's rings follow exactly (200 rings on a straight
 * wall), so every difference comes from the angular segments N and the
 * inscribed polygon's sagitta r (1 - cos(pi/N)) ~ N^-2 must show in the
 * deterministic geometry metrics. Also: bad input exits 2 and leaves nothing. */
#include <fcntl.h>
#include <jansson.h>
#include <math.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "celadon/crosscheck.h"
#include "celadon/image.h"
#include "test_render_util.h"

extern char **environ;

static const char *scene_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"30\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 1.5, 3\" target=\"0, 0.45, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"48\"/><integer name=\"height\" value=\"40\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/></transform></shape>\n"
    "  <shape type=\"disk\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/><translate y=\"3\"/></transform>\n"
    "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"5\"/></emitter></shape>\n"
    "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.3\"/></emitter>\n"
    "</scene>\n";

static const char *no_sor_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
    "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
    "  <shape type=\"sphere\"/>\n"
    "</scene>\n";

static const char *celadon_bin(void)
{
    const char *bin = getenv("CELADON_BIN");
    if (!bin || !*bin)
        cr_skip_test("CELADON_BIN is not set");
    return bin;
}

/* Runs celadon with args (NULL-terminated), stdout to /dev/null, stderr into
 * err. Returns the exit code. */
static int run_celadon(const render_fixture *f, const char *const *args, char *err, size_t errlen)
{
    char errpath[128];
    snprintf(errpath, sizeof errpath, "%s/stderr.txt", f->dir);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, errpath, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    char *argv[40];
    int n = 0;
    argv[n++] = (char *)celadon_bin();
    for (; *args && n < 39; args++)
        argv[n++] = (char *)*args;
    argv[n] = NULL;
    pid_t pid;
    cr_assert_eq(posix_spawn(&pid, argv[0], &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    FILE *fp = fopen(errpath, "r");
    cr_assert_not_null(fp);
    size_t k = fread(err, 1, errlen - 1, fp);
    err[k] = '\0';
    fclose(fp);
    remove(errpath);
    cr_assert(WIFEXITED(status), "celadon died from a signal; stderr: %s", err);
    return WEXITSTATUS(status);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static int count_newlines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

static double number(json_t *obj, const char *key)
{
    json_t *v = json_object_get(obj, key);
    cr_assert(json_is_number(v), "report field '%s' missing or not a number", key);
    return json_number_value(v);
}

/* Runs a crosscheck that must succeed and returns its report.json. */
/* What the last crosscheck_report's run printed on stderr. */
static char report_stderr[4096];

static json_t *crosscheck_report(const render_fixture *f, const char *const *args, const char *dir)
{
    char path[320], *err = report_stderr;
    cr_assert_eq(run_celadon(f, args, err, sizeof report_stderr), 0, "stderr: %s", err);
    snprintf(path, sizeof path, "%s/report.json", dir);
    json_error_t jerr;
    json_t *rep = json_load_file(path, 0, &jerr);
    cr_assert_not_null(rep, "report.json: %s", jerr.text);
    return rep;
}

static const char *const metrics[] = {"rel_mse", "mean_abs_diff", "coverage_area", "depth_rel_err",
                                       "normal_err_deg"};
/* The report's field name of a metric in a row. */
static const char *row_key(const char *metric)
{
    return strcmp(metric, "coverage_area") ? metric : "coverage_area_px";
}

/* The stall's span and slopes recomputed from the report's rows: from the
 * largest N at most a quarter of the last (else the first) to the last,
 * each slope the chord log(e_to / e_from) / log(N_to / N_from). */
static void expect_stall_from_rows(json_t *stall, json_t *rows)
{
    size_t n = json_array_size(rows);
    cr_assert_geq(n, 2);
    json_t *last = json_array_get(rows, n - 1), *first = json_array_get(rows, 0);
    for (size_t i = 0; i < n - 1; i++)
        if (4 * number(json_array_get(rows, i), "n") <= number(last, "n"))
            first = json_array_get(rows, i);
    cr_expect_eq(number(stall, "from"), number(first, "n"));
    cr_expect_eq(number(stall, "to"), number(last, "n"));
    double span = log(number(last, "n") / number(first, "n"));
    double image = log(number(last, "mean_abs_diff") / number(first, "mean_abs_diff")) / span;
    double depth = log(number(last, "depth_rel_err") / number(first, "depth_rel_err")) / span;
    cr_expect_float_eq(number(stall, "image_slope"), image, 1e-6 * (1.0 + fabs(image)));
    cr_expect_float_eq(number(stall, "depth_slope"), depth, 1e-6 * (1.0 + fabs(depth)));
}

/* Each fit's local_slopes are the slopes between successive rows. */
static void check_local_slopes(json_t *fits, json_t *rows)
{
    for (size_t m = 0; m < sizeof metrics / sizeof *metrics; m++) {
        json_t *local = json_object_get(json_object_get(fits, metrics[m]), "local_slopes");
        cr_assert_eq(json_array_size(local), json_array_size(rows) - 1, "%s", metrics[m]);
        for (size_t i = 1; i < json_array_size(rows); i++) {
            json_t *r0 = json_array_get(rows, i - 1), *r1 = json_array_get(rows, i);
            double e0 = number(r0, row_key(metrics[m])), e1 = number(r1, row_key(metrics[m]));
            json_t *v = json_array_get(local, i - 1);
            if (!(e0 > 0.0 && e1 > 0.0)) {
                cr_assert(json_is_null(v), "%s: a slope where an error is 0", metrics[m]);
                continue;
            }
            double want = log(e1 / e0) / log(number(r1, "n") / number(r0, "n"));
            cr_assert_float_eq(json_number_value(v), want, 1e-6 * (1.0 + fabs(want)), "%s", metrics[m]);
        }
    }
}

Test(crosscheck, geometry_converges_as_n_minus_2, .timeout = 120)
{
    render_fixture f;
    char scene[256], dir[256], path[320], err[4096];
    render_fixture_with_scene(&f, "cylinder", scene_xml, scene, sizeof scene);
    snprintf(dir, sizeof dir, "%s/xc", f.dir);
    const char *args[] = {"crosscheck", scene, "--segments", "8,16,32,64", "-o", dir, "--threads", "2", NULL};
    json_t *rep = crosscheck_report(&f, args, dir);
    cr_assert_eq(number(rep, "width"), 48);
    cr_assert_eq(number(rep, "height"), 40);
    cr_assert_eq(number(rep, "sor_shapes"), 1);
    cr_assert_gt(number(rep, "sor_rays"), 0);
    double slope = number(rep, "fitted_slope");
    cr_assert_lt(slope, 0.0, "fitted slope %g", slope);
    json_t *fits = json_object_get(rep, "fits");
    double depth_slope = number(json_object_get(fits, "depth_rel_err"), "slope");
    cr_assert(depth_slope > -2.25 && depth_slope < -1.75, "depth error slope %g, expected about -2", depth_slope);
    double normal_slope = number(json_object_get(fits, "normal_err_deg"), "slope");
    cr_assert_lt(normal_slope, -1.0, "normal error slope %g", normal_slope);

    json_t *rows = json_object_get(rep, "segments");
    cr_assert_eq(json_array_size(rows), 4);
    cr_assert_eq(number(rep, "fit_from"), 8, "every N is fitted by default");
    cr_assert(json_is_null(json_object_get(rep, "image_error_stall")), "a stall reported on a clean scene");
    check_local_slopes(fits, rows);
    static const char *keys[] = {"seconds", "rel_mse", "mean_abs_diff", "coverage_pixels", "coverage_rays",
                                 "coverage_area_px", "depth_rel_err", "normal_err_deg"};
    double prev_mad = INFINITY, prev_depth = INFINITY, prev_cov = INFINITY;
    for (size_t i = 0; i < json_array_size(rows); i++) {
        json_t *r = json_array_get(rows, i);
        for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
            cr_assert_geq(number(r, keys[k]), 0.0, "%s", keys[k]);
        int n = (int)number(r, "n");
        double mad = number(r, "mean_abs_diff"), depth = number(r, "depth_rel_err");
        double cov = number(r, "coverage_area_px");
        cr_assert_lt(mad, prev_mad, "mean_abs_diff does not fall at N = %d", n);
        cr_assert_lt(depth, prev_depth, "depth error does not fall at N = %d", n);
        cr_assert_leq(cov, prev_cov, "coverage difference grows at N = %d", n);
        prev_mad = mad, prev_depth = depth, prev_cov = cov;
        /* The images of every N are there. */
        snprintf(path, sizeof path, "%s/%s", dir, json_string_value(json_object_get(r, "image")));
        cr_assert(exists(path), "%s", path);
        snprintf(path, sizeof path, "%s/mesh-%d.png", dir, n);
        cr_assert(exists(path), "%s", path);
    }
    /* The coarsest mesh misses some silhouette coverage that the finest does not. */
    cr_assert_gt(number(json_array_get(rows, 0), "coverage_pixels"), 0);
    json_decref(rep);

    snprintf(path, sizeof path, "%s/convergence.png", dir);
    int w, h, c;
    cr_assert_eq(image_probe(path, &w, &h, &c, err, sizeof err), 0, "%s", err);
    cr_assert(w == 900 && h == 600, "plot is %dx%d", w, h);
    snprintf(path, sizeof path, "%s/analytic.exr", dir);
    cr_assert(exists(path));

    /* A second run into the same folder replaces the earlier results. */
    const char *again[] = {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--res", "16x12", NULL};
    cr_assert_eq(run_celadon(&f, again, err, sizeof err), 0, "stderr: %s", err);
    snprintf(path, sizeof path, "%s/mesh-64.exr", dir);
    cr_assert(!exists(path), "the earlier run's files survived");
    render_fixture_close(&f);
}

/* A curved vessel whose profile.json has only three domain boundaries: the
 * rings render --geometry mesh:N adds with N (mesh_rings) bring the profile
 * chords down with the angular ones, so the depth error still falls as N^-2.
 * With the three rings alone it would stall at the chords' error. */
Test(crosscheck, coarse_profile_domains_refined_with_n, .timeout = 120)
{
    render_fixture f;
    render_fixture_open(&f);
    render_write_profile_domains(&f, "profile.json", "plum", 3);
    char scene[256], dir[256];
    render_write_file(&f, "scene.xml", scene_xml, scene, sizeof scene);
    snprintf(dir, sizeof dir, "%s/xc", f.dir);
    const char *args[] = {"crosscheck", scene,  "--segments", "16,32,64,128", "-o", dir, "--threads",
                          "2",          "--spp", "1",         NULL};
    json_t *rep = crosscheck_report(&f, args, dir);
    json_t *fits = json_object_get(rep, "fits");
    double depth_slope = number(json_object_get(fits, "depth_rel_err"), "slope");
    cr_assert(depth_slope > -2.3 && depth_slope < -1.7, "depth error slope %g, expected about -2", depth_slope);
    json_decref(rep);
    render_fixture_close(&f);
}

/* --fit-from N fits the slopes over the N >= fit_from only: the report's
 * slope is the least-squares line through those points and no others. */
Test(crosscheck, fit_from_restricts_the_fit, .timeout = 60)
{
    render_fixture f;
    char scene[256], dir[256];
    render_fixture_with_scene(&f, "cylinder", scene_xml, scene, sizeof scene);
    snprintf(dir, sizeof dir, "%s/xc", f.dir);
    const char *args[] = {"crosscheck", scene, "--segments", "8,16,32,64", "--fit-from", "16", "-o",
                          dir,          "--res", "24x20",    "--spp",      "1",          NULL};
    json_t *rep = crosscheck_report(&f, args, dir);
    cr_assert_eq(number(rep, "fit_from"), 16);
    json_t *rows = json_object_get(rep, "segments"), *fits = json_object_get(rep, "fits");
    for (size_t m = 0; m < sizeof metrics / sizeof *metrics; m++) {
        /* The least-squares slope of the rows with N >= 16 and error > 0. */
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        int k = 0;
        for (size_t i = 1; i < json_array_size(rows); i++) {
            double e = number(json_array_get(rows, i), row_key(metrics[m]));
            if (e > 0.0) {
                double lx = log10(number(json_array_get(rows, i), "n")), ly = log10(e);
                sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, k++;
            }
        }
        json_t *fit = json_object_get(fits, metrics[m]);
        cr_assert_eq(number(fit, "points"), k, "%s", metrics[m]);
        if (k >= 2) {
            double want = (k * sxy - sx * sy) / (k * sxx - sx * sx);
            cr_assert_float_eq(number(fit, "slope"), want, 1e-9 * (1.0 + fabs(want)), "%s", metrics[m]);
        }
    }
    cr_assert_eq(number(rep, "fitted_slope"), number(json_object_get(fits, "mean_abs_diff"), "slope"));
    check_local_slopes(fits, rows);
    json_decref(rep);
    render_fixture_close(&f);
}

/* -a DIR: the scene's profile.json, not beside the scene, is found in an
 * extra search folder, as `render -a` finds it; without -a the scene is
 * refused in one line naming the file, and nothing is written. */
Test(crosscheck, an_a_folder_is_searched, .timeout = 60)
{
    render_fixture f;
    char scene[256], moved[300], dir[256], report[300], err[4096];
    render_fixture_with_scene(&f, "cylinder", scene_xml, scene, sizeof scene);
    snprintf(moved, sizeof moved, "%s/scenes", f.dir);
    cr_assert_eq(mkdir(moved, 0755), 0);
    snprintf(moved, sizeof moved, "%s/scenes/scene.xml", f.dir);
    cr_assert_eq(rename(scene, moved), 0);
    snprintf(dir, sizeof dir, "%s/xc", f.dir);
    snprintf(report, sizeof report, "%s/report.json", dir);
    const char *without[] = {"crosscheck", moved, "--segments", "8,16", "-o", dir, "--res", "12x10", "--spp", "1",
                             NULL};
    int status = run_celadon(&f, without, err, sizeof err);
    cr_expect(status == 2 && count_newlines(err) == 1 && strstr(err, "profile.json"), "%d: %s", status, err);
    cr_expect(!exists(dir), "a refused crosscheck wrote %s", dir);
    const char *with[] = {"crosscheck", moved, "--segments", "8,16", "-o", dir, "--res", "12x10", "--spp", "1",
                          "-a", f.dir, NULL};
    status = run_celadon(&f, with, err, sizeof err);
    cr_expect_eq(status, 0, "stderr: %s", err);
    cr_expect(exists(report), "no %s", report);
    render_fixture_close(&f);
}

/* A plate lying exactly in the vessel's mouth cap (y = 1, the SOR's height):
 * which of the two coincident surfaces a ray hits is decided by rounding,
 * differently for the analytic cap and the meshed one, at every N. The
 * image error stops falling while the depth error keeps its N^-2, and the
 * cross-check says so; the same vessel without the plate does not stall. */
static const char *plate_xml =
    "<scene version=\"3.0.0\">\n"
    "  <default name=\"plate_y\" value=\"1\"/>\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"30\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 3, 2\" target=\"0, 0.5, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"48\"/><integer name=\"height\" value=\"40\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/>"
    "</transform></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"0.3\"/>"
    "<translate y=\"$plate_y\"/></transform>\n"
    "    <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.9, 0.1, 0.1\"/></bsdf></shape>\n"
    "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n"
    "</scene>\n";

/* Rows at N = 8..128 whose image and depth errors follow N^image and
 * N^depth exactly. */
static crosscheck_stall stall_of_power_laws(double image, double depth)
{
    crosscheck_row rows[5];
    for (int i = 0; i < 5; i++) {
        double n = 8 << i;
        rows[i] = (crosscheck_row){.segments = 8 << i, .mean_abs_diff = 0.3 * pow(n, image),
                                   .depth_rel_err = 0.02 * pow(n, depth)};
    }
    return crosscheck_find_stall(rows, 5);
}

/* The rule itself, on errors of known slope: the image error stalls when
 * it falls more slowly than N^-1 while the depth error falls faster than
 * N^-1.5, measured over the finest factor of four (32 to 128). Slopes each
 * side of both thresholds, the image's at -0.75 (between -1 and -0.5, where
 * a coincident plate's partial stall lies) and -1.25. */
Test(crosscheck, stall_rule_on_errors_of_known_slope)
{
    crosscheck_stall st = stall_of_power_laws(-0.75, -2.0);
    cr_expect(st.found, "image N^-0.75 with depth N^-2 is a stall");
    cr_expect_eq(st.n_from, 32);
    cr_expect_eq(st.n_to, 128);
    cr_expect_float_eq(st.image_slope, -0.75, 1e-9);
    cr_expect_float_eq(st.depth_slope, -2.0, 1e-9);
    cr_expect(stall_of_power_laws(-0.2, -2.0).found, "image N^-0.2 with depth N^-2 is a stall");
    cr_expect(!stall_of_power_laws(-1.25, -2.0).found, "image N^-1.25 still converges");
    cr_expect(!stall_of_power_laws(-2.0, -2.0).found, "both at N^-2: no stall");
    cr_expect(!stall_of_power_laws(-0.75, -1.25).found, "the depth error too slow: not a mesh converging");
    crosscheck_row one = {.segments = 8, .mean_abs_diff = 0.1, .depth_rel_err = 0.01};
    cr_expect(!crosscheck_find_stall(&one, 1).found, "one row has no slope");
}

Test(crosscheck, coincident_surfaces_stall_the_image_error, .timeout = 120)
{
    render_fixture f;
    char scene[256], dir[256];
    render_fixture_with_scene(&f, "cylinder", plate_xml, scene, sizeof scene);
    snprintf(dir, sizeof dir, "%s/xc", f.dir);
    /* plate_y 1: coincident with the mouth cap; 1.05: a hair above it. */
    for (int lifted = 0; lifted < 2; lifted++) {
        const char *args[] = {"crosscheck", scene, "--segments", "8,16,32,64,128", "-o", dir, "--res", "64x52",
                              "-D", lifted ? "plate_y=1.05" : "plate_y=1", NULL};
        json_t *rep = crosscheck_report(&f, args, dir);
        json_t *stall = json_object_get(rep, "image_error_stall");
        cr_assert_not_null(stall, "report.json has no image_error_stall");
        json_t *fits = json_object_get(rep, "fits");
        cr_log_info("plate %s: mean_abs_diff slope %.2f, depth slope %.2f", lifted ? "lifted" : "coincident",
                    number(json_object_get(fits, "mean_abs_diff"), "slope"),
                    number(json_object_get(fits, "depth_rel_err"), "slope"));
        if (!lifted) {
            cr_assert(json_is_object(stall), "the coincident plate was not reported");
            cr_assert_eq(number(stall, "from"), 32);
            cr_assert_eq(number(stall, "to"), 128);
            cr_assert_gt(number(stall, "image_slope"), -1.0);
            cr_assert_lt(number(stall, "depth_slope"), -1.5);
            expect_stall_from_rows(stall, json_object_get(rep, "segments"));
            /* the note on stderr names the likely cause */
            cr_assert(strstr(report_stderr, "coincident surfaces"), "stderr: %s", report_stderr);
        } else {
            cr_assert(json_is_null(stall), "a stall reported with the plate lifted off the cap");
        }
        json_decref(rep);
    }
    render_fixture_close(&f);
}

/* Every bad input exits 2 with one line and creates nothing at DIR. */
Test(crosscheck, bad_input_exits_2_and_writes_nothing, .timeout = 60)
{
    render_fixture f;
    char scene[256], nosor[256], broken[256], missing[256], dir[256], err[4096];
    render_fixture_with_scene(&f, "cylinder", scene_xml, scene, sizeof scene);
    render_write_file(&f, "nosor.xml", no_sor_xml, nosor, sizeof nosor);
    render_write_file(&f, "broken.xml", "<scene version=\"3.0.0\"><shape type=\"sor\">", broken, sizeof broken);
    snprintf(missing, sizeof missing, "%s/missing.xml", f.dir);
    snprintf(dir, sizeof dir, "%s/out", f.dir);
    const char *cases[][12] = {
        {"crosscheck", missing, "--segments", "8,16", "-o", dir, NULL},
        {"crosscheck", broken, "--segments", "8,16", "-o", dir, NULL},
        {"crosscheck", nosor, "--segments", "8,16", "-o", dir, NULL},
        {"crosscheck", scene, "--segments", "16", "-o", dir, NULL},
        {"crosscheck", scene, "--segments", "16,8", "-o", dir, NULL},
        {"crosscheck", scene, "--segments", "2,x", "-o", dir, NULL},
        {"crosscheck", scene, "--segments", "8,16", NULL},
        {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--res", "4x", NULL},
        {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--frobnicate", "1", NULL},
        {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--fit-from", "9", NULL},
        {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--fit-from", "x", NULL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        cr_assert_eq(run_celadon(&f, cases[i], err, sizeof err), 2, "case %zu: stderr: %s", i, err);
        cr_assert_eq(count_newlines(err), 1, "case %zu: not one line: %s", i, err);
        cr_assert(!exists(dir), "case %zu left %s behind", i, dir);
    }
    /* A folder holding something else is refused and left as it was. */
    cr_assert_eq(mkdir(dir, 0755), 0);
    char keep[320];
    render_write_file(&f, "out/keep.txt", "mine\n", keep, sizeof keep);
    const char *foreign[] = {"crosscheck", scene, "--segments", "8,16", "-o", dir, "--res", "8x8", NULL};
    cr_assert_eq(run_celadon(&f, foreign, err, sizeof err), 2, "stderr: %s", err);
    cr_assert(exists(keep));
    char report[320];
    snprintf(report, sizeof report, "%s/report.json", dir);
    cr_assert(!exists(report));
    /* No staging folder is left next to it either. */
    char cmd[512];
    snprintf(cmd, sizeof cmd, "test -z \"$(ls -A '%s' | grep crosscheck)\"", f.dir);
    cr_assert_eq(system(cmd), 0, "a staging folder was left in %s", f.dir);
    render_fixture_close(&f);
}
