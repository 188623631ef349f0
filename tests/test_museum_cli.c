/* End to end: `celadon museum` ($CELADON_BIN) on drawn photos with known
 * profiles: museum.glb parses back with one vessel per photo whose LOD
 * vertices lie on the reconstructed B-spline surface, museum.xml renders with
 * every vessel where the glb puts it, and every kind of bad input is one
 * line, exit 2 and nothing written. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/curve_distance.h"
#include "celadon/image.h"
#include "celadon/profile.h"
#include "support/museum_fixture.h"
#include "support/shared_data.h"
#include "support/synth_vessel.h"

enum { N_PHOTOS = 3, PREVIEW_W = 160, PREVIEW_H = 90 };

static char workdir[256];
static char photos[N_PHOTOS][512];

static void setup(void)
{
    if (!getenv("CELADON_BIN"))
        cr_skip_test("CELADON_BIN is not set (run through make test)");
    snprintf(workdir, sizeof workdir, "/tmp/celadon-museum-XXXXXX");
    cr_assert_not_null(mkdtemp(workdir));
    museum_fixture_photos(workdir, N_PHOTOS, photos);
}

static void teardown(void)
{
    museum_fixture_remove_tree(workdir);
}

TestSuite(museum_cli, .init = setup, .fini = teardown);

static void in_work(char *buf, size_t len, const char *name) { snprintf(buf, len, "%s/%s", workdir, name); }

static int lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

/* Entries of the work folder whose names start with prefix. */
static int entries_starting(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        n += !strncmp(e->d_name, prefix, strlen(prefix));
    closedir(d);
    return n;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The number of exhibits in folder/museum.glb. */
static int exhibits_in(const char *folder)
{
    char path[600];
    snprintf(path, sizeof path, "%s/museum.glb", folder);
    glb_file g;
    glb_read(path, &g);
    int exhibit[8], vessel[8], n = glb_exhibits(&g, exhibit, vessel, 8);
    glb_close(&g);
    return n;
}

static cli_result build(const char *out, const char *spp)
{
    char csv[512];
    in_work(csv, sizeof csv, "catalogue.csv");
    const char *args[] = {"--catalogue", csv, "-o", out, "--title", "Test museum", "--preview-res", "160x90",
                          "--preview-spp", spp, NULL};
    return museum_fixture_run(workdir, args);
}

/* Every vertex of the level's mesh lies on the surface of revolution of the
 * profile's shape (profile_shape: the meridian when there is one) scaled to
 * height_m (or on the base disc), to the precision of its quantization. */
static void check_level_on_surface(const glb_file *g, int node, json_t *mesh, const profile_t *p, double height_m)
{
    json_t *attrs = json_object_get(json_array_get(json_object_get(mesh, "primitives"), 0), "attributes");
    int n, n_domains;
    const double *domains;
    const bspline_t *c = profile_shape(p, &domains, &n_domains);
    double step;
    double *pos = glb_positions(g, (int)json_integer_value(json_object_get(attrs, "POSITION")), node, &n, &step);
    /* The catalogue's height is the vessel's top: its highest point, which
     * a lip rolled over the rim puts above the curve's end (sampled here). */
    double shape_top = 0.0;
    for (int k = 0; k <= 100000; k++)
        shape_top = fmax(shape_top, bspline_eval(c, k / 100000.0).y);
    double scale = height_m / shape_top;
    /* Rounding each coordinate to the step moves a vertex by at most
     * sqrt(3)/2 steps (9 um on a 60 cm vessel); float math adds ~3e-8 m. */
    double tol = sqrt(3.0) / 2 * step + 1e-7;
    vec2 base = bspline_eval(c, 0.0);
    enum { SAMPLES = 400 };
    double worst = 0.0, top = 0.0;
    for (int i = 0; i < n; i++) {
        double x = pos[3 * i], y = pos[3 * i + 1], z = pos[3 * i + 2];
        vec2 q = v2(hypot(x, z) / scale, y / scale);
        top = fmax(top, y);
        if (fabs(q.y - base.y) * scale < tol && q.x <= base.x + tol / scale)
            continue; /* the base cap */
        int best = 0;
        double best_d = INFINITY;
        for (int k = 0; k <= SAMPLES; k++) {
            double d = v2_len(v2_sub(bspline_eval(c, (double)k / SAMPLES), q));
            if (d < best_d)
                best_d = d, best = k;
        }
        worst = fmax(worst, scale * curve_point_distance_near(c, q, (double)best / SAMPLES, NULL));
    }
    cr_expect_gt(step, 0, "the levels are quantized (KHR_mesh_quantization)");
    cr_expect_lt(worst, tol, "a vertex lies %.2g m off the profile's surface (step %.2g m)", worst, step);
    /* Never taller than the catalogue; lower by at most the level's sagitta
     * where the top falls between two rings (88 um on a 14 cm vessel's
     * coarsest level). */
    cr_expect(top < height_m + tol && top > height_m * (1 - 1e-3), "the top at %.6f m, the catalogue says %.6f m",
              top, height_m);
    free(pos);
}

static void check_vessel(const glb_file *g, const char *museum, int exhibit, int vessel, const char *title,
                         double height_cm)
{
    json_t *nodes = json_object_get(g->doc, "nodes");
    json_t *ex = json_array_get(nodes, (size_t)exhibit), *x = json_object_get(ex, "extras");
    char name[300];
    snprintf(name, sizeof name, "Exhibit: %s", title);
    cr_expect_str_eq(json_string_value(json_object_get(ex, "name")), name);
    cr_expect(fabs(json_number_value(json_object_get(x, "height_cm")) - height_cm) < 1e-9);
    cr_assert_geq(vessel, 0, "exhibit %s has a vessel node", title);
    char path[700], err[256];
    snprintf(path, sizeof path, "%s/%s", museum, json_string_value(json_object_get(x, "profile")));
    profile_t p;
    cr_assert_eq(profile_read_json(path, &p, err, sizeof err), 0, "%s", err);
    json_t *levels = json_object_get(json_array_get(nodes, (size_t)vessel), "children");
    cr_assert_geq(json_array_size(levels), 2, "at least two levels of detail");
    double last_distance = -1;
    int last_segments = 1 << 30;
    for (size_t k = 0; k < json_array_size(levels); k++) {
        json_t *lod = json_array_get(nodes, (size_t)json_integer_value(json_array_get(levels, k)));
        json_t *lx = json_object_get(lod, "extras");
        double d = json_number_value(json_object_get(lx, "lod_distance"));
        int s = (int)json_integer_value(json_object_get(lx, "segments"));
        cr_expect(d > last_distance && s < last_segments, "levels coarsen with distance");
        last_distance = d, last_segments = s;
        json_t *mesh = json_array_get(json_object_get(g->doc, "meshes"),
                                      (size_t)json_integer_value(json_object_get(lod, "mesh")));
        check_level_on_surface(g, (int)json_integer_value(json_array_get(levels, k)), mesh, &p, height_cm / 100.0);
    }
    profile_free(&p);
}

static const char *const titles[N_PHOTOS] = {"Vase with a flared mouth", "Wide bowl", "Bottle, \"narrow neck\""};
static const double heights[N_PHOTOS] = {32.0, 14.0, 28.0};

/* The entrance door stands on the floor in the entrance wall (+z), behind
 * the entrance camera, which stands within its width: the visitor came in
 * through it. */
static void check_door(const glb_file *g)
{
    json_t *nodes = json_object_get(g->doc, "nodes"), *door = NULL, *room = NULL;
    int camera = -1;
    for (size_t i = 0; i < json_array_size(nodes); i++) {
        json_t *n = json_array_get(nodes, i);
        const char *name = json_string_value(json_object_get(n, "name"));
        door = name && !strcmp(name, "Entrance door") ? n : door;
        camera = json_object_get(n, "camera") ? (int)i : camera;
        json_t *museum = json_object_get(json_object_get(n, "extras"), "celadon_museum");
        room = museum ? museum : room;
    }
    cr_assert(door && room && camera >= 0, "a door, the room's extras and the camera");
    size_t mesh_index = (size_t)json_integer_value(json_object_get(door, "mesh"));
    json_t *mesh = json_array_get(json_object_get(g->doc, "meshes"), mesh_index);
    json_t *prim = json_array_get(json_object_get(mesh, "primitives"), 0);
    json_t *attr = json_object_get(json_object_get(prim, "attributes"), "POSITION");
    json_t *acc = json_array_get(json_object_get(g->doc, "accessors"), (size_t)json_integer_value(attr));
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = json_number_value(json_array_get(json_object_get(acc, "min"), (size_t)k));
        hi[k] = json_number_value(json_array_get(json_object_get(acc, "max"), (size_t)k));
    }
    double half_depth = 0.5 * json_number_value(json_array_get(json_object_get(room, "room"), 1));
    vec3 eye = glb_node_world_translation(g, camera);
    cr_expect(fabs(lo[1]) < 1e-6 && hi[1] > 2.0 && hi[1] < 2.5, "on the floor, a door's height: %g to %g", lo[1],
              hi[1]);
    cr_expect(fabs(hi[2] - half_depth) < 1e-5 && hi[2] - lo[2] < 0.1, "against the entrance wall: z %g to %g", lo[2],
              hi[2]);
    cr_expect(fabs(lo[0] + hi[0]) < 1e-6 && hi[0] - lo[0] > 0.9, "centred, a door's width: x %g to %g", lo[0],
              hi[0]);
    cr_expect(eye.z < lo[2] && eye.x > lo[0] && eye.x < hi[0], "the entrance camera stands in front of it");
}

