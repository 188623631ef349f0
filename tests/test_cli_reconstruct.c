/* End to end: `celadon reconstruct` run as a process ($CELADON_BIN, the
 * sanitized CLI under `make test-asan`) on drawn photos with known geometry,
 * and on every kind of bad input. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <ftw.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/profile.h"
#include "support/cli_run.h"
#include "support/drawn_silhouettes.h"
#include "support/synth_vessel.h"

#define SEGMENTS 48

static char workdir[256];

static void make_workdir(void)
{
    if (!getenv("CELADON_BIN"))
        cr_skip_test("CELADON_BIN is not set (run through make test)");
    snprintf(workdir, sizeof workdir, "/tmp/celadon-cli-XXXXXX");
    cr_assert_not_null(mkdtemp(workdir));
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_workdir(void)
{
    if (workdir[0])
        nftw(workdir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

TestSuite(cli_reconstruct, .init = make_workdir, .fini = remove_workdir);

/* Slurps a whole file (NUL-terminated); *len may be NULL. */
static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    cr_assert_not_null(buf);
    cr_assert_eq(fread(buf, 1, (size_t)n, f), (size_t)n);
    buf[n] = 0;
    fclose(f);
    if (len)
        *len = (size_t)n;
    return buf;
}

/* Runs `celadon reconstruct ARGS...` (NULL-terminated), capturing stdout and stderr. */
static cli_result run_reconstruct(const char *const *args)
{
    const char *argv[64] = {"reconstruct"};
    int n = 1;
    for (; args[n - 1] && n < 63; n++)
        argv[n] = args[n - 1];
    argv[n] = NULL;
    return cli_run(workdir, argv);
}

static void path_in(char *buf, size_t len, const char *name) { snprintf(buf, len, "%s/%s", workdir, name); }

static void draw_photo(const char *name, synth_shape shape, double tilt_deg, int width, int height)
{
    synth_params p = synth_defaults(shape, width, height);
    p.tilt_deg = tilt_deg;
    p.textured = 1;
    p.subrows = 4; /* anti-aliased enough, and four times faster to draw */
    p.fg2[0] = 0.8f, p.fg2[1] = 0.75f, p.fg2[2] = 0.3f;
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    char path[300], err[256];
    path_in(path, sizeof path, name);
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
}

static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return n;
}

/* Lines of an OBJ file starting with the given tag ("v ", "vt ", "f "...). */
static int count_obj(const char *text, const char *tag)
{
    int n = 0;
    size_t len = strlen(tag);
    for (const char *line = text; line && *line; line = strchr(line, '\n'), line = line ? line + 1 : NULL)
        n += !strncmp(line, tag, len);
    return n;
}

/* The vertex and face counts of the profile's mesh at s segments with a base
 * cap (mesh.h): one ring per domain parameter, the base ring again with one
 * centre vertex per segment. */
/* The mesh's counts: one ring per domain boundary of the profile's shape
 * (profile_shape: the meridian when the file has one). */
static void expected_mesh(const profile_t *p, int s, int *verts, int *faces)
{
    const double *domains;
    int n;
    profile_shape(p, &domains, &n);
    *verts = n * s + 2 * s;
    *faces = 2 * s * (n - 1) + s;
}

