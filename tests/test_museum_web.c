/* The museum in a browser: tests/web/museum_page.mjs validates museum.glb
 * with the Khronos glTF validator, serves the folder with `celadon museum
 * --serve`, and loads index.html in headless Chromium; this test judges what
 * it reports: no validator error, no console error, every vessel loaded and
 * pickable, and a screenshot from the entrance that shows each vessel where
 * the glb's camera and nodes put it (against a screenshot without vessels).
 * Skips, saying why, when Node.js, the npm packages (make deps), Chromium or
 * the built page are missing. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/image.h"
#include "support/museum_fixture.h"
#include "support/test_build.h"

/* Two vessels: every check below needs no more. The screenshots are 320 x
 * 180 (the driver walks in a window of its own): software WebGL's cost goes
 * with the pixels (the driver took 10.7 s more CPU at 640 x 360,
 * docs/BENCHMARKS.md, "Test suite"), and the pixel bounds below are those
 * that held at 640 x 360 scaled to it (POS_TOL_PX) or are stricter at it. */
enum { N_PHOTOS = 2, SHOT_W = 320, SHOT_H = 180 };
/* three.js's projection of a vessel against ours: within a pixel of a
 * 640-wide window. */
#define POS_TOL_PX (SHOT_W / 640.0)

static char workdir[256];

static void teardown(void)
{
    museum_fixture_remove_tree(workdir);
}

TestSuite(museum_web, .fini = teardown);

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void skip_unless_tools(void)
{
    if (!getenv("CELADON_BIN"))
        cr_skip_test("CELADON_BIN is not set (run through make test)");
    if (system("command -v node >/dev/null 2>&1") != 0)
        cr_skip_test("node is not installed (make deps installs it): the page is not tested");
    if (!exists("web/node_modules/playwright-core") || !exists("web/node_modules/gltf-validator"))
        cr_skip_test("web/node_modules is missing (make deps runs npm ci): the page is not tested");
    if (!exists("/usr/bin/chromium"))
        cr_skip_test("/usr/bin/chromium is missing (make deps installs Debian's chromium): the page is not tested");
    if (!exists("build/web/museum.js"))
        cr_skip_test("build/web/museum.js is missing (make web bundles it): the page is not tested");
}

/* Runs the driver and parses the JSON line it prints; without the page, it
 * validates the glb and probes the server only. */
static json_t *drive(const char *museum, int page)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "node tests/web/museum_page.mjs '%s' '%s' '%s' %d %d %s", getenv("CELADON_BIN"), museum,
             workdir, SHOT_W, SHOT_H, page ? "page" : "server");
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    static char line[1 << 16];
    size_t n = fread(line, 1, sizeof line - 1, p);
    line[n] = 0;
    int status = pclose(p);
    cr_assert_eq(status, 0, "the driver failed (status %d): %s", status, line);
    json_error_t je;
    json_t *r = json_loads(line, 0, &je);
    cr_assert_not_null(r, "driver output is not JSON (%s): %s", je.text, line);
    return r;
}

static double mean_diff(const image_t *a, const image_t *b, double cx, double cy, int half)
{
    double sum = 0;
    int count = 0;
    for (int y = (int)cy - half; y <= (int)cy + half; y++)
        for (int x = (int)cx - half; x <= (int)cx + half; x++) {
            if (x < 0 || y < 0 || x >= a->width || y >= a->height)
                continue;
            for (int c = 0; c < 3; c++)
                sum += fabs(a->data[(y * a->width + x) * a->channels + c] - b->data[(y * b->width + x) * b->channels + c]);
            count += 3;
        }
    return count ? sum / count : 0;
}

static double luminance_stddev(const image_t *im)
{
    double s = 0, s2 = 0;
    int n = im->width * im->height;
    for (int i = 0; i < n; i++) {
        double l = 0.3 * im->data[i * im->channels] + 0.59 * im->data[i * im->channels + 1] +
                   0.11 * im->data[i * im->channels + 2];
        s += l, s2 += l * l;
    }
    return sqrt(fmax(s2 / n - (s / n) * (s / n), 0));
}

/* The mean of the linear luminance (Rec. 709) of an sRGB image. */
static double mean_linear_luminance(const image_t *im)
{
    static const double w[3] = {0.2126, 0.7152, 0.0722};
    double s = 0;
    int n = im->width * im->height;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double v = im->data[i * im->channels + c];
            s += w[c] * (v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
        }
    return s / n;
}