Test(museum_cli, glb_parses_back_with_every_vessel_on_its_surface)
{
    char out[512], path[600];
    in_work(out, sizeof out, "museum");
    cli_result r = build(out, "0");
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);

    snprintf(path, sizeof path, "%s/museum.glb", out);
    glb_file g;
    glb_read(path, &g);
    static const char *const ext[] = {"KHR_materials_clearcoat", "KHR_materials_transmission", "KHR_materials_ior",
                                      "KHR_lights_punctual", "KHR_mesh_quantization"};
    json_t *used = json_object_get(g.doc, "extensionsUsed");
    for (int k = 0; k < 5; k++) {
        int found = 0;
        for (size_t i = 0; i < json_array_size(used); i++)
            found |= !strcmp(json_string_value(json_array_get(used, i)), ext[k]);
        cr_expect(found, "%s declared", ext[k]);
    }
    /* Textures are embedded images: the room's six lightmaps, then per
     * exhibit its pedestal's lightmap and its vessel's texture as JPEG, its
     * label and its title sign as PNG (sharp text), each what its mimeType
     * says. */
    json_t *images = json_object_get(g.doc, "images");
    cr_expect_eq(json_array_size(images), 6 + 4 * N_PHOTOS);
    for (size_t i = 0; i < json_array_size(images); i++) {
        json_t *im = json_array_get(images, i);
        const char *name = json_string_value(json_object_get(im, "name"));
        int jpeg = strncmp(name, "Label: ", 7) != 0 && strncmp(name, "Sign: ", 6) != 0;
        cr_expect_eq(jpeg, i < 6 || (i - 6) % 4 < 2, "image %zu is %s", i, name);
        cr_expect_str_eq(json_string_value(json_object_get(im, "mimeType")), jpeg ? "image/jpeg" : "image/png");
        json_t *v = json_array_get(json_object_get(g.doc, "bufferViews"),
                                   (size_t)json_integer_value(json_object_get(im, "bufferView")));
        size_t off = (size_t)json_integer_value(json_object_get(v, "byteOffset"));
        cr_expect(!memcmp(g.bin + off, jpeg ? "\xff\xd8\xff" : "\x89PNG\r\n\x1a\n", jpeg ? 3 : 8), "image %zu's signature", i);
    }
    check_door(&g);
    int exhibit[8], vessel[8];
    cr_assert_eq(glb_exhibits(&g, exhibit, vessel, 8), N_PHOTOS, "one exhibit per photo");
    for (int k = 0; k < N_PHOTOS; k++)
        check_vessel(&g, out, exhibit[k], vessel[k], titles[k], heights[k]);
    glb_close(&g);

    /* The manifest lists exactly the files of the folder; a second run replaces the museum. */
    snprintf(path, sizeof path, "%s/museum.json", out);
    json_t *m = json_load_file(path, 0, NULL);
    cr_assert_not_null(m);
    json_t *files = json_object_get(m, "files");
    for (size_t i = 0; i < json_array_size(files); i++) {
        snprintf(path, sizeof path, "%s/%s", out, json_string_value(json_array_get(files, i)));
        cr_expect(exists(path), "%s listed and present", path);
    }
    json_decref(m);
    r = build(out, "0");
    cr_expect_eq(r.status, 0, "rebuilding over a museum: %s", r.err);
    cli_result_free(&r);
    cr_expect_eq(entries_starting(workdir, ".celadon"), 0, "no temporary folder left behind");
}