static void check_outputs(const char *dir, const synth_params *truth, int *verts, int *faces)
{
    static const char *const names[] = {"profile.json", "texture.png", "model.obj", "model.mtl", "model.ply",
                                        "overlay.png"};
    char path[512], err[256];
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        struct stat st;
        cr_assert(stat(path, &st) == 0 && st.st_size > 0, "%s missing or empty", path);
    }
    cr_expect_eq(count_entries(dir), 6, "%s holds exactly the six outputs", dir);

    profile_t p;
    snprintf(path, sizeof path, "%s/profile.json", dir);
    cr_assert_eq(profile_read_json(path, &p, err, sizeof err), 0, "%s", err);
    cr_expect_leq(p.err_curve_to_polyline, 2.0);
    cr_expect_leq(p.err_polyline_to_curve, 2.0);
    cr_expect_gt(p.contour_points, 100);
    cr_expect_geq(p.n_domains, 2);
    cr_expect_gt(p.ms_image_processing, 0.0);
    cr_expect_gt(p.ms_mesh, 0.0);
    synth_truth t = synth_truth_of(truth);
    cr_expect(fabs(p.tilt_deg - t.tilt_deg) < 1.0, "tilt %.2f, drawn %.2f", p.tilt_deg, t.tilt_deg);
    /* The curve ends at the drawn rim height, and follows the drawn profile
     * r(h) between 10% and 90% of it (px). */
    vec2 rim = bspline_eval(&p.curve, 1.0);
    cr_expect(fabs(rim.y - t.height_px) < 3.0, "rim at h = %.1f, drawn %.1f", rim.y, t.height_px);
    enum { SAMPLES = 4000 };
    vec2 *c = malloc(SAMPLES * sizeof *c);
    cr_assert_not_null(c);
    for (int i = 0; i < SAMPLES; i++)
        c[i] = bspline_eval(&p.curve, i / (SAMPLES - 1.0));
    for (double f = 0.1; f <= 0.9; f += 0.05) {
        double h = f * t.height_px;
        int best = 0;
        for (int i = 1; i < SAMPLES; i++)
            if (fabs(c[i].y - h) < fabs(c[best].y - h))
                best = i;
        cr_expect(fabs(c[best].x - synth_radius(truth, c[best].y)) < 1.5, "at h = %.1f: r = %.2f, drawn %.2f",
                  c[best].y, c[best].x, synth_radius(truth, c[best].y));
    }
    free(c);

    expected_mesh(&p, SEGMENTS, verts, faces);
    snprintf(path, sizeof path, "%s/model.obj", dir);
    char *obj = read_all(path, NULL);
    cr_expect_eq(count_obj(obj, "v "), *verts);
    cr_expect_eq(count_obj(obj, "vt "), *verts);
    cr_expect_eq(count_obj(obj, "vn "), *verts);
    cr_expect_eq(count_obj(obj, "f "), *faces);
    cr_expect_not_null(strstr(obj, "mtllib model.mtl"));
    free(obj);
    snprintf(path, sizeof path, "%s/model.mtl", dir);
    char *mtl = read_all(path, NULL);
    cr_expect_not_null(strstr(mtl, "map_Kd texture.png"));
    free(mtl);

    /* Binary PLY: header counts, then 8 floats per vertex and 1 + 3*4 bytes per face. */
    size_t len;
    snprintf(path, sizeof path, "%s/model.ply", dir);
    char *ply = read_all(path, &len);
    int nv = -1, nf = -1;
    const char *v = strstr(ply, "element vertex "), *f = strstr(ply, "element face "), *end = strstr(ply, "end_header\n");
    cr_assert(v && f && end);
    sscanf(v, "element vertex %d", &nv);
    sscanf(f, "element face %d", &nf);
    cr_expect_eq(nv, *verts);
    cr_expect_eq(nf, *faces);
    size_t header = (size_t)(end - ply) + strlen("end_header\n");
    cr_expect_eq(len, header + (size_t)nv * 32 + (size_t)nf * 13);
    free(ply);
    profile_free(&p);
}