/* The page's entrance view and the path tracer's (preview.png, museum.xml)
 * are the same room: their mean luminances within 10% (docs/museum.md,
 * "Light"). */
static void check_same_light(const image_t *page, const char *museum)
{
    char path[600], err[256];
    image_t preview;
    snprintf(path, sizeof path, "%s/preview.png", museum);
    cr_assert_eq(image_read(path, &preview, err, sizeof err), 0, "%s", err);
    double lp = mean_linear_luminance(page), lr = mean_linear_luminance(&preview);
    cr_expect(fabs(lp / lr - 1) < 0.10, "mean luminance: page %.4f, path-traced %.4f", lp, lr);
    cr_log_info("mean linear luminance of the entrance view: page %.4f, path-traced %.4f (%+.1f%%)", lp, lr,
                100 * (lp / lr - 1));
    image_free(&preview);
}

static double num(json_t *o, const char *k) { return json_number_value(json_object_get(o, k)); }

static const char *exhibit_extra(const glb_file *g, int exhibit, const char *key)
{
    json_t *x = json_object_get(json_array_get(json_object_get(g->doc, "nodes"), (size_t)exhibit), "extras");
    return json_string_value(json_object_get(x, key));
}

/* The loading bar counted every byte of the file. */
static void check_loading(json_t *pg, const char *glb)
{
    struct stat st;
    cr_assert_eq(stat(glb, &st), 0);
    json_t *b = json_object_get(pg, "bytes");
    cr_expect_eq((long long)num(b, "loaded"), (long long)st.st_size, "bytes loaded %.0f of %lld", num(b, "loaded"),
                 (long long)st.st_size);
    cr_expect_eq((long long)num(b, "total"), (long long)st.st_size);
}

/* A pick opens the label (panel and floating plate, with the catalogue's
 * size line); the close button and a pick of nothing close both. */
static void check_label_closes(json_t *pg, const glb_file *g, int exhibit)
{
    json_t *l = json_object_get(pg, "label");
    json_t *open = json_object_get(l, "open"), *closed = json_object_get(l, "closed"),
           *nothing = json_object_get(l, "nothing");
    cr_expect_str_eq(json_string_value(json_object_get(open, "title")), exhibit_extra(g, exhibit, "title"));
    cr_expect(json_is_true(json_object_get(open, "floating")) && json_is_true(json_object_get(open, "shown")));
    cr_expect_not_null(strstr(json_string_value(json_object_get(open, "text")), exhibit_extra(g, exhibit, "size")),
                       "the panel shows the catalogue's size line");
    for (json_t *c = closed;; c = nothing) {
        cr_expect(json_is_null(json_object_get(c, "title")) && json_is_false(json_object_get(c, "floating")) &&
                      json_is_false(json_object_get(c, "shown")),
                  "the label and its floating plate close");
        if (c == nothing)
            break;
    }
}

/* Displacement (dx, dz) of the visitor between two poses, and the unit
 * vector along the floor where the first one looks. */
static void walked(json_t *a, json_t *b, double *along, double *across)
{
    double yaw = num(a, "yawDeg") * M_PI / 180, fx = -sin(yaw), fz = -cos(yaw);
    double dx = num(b, "x") - num(a, "x"), dz = num(b, "z") - num(a, "z");
    *along = dx * fx + dz * fz;
    *across = fabs(dx * fz - dz * fx);
}

#define WALK_SPEED 1.4 /* m/s, web/walk.js */

static void expect_walked_ahead(json_t *a, json_t *b, double seconds, const char *how)
{
    double along, across;
    walked(a, b, &along, &across);
    cr_expect(along > 0.05 && along <= WALK_SPEED * seconds + 1e-6 && across < 0.05 * along,
              "%s: %.3f m ahead (at most %.3f in %.2f s), %.3f m aside", how, along, WALK_SPEED * seconds, seconds,
              across);
}

/* Emulated touch: a tap names the vessel under it, a 100 px drag turns the
 * head by 100 x 0.005 rad (web/touch.js), the stick walks ahead. */