/* museum.xml without its `sor` shapes: the same museum without vessels. */
static void write_without_vessels(const char *xml, const char *out)
{
    FILE *f = fopen(xml, "rb");
    cr_assert_not_null(f);
    static char text[1 << 20], kept[1 << 20];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    char *dst = kept;
    for (const char *p = text; *p;) {
        const char *s = strstr(p, "<shape type=\"sor\"");
        if (!s) {
            dst += sprintf(dst, "%s", p);
            break;
        }
        memcpy(dst, p, (size_t)(s - p));
        dst += s - p;
        const char *e = strstr(s, "</shape>");
        cr_assert_not_null(e);
        p = e + strlen("</shape>");
    }
    f = fopen(out, "wb");
    cr_assert_not_null(f);
    fputs(kept, f);
    fclose(f);
}

static double pixel_diff(const image_t *a, const image_t *b, int x, int y)
{
    double d = 0;
    for (int c = 0; c < 3; c++)
        d += fabs(a->data[(y * a->width + x) * a->channels + c] - b->data[(y * b->width + x) * b->channels + c]);
    return d / 3;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Each vessel changes the path-traced image around the pixel the glb's
 * camera and node put it at, much more than the image changes elsewhere. */
Test(museum_cli, preview_shows_each_vessel_where_the_glb_puts_it)
{
    char out[512], path[600], empty_xml[600], empty_png[600], err[256];
    in_work(out, sizeof out, "museum");
    cli_result r = build(out, "4");
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/museum.xml", out);
    snprintf(empty_xml, sizeof empty_xml, "%s/empty.xml", workdir);
    snprintf(empty_png, sizeof empty_png, "%s/empty.png", workdir);
    /* Beside museum.xml, so its file names resolve the same way. */
    char beside[600];
    snprintf(beside, sizeof beside, "%s/empty.xml", out);
    write_without_vessels(path, beside);
    const char *args[] = {"render", beside, "-o", empty_png, "--spp", "4", NULL};
    r = cli_run(workdir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);
    remove(beside);

    image_t with, without;
    snprintf(path, sizeof path, "%s/preview.png", out);
    cr_assert_eq(image_read(path, &with, err, sizeof err), 0, "%s", err);
    cr_assert_eq(image_read(empty_png, &without, err, sizeof err), 0, "%s", err);
    cr_assert(with.width == PREVIEW_W && with.height == PREVIEW_H && without.width == PREVIEW_W);
    static double all[PREVIEW_W * PREVIEW_H];
    for (int i = 0; i < PREVIEW_W * PREVIEW_H; i++)
        all[i] = pixel_diff(&with, &without, i % PREVIEW_W, i / PREVIEW_W);
    qsort(all, PREVIEW_W * PREVIEW_H, sizeof *all, by_value);
    double median = all[PREVIEW_W * PREVIEW_H / 2];

    snprintf(path, sizeof path, "%s/museum.glb", out);
    glb_file g;
    glb_read(path, &g);
    int exhibit[8], vessel[8];
    cr_assert_eq(glb_exhibits(&g, exhibit, vessel, 8), N_PHOTOS);
    for (int k = 0; k < N_PHOTOS; k++) {
        vec3 base = glb_node_world_translation(&g, vessel[k]);
        double px, py;
        cr_assert_eq(glb_project(&g, v3_add(base, v3(0, heights[k] / 200.0, 0)), PREVIEW_W, PREVIEW_H, &px, &py), 0);
        double sum = 0;
        int count = 0;
        for (int y = (int)py - 2; y <= (int)py + 2; y++)
            for (int x = (int)px - 2; x <= (int)px + 2; x++)
                if (x >= 0 && y >= 0 && x < PREVIEW_W && y < PREVIEW_H)
                    sum += pixel_diff(&with, &without, x, y), count++;
        cr_assert_gt(count, 0, "vessel %d projects into the image (%.1f, %.1f)", k, px, py);
        cr_expect_gt(sum / count, 4 * median + 0.03, "vessel %d at (%.1f, %.1f): difference %.3f, median %.3f", k,
                     px, py, sum / count, median);
    }
    glb_close(&g);
    image_free(&with);
    image_free(&without);
}

/* A bad input: exit 2, exactly one line naming the problem, and the output
 * folder not created. */
static void expect_refused(const char *const *args, const char *out, const char *needle)
{
    cli_result r = museum_fixture_run(workdir, args);
    cr_expect_eq(r.status, 2, "exit %d, stderr: %s", r.status, r.err);
    cr_expect_eq(lines(r.err), 1, "one line: %s", r.err);
    cr_expect_not_null(strstr(r.err, needle), "'%s' in: %s", needle, r.err);
    if (out)
        cr_expect(!exists(out), "%s not created", out);
    cr_expect_eq(entries_starting(workdir, ".celadon"), 0, "no temporary folder left behind");
    cli_result_free(&r);
}

static void write_text(const char *name, const char *text)
{
    char path[600];
    in_work(path, sizeof path, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs(text, f);
    fclose(f);
}

Test(museum_cli, bad_inputs_are_one_line_exit_2_and_nothing_written)
{
    char out[512], csv[512];
    in_work(out, sizeof out, "out");

    write_text("missing.csv", "file,title\nvessel-0.png,Vase\nno-such-photo.png,Ghost\n");
    in_work(csv, sizeof csv, "missing.csv");
    const char *a1[] = {"--catalogue", csv, "-o", out, NULL};
    expect_refused(a1, out, "no-such-photo.png' not found");

    write_text("malformed.csv", "file,title\nvessel-0.png,\"Vase with an open quote\nvessel-1.png,Bowl\n");
    in_work(csv, sizeof csv, "malformed.csv");
    const char *a2[] = {"--catalogue", csv, "-o", out, NULL};
    expect_refused(a2, out, "malformed CSV");

    write_text("columns.csv", "file,title,colour\nvessel-0.png,Vase,green\n");
    in_work(csv, sizeof csv, "columns.csv");
    const char *a3[] = {"--catalogue", csv, "-o", out, NULL};
    expect_refused(a3, out, "unknown column 'colour'");

    /* A folder with someone else's file is left exactly as it was. */
    char stray[600];
    cr_assert_eq(mkdir(out, 0777), 0);
    snprintf(stray, sizeof stray, "%s/notes.txt", out);
    FILE *f = fopen(stray, "w");
    fputs("mine\n", f);
    fclose(f);
    const char *a4[] = {photos[0], "-o", out, NULL};
    expect_refused(a4, NULL, "is not a museum");
    cr_expect_eq(entries_starting(out, ""), 3, "only ., .. and notes.txt");
    remove(stray);
    rmdir(out);

    /* Every photo refused: one line for the photo, no museum. */
    write_text("not-a-photo.png", "this is text\n");
    char bad[512];
    in_work(bad, sizeof bad, "not-a-photo.png");
    const char *a5[] = {bad, "-o", out, NULL};
    expect_refused(a5, out, "not-a-photo.png");
}

Test(museum_cli, a_refused_photo_is_left_out_and_the_rest_make_the_museum)
{
    char out[512], bad[512];
    in_work(out, sizeof out, "museum");
    write_text("blank.png", "");
    in_work(bad, sizeof bad, "blank.png");
    const char *args[] = {photos[1], bad, "-o", out, "--preview-spp", "0", NULL};
    cli_result r = museum_fixture_run(workdir, args);
    cr_expect_eq(r.status, 2, "a refused photo makes the exit code 2");
    cr_expect_not_null(strstr(r.err, "blank.png"), "%s", r.err);
    cli_result_free(&r);
    cr_expect_eq(exhibits_in(out), 1);
}

/* The synth-dev catalogue photographs (../shared) make a museum too. */
Test(museum_cli, synth_dev_photos)
{
    char a[600], b[600], out[512];
    shared_data_path(a, sizeof a, "data/synth-dev/pear_bottle_e3/photo.png");
    shared_data_path(b, sizeof b, "data/synth-dev/squat_jar_crane/photo.png");
    shared_data_require(a);
    shared_data_require(b);
    in_work(out, sizeof out, "synth");
    const char *args[] = {a, b, "-o", out, "--preview-spp", "0", NULL};
    cli_result r = museum_fixture_run(workdir, args);
    cr_expect_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);
    cr_expect_eq(exhibits_in(out), 2);
}

/* A photo whose vessel runs off the top of the image fails the quality
 * gate: refused without --force, with it in the museum and marked so; with
 * no catalogue its label states no height, its folder keeps the title's
 * accents. */
Test(museum_cli, force_includes_a_vessel_below_the_gate_and_says_so)
{
    synth_params p = synth_defaults(SYNTH_JAR, 240, 320);
    p.base_center.y = p.height_px - 4; /* the rim 4 px above the image */
    image_t img;
    char cut[512], err[256], out[512];
    cr_assert_eq(synth_draw(&p, &img), 0);
    in_work(cut, sizeof cut, "Vase des âges.png");
    cr_assert_eq(synth_write(cut, &img, 8, err, sizeof err), 0, "%s", err);
    image_free(&img);
    in_work(out, sizeof out, "forced");
    /* The learned prior would retry the cut photo (seconds of a network);
     * what is tested here is the gate's verdict, which is the classical one. */
    setenv("CELADON_PRIOR_MODEL", "/nonexistent/celadon-test-no-prior.onnx", 1);
    const char *refused[] = {photos[1], cut, "-o", out, "--preview-spp", "0", NULL};
    cli_result r = museum_fixture_run(workdir, refused);
    cr_expect_eq(r.status, 2, "without --force the photo is refused: %s", r.err);
    cr_expect_not_null(strstr(r.err, "touches the top image border"), "%s", r.err);
    cli_result_free(&r);

    const char *forced[] = {photos[1], cut, "-o", out, "--preview-spp", "0", "--force", NULL};
    r = museum_fixture_run(workdir, forced);
    cr_expect_eq(r.status, 0, "%s", r.err);
    cr_expect_not_null(strstr(r.err, "warning: "), "a warning names the forced photo: %s", r.err);
    cli_result_free(&r);
    char path[700];
    snprintf(path, sizeof path, "%s/museum.glb", out);
    glb_file g;
    glb_read(path, &g);
    int exhibit[8], vessel[8];
    cr_assert_eq(glb_exhibits(&g, exhibit, vessel, 8), 2);
    json_t *x = json_object_get(json_array_get(json_object_get(g.doc, "nodes"), (size_t)exhibit[1]), "extras");
    cr_expect_str_eq(json_string_value(json_object_get(x, "title")), "Vase des âges");
    cr_expect_str_eq(json_string_value(json_object_get(x, "size")), "Height not recorded");
    cr_expect_str_eq(json_string_value(json_object_get(x, "size_from")), "default (not recorded)");
    cr_expect_not_null(json_object_get(x, "note"), "the label says the shape is below the gate");
    cr_expect_str_eq(json_string_value(json_object_get(x, "profile")), "vessels/vase-des-âges/profile.json");
    glb_close(&g);
    snprintf(path, sizeof path, "%s/labels/vase-des-âges.png", out);
    cr_expect(exists(path), "%s", path);
    snprintf(path, sizeof path, "%s/museum.json", out);
    json_t *m = json_load_file(path, 0, NULL);
    cr_assert_not_null(m);
    json_t *v = json_object_get(m, "vessels");
    cr_expect(json_is_true(json_object_get(json_array_get(v, 0), "quality_gate_passed")));
    cr_expect(json_is_false(json_object_get(json_array_get(v, 1), "quality_gate_passed")));
    json_decref(m);
    unsetenv("CELADON_PRIOR_MODEL");
}