Test(cli_reconstruct, one_photo_gives_every_output)
{
    draw_photo("vase.png", SYNTH_VASE, 2.0, 300, 400);
    synth_params truth = synth_defaults(SYNTH_VASE, 300, 400);
    truth.tilt_deg = 2.0;
    char photo[300], out[300];
    path_in(photo, sizeof photo, "vase.png");
    path_in(out, sizeof out, "out");
    cli_result r = run_reconstruct((const char *const[]){photo, "-o", out, "--segments", "48", NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cr_expect_str_empty(r.out);
    cr_expect_not_null(strstr(r.err, "vase.png"), "a human summary on stderr");
    int verts, faces;
    check_outputs(out, &truth, &verts, &faces);
    cli_result_free(&r);
}

Test(cli_reconstruct, transparent_background_photo)
{
    synth_params p = synth_defaults(SYNTH_BOTTLE, 200, 260);
    p.rgba = 1;
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    char photo[300], out[300], err[256], path[400];
    path_in(photo, sizeof photo, "bottle.png");
    cr_assert_eq(synth_write(photo, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
    path_in(out, sizeof out, "out");
    cli_result r = run_reconstruct((const char *const[]){photo, "-o", out, "--segments", "16", "--json", NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    json_t *rep = json_loads(r.out, 0, NULL);
    cr_assert_not_null(rep);
    cr_expect_eq(json_integer_value(json_object_get(rep, "threshold")), -1, "the mask came from alpha");
    json_decref(rep);
    snprintf(path, sizeof path, "%s/texture.png", out);
    cr_expect_eq(access(path, R_OK), 0);
    cli_result_free(&r);
}

Test(cli_reconstruct, json_report_has_the_table_1_columns)
{
    draw_photo("jar.png", SYNTH_JAR, -1.0, 280, 360);
    char photo[300], out[300], path[400], err[256];
    path_in(photo, sizeof photo, "jar.png");
    path_in(out, sizeof out, "out");
    cli_result r = run_reconstruct((const char *const[]){"--json", "--segments", "48", "--side", "left", photo, "-o",
                                                         out, "--lod", "8,16", NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    json_error_t jerr;
    json_t *rep = json_loads(r.out, 0, &jerr);
    cr_assert_not_null(rep, "stdout is not JSON: %s", jerr.text);
    cr_assert(json_is_object(rep), "one photo: one object");

    profile_t p;
    snprintf(path, sizeof path, "%s/profile.json", out);
    cr_assert_eq(profile_read_json(path, &p, err, sizeof err), 0, "%s", err);
    cr_expect_str_eq(p.side, "left");
    cr_expect_str_eq(json_string_value(json_object_get(rep, "side")), "left");
    cr_expect_eq(json_integer_value(json_object_get(rep, "contour_points")), p.contour_points);
    cr_expect_eq(json_integer_value(json_object_get(rep, "control_points")), p.curve.n_ctrl);
    cr_expect_eq(json_integer_value(json_object_get(rep, "domains")), p.n_domains);
    int verts, faces;
    expected_mesh(&p, SEGMENTS, &verts, &faces);
    cr_expect_eq(json_integer_value(json_object_get(rep, "vertices")), verts);
    cr_expect_eq(json_integer_value(json_object_get(rep, "faces")), faces);
    json_t *e = json_object_get(rep, "error_px");
    cr_expect_float_eq(json_real_value(json_object_get(e, "curve_to_polyline")), p.err_curve_to_polyline, 1e-5);
    cr_expect_float_eq(json_real_value(json_object_get(e, "polyline_to_curve")), p.err_polyline_to_curve, 1e-5);
    json_t *t = json_object_get(rep, "timings_ms");
    static const char *const stages[] = {"decode", "image_processing", "bspline", "domains", "hausdorff",
                                         "camera", "texture", "mesh", "overlay", "write", "total"};
    double sum = 0;
    for (size_t i = 0; i < sizeof stages / sizeof *stages; i++) {
        json_t *v = json_object_get(t, stages[i]);
        cr_assert(json_is_real(v), "timings_ms.%s", stages[i]);
        cr_expect_geq(json_real_value(v), 0.0);
        if (i + 1 < sizeof stages / sizeof *stages)
            sum += json_real_value(v);
    }
    cr_expect_leq(sum, json_real_value(json_object_get(t, "total")) + 1e-3, "the stages fit in the total");
    /* The LODs: model_8 and model_16, counts by the same formula. */
    json_t *lods = json_object_get(rep, "lods");
    cr_assert_eq(json_array_size(lods), 2);
    for (int k = 0; k < 2; k++) {
        int s = 8 << k;
        json_t *l = json_array_get(lods, (size_t)k);
        expected_mesh(&p, s, &verts, &faces);
        cr_expect_eq(json_integer_value(json_object_get(l, "segments")), s);
        cr_expect_eq(json_integer_value(json_object_get(l, "faces")), faces);
        snprintf(path, sizeof path, "%s/model_%d.obj", out, s);
        char *obj = read_all(path, NULL);
        cr_expect_eq(count_obj(obj, "f "), faces);
        free(obj);
        snprintf(path, sizeof path, "%s/model_%d.ply", out, s);
        cr_expect_eq(access(path, R_OK), 0);
    }
    cr_expect_eq(count_entries(out), 10);
    profile_free(&p);
    json_decref(rep);
    cli_result_free(&r);
}

/* The drawn jar is a level orthographic view: its base and rim are straight
 * lines, so the camera is orthographic and says why; with --fov the focal
 * length is the one the field of view gives, and the report and
 * profile.json's camera block agree. */
Test(cli_reconstruct, the_report_says_which_camera_model)
{
    draw_photo("jar.png", SYNTH_JAR, 0.0, 280, 360);
    char photo[300], out[300], path[400], err[256];
    path_in(photo, sizeof photo, "jar.png");
    for (int k = 0; k < 2; k++) {
        path_in(out, sizeof out, k ? "fov" : "auto");
        cli_result r = k ? run_reconstruct((const char *const[]){"--json", "--fov", "20", photo, "-o", out, NULL})
                         : run_reconstruct((const char *const[]){"--json", photo, "-o", out, NULL});
        cr_assert_eq(r.status, 0, "stderr: %s", r.err);
        json_t *rep = json_loads(r.out, 0, NULL);
        cr_assert_not_null(rep);
        json_t *cam = json_object_get(rep, "camera");
        const char *model = json_string_value(json_object_get(cam, "model"));
        const char *method = json_string_value(json_object_get(cam, "method"));
        double focal = json_real_value(json_object_get(cam, "focal_px"));
        cr_assert(model && method, "camera.model and camera.method");
        profile_t p;
        snprintf(path, sizeof path, "%s/profile.json", out);
        cr_assert_eq(profile_read_json(path, &p, err, sizeof err), 0, "%s", err);
        cr_expect(p.has_camera && p.has_meridian, "profile.json has the camera and the meridian");
        cr_expect_str_eq(p.camera.method, method);
        cr_expect_float_eq(p.camera.focal_px, focal, 0.01); /* the report has 6 digits */
        if (k) {
            cr_expect_str_eq(model, "perspective");
            cr_expect_str_eq(method, "flag");
            cr_expect_float_eq(focal, 140.0 / tan(10.0 * M_PI / 180), 0.01, "f = (W/2) / tan(fov/2): %g", focal);
            cr_expect_not_null(strstr(r.err, "camera: perspective"), "stderr: %s", r.err);
        } else {
            cr_expect_str_eq(model, "orthographic");
            cr_expect_str_eq(method, "orthographic");
            cr_expect_eq(focal, 0.0);
            cr_expect_neq(json_string_value(json_object_get(cam, "note"))[0], '\0', "the fallback says why");
            cr_expect_not_null(strstr(r.err, "camera: orthographic"), "stderr: %s", r.err);
        }
        profile_free(&p);
        json_decref(rep);
        cli_result_free(&r);
    }
}

Test(cli_reconstruct, batch_gives_one_folder_per_photo)
{
    char a[300], b[300], c[300], out[300], sub[400];
    path_in(a, sizeof a, "a");
    path_in(b, sizeof b, "b");
    cr_assert_eq(mkdir(a, 0755), 0);
    cr_assert_eq(mkdir(b, 0755), 0);
    draw_photo("a/pot.png", SYNTH_VASE, 0.0, 240, 320);
    draw_photo("b/pot.png", SYNTH_BOTTLE, 1.5, 240, 320);
    draw_photo("bowl.png", SYNTH_BOWL, -2.0, 320, 240);
    path_in(a, sizeof a, "a/pot.png");
    path_in(b, sizeof b, "b/pot.png");
    path_in(c, sizeof c, "bowl.png");
    path_in(out, sizeof out, "batch");
    cli_result r = run_reconstruct((const char *const[]){"--json", "--segments", "48", a, b, c, "-o", out, NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    json_t *rep = json_loads(r.out, 0, NULL);
    cr_assert(json_is_array(rep) && json_array_size(rep) == 3, "several photos: an array, in order");
    static const char *const folders[] = {"pot", "pot-2", "bowl"};
    static const synth_shape shapes[] = {SYNTH_VASE, SYNTH_BOTTLE, SYNTH_BOWL};
    static const double tilts[] = {0.0, 1.5, -2.0};
    for (int i = 0; i < 3; i++) {
        snprintf(sub, sizeof sub, "%s/%s", out, folders[i]);
        cr_expect_str_eq(json_string_value(json_object_get(json_array_get(rep, (size_t)i), "output")), sub);
        synth_params truth = synth_defaults(shapes[i], i == 2 ? 320 : 240, i == 2 ? 240 : 320);
        truth.tilt_deg = tilts[i];
        int verts, faces;
        check_outputs(sub, &truth, &verts, &faces);
    }
    cr_expect_eq(count_entries(out), 3, "no temporary folder left");
    json_decref(rep);
    cli_result_free(&r);
}

/* Runs one bad photo into an existing empty folder: exit 2, one stderr line
 * naming the file, nothing written. */
static void expect_refused(const char *photo, const char *why)
{
    char out[300];
    path_in(out, sizeof out, "out");
    mkdir(out, 0755);
    cli_result r = run_reconstruct((const char *const[]){photo, "-o", out, NULL});
    cr_expect_eq(r.status, 2, "%s: exit %d, stderr: %s", why, r.status, r.err);
    cr_expect_eq(cli_count_lines(r.err), 1, "%s: stderr: %s", why, r.err);
    char prefix[400];
    snprintf(prefix, sizeof prefix, "celadon: %s: ", photo);
    cr_expect(!strncmp(r.err, prefix, strlen(prefix)), "%s: stderr: %s", why, r.err);
    cr_expect_eq(count_entries(out), 0, "%s: the output folder stays empty", why);
    cli_result_free(&r);
}

Test(cli_reconstruct, a_failed_run_creates_no_output_folder)
{
    char photo[300], fresh[300], parent[300];
    path_in(photo, sizeof photo, "missing.png");
    path_in(fresh, sizeof fresh, "fresh/deeper");
    path_in(parent, sizeof parent, "fresh");
    cli_result r = run_reconstruct((const char *const[]){photo, "-o", fresh, NULL});
    cr_expect_eq(r.status, 2);
    cr_expect_neq(access(parent, F_OK), 0, "the folders made for the outputs are removed again");
    cli_result_free(&r);
}

static void write_bytes(const char *name, const void *data, size_t n, char *path, size_t len)
{
    path_in(path, len, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(data, 1, n, f), n);
    fclose(f);
}

Test(cli_reconstruct, unusable_files_are_refused)
{
    char path[300];
    path_in(path, sizeof path, "missing.png");
    expect_refused(path, "missing file");
    write_bytes("empty.png", "", 0, path, sizeof path);
    expect_refused(path, "empty file");
    write_bytes("notes.png", "these are not pixels\n", 21, path, sizeof path);
    expect_refused(path, "not an image");
    path_in(path, sizeof path, "folder.png");
    cr_assert_eq(mkdir(path, 0755), 0);
    expect_refused(path, "a folder");
    expect_refused("/dev/null", "not a regular file");
    if (geteuid() != 0) { /* root reads anything */
        draw_photo("locked.png", SYNTH_JAR, 0.0, 64, 80);
        path_in(path, sizeof path, "locked.png");
        cr_assert_eq(chmod(path, 0), 0);
        expect_refused(path, "unreadable");
    }

    /* A real PNG cut in half. */
    draw_photo("whole.png", SYNTH_VASE, 0.0, 200, 260);
    char whole[300];
    path_in(whole, sizeof whole, "whole.png");
    size_t len;
    char *bytes = read_all(whole, &len);
    write_bytes("truncated.png", bytes, len / 2, path, sizeof path);
    free(bytes);
    expect_refused(path, "truncated PNG");

    /* Sizes, from headers alone: 20x20 pixels, and 20000x20000 (400 MP). */
    static const char small[] = "P6\n20 20\n255\n";
    char pix[sizeof small - 1 + 1200];
    memcpy(pix, small, sizeof small - 1);
    memset(pix + sizeof small - 1, 200, 1200);
    write_bytes("small.ppm", pix, sizeof pix, path, sizeof path);
    expect_refused(path, "too small");
    static const char big[] = "P6\n20000 20000\n255\n\1\2\3";
    write_bytes("big.ppm", big, sizeof big - 1, path, sizeof path);
    expect_refused(path, "too large");
}

Test(cli_reconstruct, photos_without_a_usable_vessel_are_refused)
{
    char path[300], err[256];
    /* Nothing but background. */
    image_t img = image_alloc(120, 160, 3);
    for (size_t i = 0; i < (size_t)120 * 160 * 3; i++)
        img.data[i] = 0.9f;
    path_in(path, sizeof path, "blank.png");
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    expect_refused(path, "no object");

    /* A bar lying at 60 degrees: no vessel stands like that. */
    for (int y = 0; y < 160; y++)
        for (int x = 0; x < 120; x++) {
            double dx = x + 0.5 - 60, dy = y + 0.5 - 80;
            double u = 0.5 * dx + 0.8660254 * dy, v = -0.8660254 * dx + 0.5 * dy;
            float c = fabs(u) < 12 && fabs(v) < 55 ? 0.2f : 0.9f;
            for (int k = 0; k < 3; k++)
                img.data[3 * ((size_t)y * 120 + x) + k] = c;
        }
    path_in(path, sizeof path, "lying.png");
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    expect_refused(path, "leans");
    image_free(&img);

    /* A vessel whose base runs off the bottom of the photo. */
    synth_params p = synth_defaults(SYNTH_VASE, 200, 260);
    p.base_center.y = 270;
    cr_assert_eq(synth_draw(&p, &img), 0);
    path_in(path, sizeof path, "cut.png");
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
    expect_refused(path, "touches the bottom image border");
}

/* A five-pointed star is no vessel: exit 2, one line that says so with the
 * measured figure, and nothing written (the classical segmenter: auto would
 * run the learned prior on the refused photo too, and refuse it again). */
Test(cli_reconstruct, a_star_is_not_a_vessel)
{
    char path[300], out[300], err[256];
    image_t img;
    cr_assert_eq(drawn_silhouette_draw(DRAWN_STAR, 200, 200, &img), 0);
    path_in(path, sizeof path, "star.png");
    cr_assert_eq(synth_write(path, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
    path_in(out, sizeof out, "star_out");
    cli_result r = run_reconstruct((const char *const[]){path, "-o", out, "--segmenter", "classic", NULL});
    cr_expect_eq(r.status, 2, "exit %d, stderr: %s", r.status, r.err);
    cr_expect_eq(cli_count_lines(r.err), 1, "stderr: %s", r.err);
    cr_expect(strstr(r.err, "not a vessel") && strstr(r.err, "% of its height"), "stderr: %s", r.err);
    struct stat st;
    cr_expect_neq(stat(out, &st), 0, "a refused photo leaves no output folder");
    cli_result_free(&r);
}

Test(cli_reconstruct, a_bad_photo_in_a_batch_spares_the_others)
{
    draw_photo("good.png", SYNTH_JAR, 0.0, 200, 260);
    char good[300], bad[300], out[300];
    path_in(good, sizeof good, "good.png");
    path_in(bad, sizeof bad, "nothing-here.jpg");
    path_in(out, sizeof out, "out");
    cli_result r = run_reconstruct((const char *const[]){bad, good, "--segments", "16", "-o", out, NULL});
    cr_expect_eq(r.status, 2);
    char line[400];
    snprintf(line, sizeof line, "celadon: %s: ", bad);
    const char *at = strstr(r.err, line);
    cr_expect_not_null(at, "stderr: %s", r.err);
    cr_expect(at && !strstr(at + 1, line), "exactly one line for the bad photo");
    cr_expect_eq(count_entries(out), 1, "only the good photo's folder");
    char sub[400];
    snprintf(sub, sizeof sub, "%s/good/profile.json", out);
    cr_expect_eq(access(sub, R_OK), 0);
    cli_result_free(&r);
}

Test(cli_reconstruct, usage_errors_exit_2)
{
    char out[300];
    path_in(out, sizeof out, "out");
    /* Each case: the arguments, then after their NULL the words of the one line. */
    static const char *const cases[][8] = {
        {"photo.png", NULL, "no output folder (-o DIR)"},
        {"-o", "x", NULL, "no photo given"},
        {"photo.png", "-o", "x", "--side", "up", NULL, "--side wants left, right or auto, not 'up'"},
        {"photo.png", "-o", "x", "--segments", "2", NULL, "--segments wants an integer 3..100000, not '2'"},
        {"photo.png", "-o", "x", "--threshold", "300", NULL, "--threshold wants an integer 0..255, not '300'"},
        {"photo.png", "-o", "x", "--frobnicate", NULL, "unknown option '--frobnicate'"},
        {"photo.png", "-o", "x", "--fov", "0", NULL, "--fov wants degrees between 1 and 150, not '0'"},
        {"photo.png", "-o", "x", "--fov", "20deg", NULL, "--fov wants degrees between 1 and 150, not '20deg'"},
        {"photo.png", "-o", "x", "--segmenter", "neural", NULL, "--segmenter wants classic, learned or auto, not 'neural'"},
        {"photo.png", "-o", "x", "--lod", "40,2", NULL, "--lod wants up to 8 comma-separated integers 3..100000"},
        {"photo.png", "-o", "x", "--smoothing", NULL, "--smoothing needs a value"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        cli_result r = run_reconstruct(cases[i]);
        const char *words = NULL;
        for (int k = 0; !words; k++)
            if (!cases[i][k])
                words = cases[i][k + 1];
        cr_expect_eq(r.status, 2, "case %zu: exit %d", i, r.status);
        cr_expect_eq(cli_count_lines(r.err), 1, "case %zu: %s", i, r.err);
        cr_expect_not_null(strstr(r.err, words), "case %zu: '%s' does not say '%s'", i, r.err, words);
        cli_result_free(&r);
    }
    cli_result r = run_reconstruct((const char *const[]){"--help", NULL});
    cr_expect_eq(r.status, 0);
    cr_expect_not_null(strstr(r.out, "usage: celadon reconstruct"));
    cli_result_free(&r);
}