static void check_touch(json_t *pg, const glb_file *g, int exhibit)
{
    json_t *t = json_object_get(pg, "touch");
    cr_expect_str_eq(json_string_value(json_object_get(t, "tapped")), exhibit_extra(g, exhibit, "title"));
    double turn = num(json_object_get(t, "turned"), "yawDeg") - num(json_object_get(t, "before"), "yawDeg");
    cr_expect(fabs(turn + 100 * 0.005 * 180 / M_PI) < 0.1, "a drag right turns right by 28.6 deg, not %.2f", turn);
    expect_walked_ahead(json_object_get(t, "turned"), json_object_get(t, "walked"), num(t, "seconds"),
                        "the virtual stick");
}

/* Emulated WebXR thumbsticks: the left walks ahead, the right snaps 30 deg
 * once per push. */
static void check_thumbsticks(json_t *pg)
{
    json_t *x = json_object_get(pg, "xr");
    expect_walked_ahead(json_object_get(x, "before"), json_object_get(x, "walked"), num(x, "seconds"),
                        "the left thumbstick");
    double y0 = num(json_object_get(x, "walked"), "yawDeg");
    double snap = num(json_object_get(x, "snapped"), "yawDeg") - y0;
    double held = num(json_object_get(x, "held"), "yawDeg") - y0;
    double again = num(json_object_get(x, "again"), "yawDeg") - y0;
    cr_expect(fabs(snap + 30) < 1e-3 && fabs(held + 30) < 1e-3 && fabs(again + 60) < 1e-3,
              "snap turn: %.3f, held %.3f, pushed again %.3f deg (want -30, -30, -60)", snap, held, again);
    cr_expect(fabs(num(json_object_get(x, "again"), "x") - num(json_object_get(x, "walked"), "x")) < 1e-6 &&
                  fabs(num(json_object_get(x, "again"), "z") - num(json_object_get(x, "walked"), "z")) < 1e-6,
              "a snap turn turns on the spot");
}

Test(museum_web, the_page_loads_and_shows_every_vessel, .timeout = 600)
{
    skip_unless_tools();
    snprintf(workdir, sizeof workdir, "/tmp/celadon-museum-web-XXXXXX");
    cr_assert_not_null(mkdtemp(workdir));
    char photos[N_PHOTOS][512], csv[512], out[512];
    museum_fixture_photos(workdir, N_PHOTOS, photos);
    snprintf(csv, sizeof csv, "%s/catalogue.csv", workdir);
    snprintf(out, sizeof out, "%s/museum", workdir);
    /* A small, noisy preview: its mean luminance is what the page must match. */
    const char *args[] = {"--catalogue", csv, "-o", out, "--preview-spp", "4", "--preview-res", "160x90", NULL};
    cli_result r = museum_fixture_run(workdir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);

    /* The browser's work is the same whichever build of celadon serves the
     * page: the ASan+UBSan run builds the museum and probes its server, and
     * leaves the page (Chromium's software WebGL, most of the test's time)
     * to the optimised run. */
    int page = !test_build_is_sanitized();
    json_t *res = drive(out, page);
    json_t *val = json_object_get(res, "validator");
    cr_expect_eq(json_integer_value(json_object_get(val, "errors")), 0, "glTF validator: %s",
                 json_dumps(json_object_get(val, "messages"), 0));
    cr_expect_eq(json_integer_value(json_object_get(val, "warnings")), 0);
    cr_assert_null(json_object_get(res, "failure"), "%s", json_string_value(json_object_get(res, "failure")));
    cr_expect_eq(json_integer_value(json_object_get(res, "serverExit")), 0, "the server stops cleanly on SIGTERM");
    json_t *served = json_object_get(res, "server");
    static const char *const paths[] = {"/", "museum.glb", "..%2f..%2fetc%2fpasswd",
                                        "vessels%2f..%2f..%2fmuseum.json", ".hidden",
                                        "no-such-file"};
    static const int codes[] = {200, 200, 404, 404, 404, 404};
    for (int k = 0; k < 6; k++)
        cr_expect_eq(json_integer_value(json_object_get(json_object_get(served, paths[k]), "status")), codes[k],
                     "GET %s", paths[k]);
    cr_expect_str_eq(json_string_value(json_object_get(json_object_get(served, "museum.glb"), "type")),
                     "model/gltf-binary");
    if (!page) {
        cr_log_info("ASan+UBSan build: the museum and its server are tested, the page in the optimised build");
        json_decref(res);
        return;
    }
    json_t *pg = json_object_get(res, "page");
    cr_expect(json_is_null(json_object_get(pg, "error")), "page error: %s",
              json_string_value(json_object_get(pg, "error")));
    json_t *errors = json_object_get(pg, "consoleErrors");
    cr_expect_eq(json_array_size(errors), 0, "console errors: %s", json_dumps(errors, 0));
    cr_expect_eq(json_integer_value(json_object_get(pg, "vessels")), N_PHOTOS);
    long long tris = json_integer_value(json_object_get(pg, "triangles"));
    long long calls = json_integer_value(json_object_get(pg, "drawCalls"));
    cr_expect_gt(tris, 0);
    cr_expect_gt(calls, 0);
    cr_log_info("museum page: %lld triangles, %lld draw calls per frame, loaded in %lld ms", tris, calls,
                json_integer_value(json_object_get(pg, "loadMs")));

    char path[600], err[256];
    image_t with, without;
    snprintf(path, sizeof path, "%s/page.png", workdir);
    cr_assert_eq(image_read(path, &with, err, sizeof err), 0, "%s", err);
    snprintf(path, sizeof path, "%s/page-without-vessels.png", workdir);
    cr_assert_eq(image_read(path, &without, err, sizeof err), 0, "%s", err);
    cr_assert(with.width == SHOT_W && with.height == SHOT_H);
    cr_expect_gt(luminance_stddev(&with), 0.03, "the screenshot is not blank");
    check_same_light(&with, out);

    snprintf(path, sizeof path, "%s/museum.glb", out);
    glb_file g;
    glb_read(path, &g);
    int exhibit[8], vessel[8];
    cr_assert_eq(glb_exhibits(&g, exhibit, vessel, 8), N_PHOTOS);
    json_t *positions = json_object_get(pg, "positions"), *picked = json_object_get(pg, "picked");
    for (int k = 0; k < N_PHOTOS; k++) {
        json_t *x = json_object_get(json_array_get(json_object_get(g.doc, "nodes"), (size_t)exhibit[k]), "extras");
        double height_m = json_number_value(json_object_get(x, "height_cm")) / 100;
        const char *title = json_string_value(json_object_get(x, "title"));
        double px, py;
        vec3 centre = v3_add(glb_node_world_translation(&g, vessel[k]), v3(0, height_m / 2, 0));
        cr_assert_eq(glb_project(&g, centre, SHOT_W, SHOT_H, &px, &py), 0);
        /* three.js puts the vessel where our own projection of the glb does ... */
        json_t *pos = json_array_get(positions, (size_t)k);
        cr_expect(fabs(json_number_value(json_object_get(pos, "x")) - px) < POS_TOL_PX &&
                      fabs(json_number_value(json_object_get(pos, "y")) - py) < POS_TOL_PX,
                  "%s: page (%.1f, %.1f), glb (%.1f, %.1f)", title, json_number_value(json_object_get(pos, "x")),
                  json_number_value(json_object_get(pos, "y")), px, py);
        /* ... the screenshot shows it there ... */
        double d = mean_diff(&with, &without, px, py, 3);
        cr_expect_gt(d, 0.05, "%s: the screenshot changes by %.3f around (%.0f, %.0f) without it", title, d, px, py);
        /* ... standing on its pedestal at its height as drawn (each level
         * keeps its quantization offset: they once sank by half their
         * height) ... */
        json_t *hts = json_array_get(json_object_get(pg, "heights"), (size_t)k);
        double base = glb_node_world_translation(&g, vessel[k]).y;
        cr_expect(fabs(num(hts, "bottom") - base) < 0.01 && fabs(num(hts, "top") - (base + height_m)) < 0.01,
                  "%s: drawn from y %.3f to %.3f, stands from %.3f to %.3f", title, num(hts, "bottom"),
                  num(hts, "top"), base, base + height_m);
        /* ... and clicking there names it. */
        cr_expect_str_eq(json_string_value(json_array_get(picked, (size_t)k)), title);
    }
    /* Away from the vessels (the floor at the bottom corners) nothing changes. */
    cr_expect_lt(mean_diff(&with, &without, 20, SHOT_H - 20, 8), 0.01);
    check_loading(pg, path);
    check_label_closes(pg, &g, exhibit[0]);
    check_touch(pg, &g, exhibit[1]);
    check_thumbsticks(pg);
    glb_close(&g);
    image_free(&with);
    image_free(&without);
    json_decref(res);
}
