/* What `celadon render` writes (issue 28): the metadata every format
 * carries, as `oiiotool --info -v` shows it; an interrupted render's
 * header and per-pixel sample counts; the formats and view transforms. */
#include <criterion/criterion.h>
#include <math.h>
#include <openexr.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "celadon/film.h"
#include "celadon/image.h"
#include "support/cli_run.h"
#include "support/exr_planes.h"
#include "support/scratch_dir.h"

static char dir[64];

static void open_dir(void) { scratch_dir_make(dir, sizeof dir, "outputs"); }
static void close_dir(void) { scratch_dir_remove(dir); }

TestSuite(render_outputs, .init = open_dir, .fini = close_dir);

/* A white diffuse sphere under a white sky: every sample is 1 wherever it
 * lands (the furnace), through a box filter, so a pixel is black exactly
 * when it has no sample. */
static const char sphere_xml[] =
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
    "<lookat origin=\"0,0,4\" target=\"0,0,0\" up=\"0,1,0\"/></transform>"
    "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>"
    "<film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"16\"/>"
    "<rfilter type=\"box\"/></film></sensor>"
    "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1,1,1\"/></emitter>"
    "<shape type=\"sphere\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1,1,1\"/></bsdf></shape>"
    "</scene>\n";

static void write_scene(char *path, size_t len) { scratch_write_file(dir, "scene.xml", sphere_xml, path, len); }

static void render_ok(const char *const *args)
{
    cli_result r = cli_run(dir, args);
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);
}

/* What `oiiotool --info -v path` prints (malloc'd). */
static char *oiio_info(const char *path)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "oiiotool --info -v '%s' 2>&1", path);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    size_t cap = 1 << 16, n = 0;
    char *text = malloc(cap);
    cr_assert_not_null(text);
    n = fread(text, 1, cap - 1, p);
    text[n] = '\0';
    cr_assert_eq(pclose(p), 0, "oiiotool (Debian's openimageio-tools, `make deps`) failed: %s", text);
    return text;
}

/* Every format carries what made it: the EXR as header attributes, PNG as
 * text chunks, JPEG in its comment; oiiotool shows them all. */
Test(render_outputs, every_format_says_what_made_it, .timeout = 120)
{
    char scene[128], out[160];
    write_scene(scene, sizeof scene);
    static const char *const exts[] = {"exr", "png", "jpg", "tif", "hdr"};
    static const char *const keys[] = {"celadon/version",      "celadon/scene",     "celadon/sceneDigest",
                                       "celadon/commandLine",  "celadon/seed",      "celadon/sampler",
                                       "celadon/integrator",   "celadon/sppRequested", "celadon/sppDone",
                                       "celadon/passes",       "celadon/renderSeconds", "celadon/interrupted",
                                       "celadon/threads",      "celadon/ranks"};
    for (size_t e = 0; e < sizeof exts / sizeof exts[0]; e++) {
        snprintf(out, sizeof out, "%s/out.%s", dir, exts[e]);
        render_ok((const char *[]){"render", scene, "-o", out, "--seed", "77", "--threads", "2", NULL});
        char *info = oiio_info(out);
        if (strcmp(exts[e], "hdr") == 0) { /* Radiance's header has no room for them */
            free(info);
            continue;
        }
        for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
            cr_expect_not_null(strstr(info, keys[k]), "%s: no %s in\n%s", exts[e], keys[k], info);
        cr_expect_not_null(strstr(info, "77"), "%s: the seed", exts[e]);
        cr_expect_not_null(strstr(info, "--seed 77"), "%s: the command line", exts[e]);
        cr_expect_not_null(strstr(info, "independent"), "%s: the sampler", exts[e]);
        if (!strcmp(exts[e], "exr")) {
            cr_expect_not_null(strstr(info, "celadon/sppDone: \"4\""), "%s", info);
            cr_expect_not_null(strstr(info, "celadon/interrupted: \"no\""), "%s", info);
            cr_expect_not_null(strstr(info, "DateTime: \""), "the standard capDate (OpenImageIO: DateTime): %s", info);
            cr_expect_not_null(strstr(info, "channel list: R, G, B\n"), "an uninterrupted render has no spp "
                                                                         "channel: %s", info);
        }
        free(info);
    }
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Runs celadon ARGS (output thrown away), sends sig after delay seconds
 * once it handles sig; the wait status. */
static int run_interrupted(const char *const *args, double delay, int sig)
{
    pid_t pid = cli_start_quiet(args);
    cr_assert(cli_wait_for_handler(pid, sig, 60.0), "no handler for signal %d", sig);
    return cli_signal_after(pid, delay, sig);
}

/* The string attribute of the EXR header (into out; "" when missing). */
static void header_string(const char *path, const char *name, char *out, size_t len)
{
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS, "%s", path);
    const char *s = NULL;
    int32_t n = 0;
    out[0] = '\0';
    if (exr_attr_get_string(ctx, 0, name, &n, &s) == EXR_ERR_SUCCESS)
        snprintf(out, len, "%.*s", (int)n, s);
    exr_finish(&ctx);
}

/* SIGINT and SIGHUP finish the pass (every pixel the same count, a whole
 * number of passes), SIGTERM stops at once (an spp channel where the
 * counts differ); each writes the image labelled interrupted and exits
 * 128 + the signal. The truth of the spp channel: under the furnace with a
 * box filter a pixel is black exactly when it got no sample. */
Test(render_outputs, an_interrupted_render_says_so_pixel_by_pixel, .timeout = 300)
{
    char scene[128], out[160], spp[16];
    write_scene(scene, sizeof scene);
    snprintf(out, sizeof out, "%s/cut.exr", dir);
    snprintf(spp, sizeof spp, "%d", 4096);
    const char *args[] = {"render", scene, "-o", out, "--spp", spp, "--res", "48x32", "--threads", "2", NULL};
    static const int sigs[] = {SIGINT, SIGHUP, SIGTERM};
    int cut_short = 0;
    for (int k = 0; k < 3; k++) {
        unlink(out);
        double t0 = now();
        int status = run_interrupted(args, 0.5, sigs[k]);
        cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 128 + sigs[k], "signal %d: status %#x (%.1f s)",
                  sigs[k], status, now() - t0);
        exr_planes e;
        read_exr(out, &e);
        char interrupted[8], done[32];
        header_string(out, "celadon/interrupted", interrupted, sizeof interrupted);
        header_string(out, "celadon/sppDone", done, sizeof done);
        int least = -1, most = -1;
        cr_assert(sscanf(done, "%d-%d", &least, &most) >= 1, "sppDone '%s'", done);
        most = most < 0 ? least : most;
        cr_expect_eq(!strcmp(interrupted, "yes"), most < 4096, "interrupted %s with sppDone %s", interrupted, done);
        if (sigs[k] != SIGTERM) {
            cr_expect_eq(least, most, "signal %d stopped inside a pass: %s", sigs[k], done);
            cr_expect_eq(least % 64, 0, "not a whole number of passes of 64: %s", done);
            cr_expect(!exr_planes_has(&e, "spp.X"));
        }
        if (exr_planes_has(&e, "spp.X")) {
            int s = plane_index(&e, "spp.X"), r = plane_index(&e, "R");
            float lo = 1e30f, hi = -1.0f;
            for (int p = 0; p < e.width * e.height; p++) {
                float n = e.planes[s][p];
                lo = fminf(lo, n), hi = fmaxf(hi, n);
                cr_assert_eq(n, floorf(n));
                cr_assert_eq(n > 0, e.planes[r][p] > 0, "pixel %d: %g samples, R %g", p, n, e.planes[r][p]);
            }
            cr_expect(lo == least && hi == most, "the channel's %g-%g, the header's %s", lo, hi, done);
            cut_short += lo < hi;
        }
        exr_planes_free(&e);
    }
    cr_log_info("SIGTERM stopped inside a pass: %d", cut_short);
}

/* A film whose pixel i holds the value v(i) = 2^(i/8 - 12) in R, half of
 * it in G, a tenth in B: 2^-12 to about 2^6, across every view's range. */
enum { RAMP_W = 16, RAMP_H = 9 };
static double ramp_value(int i) { return exp2(i / 8.0 - 12.0); }
static void ramp_film(film_t *f)
{
    char err[256];
    cr_assert_eq(film_init(f, RAMP_W, RAMP_H, NULL, 0, err, sizeof err), 0, "%s", err);
    for (int i = 0; i < RAMP_W * RAMP_H; i++) {
        double v = ramp_value(i), rgb[3] = {v, 0.5 * v, 0.1 * v};
        film_add(f, i % RAMP_W, i / RAMP_W, rgb, 1.0);
    }
}

/* Writes the ramp as name with the options and reads it back. */
static image_t write_and_read(const film_t *f, const char *name, film_output o)
{
    char path[160], err[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    cr_assert_eq(film_write_as(f, path, &o, err, sizeof err), 0, "%s", err);
    image_t img;
    cr_assert_eq(image_read(path, &img, err, sizeof err), 0, "%s: %s", name, err);
    cr_assert(img.width == RAMP_W && img.height == RAMP_H && img.channels == 3, "%s: %dx%dx%d", name, img.width,
              img.height, img.channels);
    return img;
}

/* Float TIFF is bit-exact, Radiance HDR within its shared 8-bit mantissa,
 * 16-bit PNG and TIFF within half a code of the sRGB curve (and they are
 * 16-bit: finer than 8-bit codes), 8-bit PNG the film's sRGB bytes. */
Test(render_outputs, formats_round_trip)
{
    film_t f;
    ramp_film(&f);
    film_output plain = {0.0, FILM_VIEW_STANDARD, 0}, deep = {0.0, FILM_VIEW_STANDARD, 16};
    image_t tif = write_and_read(&f, "ramp.tif", plain), hdr = write_and_read(&f, "ramp.hdr", plain);
    image_t png16 = write_and_read(&f, "ramp16.png", deep), tif16 = write_and_read(&f, "ramp16.tif", deep);
    image_t png8 = write_and_read(&f, "ramp8.png", plain);
    cr_expect_eq(tif.bits, 32);
    cr_expect_eq(png16.bits, 16);
    cr_expect_eq(tif16.bits, 16);
    int finer = 0;
    for (int i = 0; i < RAMP_W * RAMP_H; i++) {
        double v[3] = {ramp_value(i), 0.5 * ramp_value(i), 0.1 * ramp_value(i)};
        for (int c = 0; c < 3; c++) {
            size_t k = (size_t)i * 3 + c;
            cr_assert_eq(tif.data[k], (float)v[c], "tif pixel %d", i);
            cr_assert(fabs(hdr.data[k] - v[c]) <= v[0] / 128.0, "hdr pixel %d: %g for %g", i, hdr.data[k], v[c]);
            double code = film_view_encode(FILM_VIEW_STANDARD, v[c]);
            cr_assert(fabs(png16.data[k] - code) <= 0.5 / 65535 + 1e-7, "png16 pixel %d: %g for %g", i,
                      png16.data[k], code);
            cr_assert(fabs(tif16.data[k] - code) <= 0.5 / 65535 + 1e-7, "tif16 pixel %d", i);
            cr_assert_eq(lrintf(png8.data[k] * 255.0f), film_srgb8(v[c]), "png8 pixel %d", i);
            finer += fabs(png16.data[k] * 255.0 - lrint(png16.data[k] * 255.0)) > 0.01;
        }
    }
    cr_expect_gt(finer, 100, "the 16-bit codes are 8-bit ones in disguise");
    image_free(&tif), image_free(&hdr), image_free(&png16), image_free(&tif16), image_free(&png8);
    film_free(&f);
}

/* --exposure S is the same image with the light times 2^S; the filmic
 * view is monotone, puts middle grey near the middle, black at 0, reaches
 * 1 only 6.5 stops above middle grey (where standard clips at 1.0), and
 * keeps highlights apart that standard clips to one value. */
Test(render_outputs, exposure_and_views)
{
    film_t f;
    ramp_film(&f);
    image_t up = write_and_read(&f, "up.png", (film_output){1.0, FILM_VIEW_STANDARD, 0});
    image_t filmic = write_and_read(&f, "filmic.png", (film_output){0.0, FILM_VIEW_FILMIC, 16});
    for (int i = 0; i < RAMP_W * RAMP_H; i++)
        cr_assert_eq(lrintf(up.data[i * 3] * 255.0f), film_srgb8(2.0 * ramp_value(i)), "pixel %d", i);
    for (int i = 1; i < RAMP_W * RAMP_H; i++)
        cr_assert_geq(filmic.data[i * 3], filmic.data[(i - 1) * 3], "filmic is not monotone at %d", i);
    double grey = film_view_encode(FILM_VIEW_FILMIC, 0.18);
    cr_expect(grey > 0.4 && grey < 0.6, "middle grey at %g", grey);
    cr_expect_lt(film_view_encode(FILM_VIEW_FILMIC, 1e-9), 1e-3);
    cr_expect_lt(film_view_encode(FILM_VIEW_FILMIC, 1.0), 0.95, "filmic clips at 1.0");
    cr_expect_gt(film_view_encode(FILM_VIEW_FILMIC, 0.18 * exp2(6.5)), 0.999);
    cr_expect_gt(film_view_encode(FILM_VIEW_FILMIC, 4.0), film_view_encode(FILM_VIEW_FILMIC, 2.0) + 0.01);
    cr_expect_eq(film_view_encode(FILM_VIEW_STANDARD, 4.0), film_view_encode(FILM_VIEW_STANDARD, 2.0));
    image_free(&up), image_free(&filmic);
    film_free(&f);
}

/* A floor under a white sky with a sphere resting on it, seen from above:
 * each sample's value varies (bounded: no heavy tail) with whether its
 * directions toward the sky are blocked by the sphere. */
static const char lit_floor_xml[] =
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
    "<lookat origin=\"0,3,0.01\" target=\"0,0,0\" up=\"0,0,1\"/></transform>"
    "<float name=\"fov\" value=\"60\"/>"
    "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"16\"/></sampler>"
    "<film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"24\"/>"
    "<rfilter type=\"box\"/></film></sensor>"
    "<integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>"
    "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1,1,1\"/></emitter>"
    "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/>"
    "</transform><bsdf type=\"diffuse\"/></shape>"
    "<shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0.5\" z=\"0\"/><float name=\"radius\" value=\"0.5\"/>"
    "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2,0.6,0.3\"/></bsdf></shape>"
    "</scene>\n";

/* The variance channel is the variance of the pixel's estimate: over
 * renders with other seeds, the pixels' luminance varies by what the
 * channel says on average (the ratio within 15%; its statistical spread
 * over 16 seeds and 576 pixels is a few percent), and not by the variance
 * of single samples, 16 times as much. */
Test(render_outputs, variance_is_that_of_the_estimate, .timeout = 240)
{
    enum { SEEDS = 16, NPIX = 24 * 24 };
    char scene[128], out[160], seed[16];
    scratch_write_file(dir, "floor.xml", lit_floor_xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/floor.exr", dir);
    static double sum[NPIX], sum2[NPIX], reported[NPIX];
    for (int k = 0; k < SEEDS; k++) {
        snprintf(seed, sizeof seed, "%d", 1000 + k);
        render_ok((const char *[]){"render", scene, "-o", out, "--seed", seed, "--aov", "variance,spp", "--threads",
                                   "2", NULL});
        exr_planes e;
        read_exr(out, &e);
        int r = plane_index(&e, "R"), g = plane_index(&e, "G"), b = plane_index(&e, "B");
        int v = plane_index(&e, "variance.X"), n = plane_index(&e, "spp.X");
        for (int p = 0; p < NPIX; p++) {
            double y = 0.212671 * e.planes[r][p] + 0.715160 * e.planes[g][p] + 0.072169 * e.planes[b][p];
            sum[p] += y, sum2[p] += y * y, reported[p] += e.planes[v][p] / SEEDS;
            cr_assert_eq(e.planes[n][p], 16.0f);
        }
        exr_planes_free(&e);
    }
    double seen = 0.0, said = 0.0;
    for (int p = 0; p < NPIX; p++) {
        seen += (sum2[p] - sum[p] * sum[p] / SEEDS) / (SEEDS - 1);
        said += reported[p];
    }
    cr_log_info("variance across seeds %.4g, the channel's mean %.4g (ratio %.3f)", seen, said, seen / said);
    cr_assert_gt(said, 0.0);
    cr_expect(fabs(seen / said - 1.0) < 0.15, "across seeds %g, the channel says %g", seen, said);
}

/* The scene xml rendered with --aov aovs (its own sampler and size), read
 * into e. */
static void render_aovs(const char *xml, const char *aovs, exr_planes *e)
{
    char scene[128], out[160];
    scratch_write_file(dir, "aovs.xml", xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/aovs.exr", dir);
    render_ok((const char *[]){"render", scene, "-o", out, "--aov", aovs, NULL});
    read_exr(out, e);
}

/* The index AOVs are never averaged: each pixel holds one shape's number
 * (the floor is 1, the sphere 2) and one material's. */
Test(render_outputs, index_aovs_hold_whole_numbers, .timeout = 60)
{
    exr_planes e;
    render_aovs(lit_floor_xml, "index,Z,N,albedo", &e);
    int ob = plane_index(&e, "IndexOB.X"), ma = plane_index(&e, "IndexMA.X");
    (void)plane_index(&e, "Z"), (void)plane_index(&e, "N.X"), (void)plane_index(&e, "albedo.R");
    int seen[3] = {0, 0, 0};
    for (int p = 0; p < e.width * e.height; p++) {
        float o = e.planes[ob][p], m = e.planes[ma][p];
        cr_assert(o == 1.0f || o == 2.0f, "pixel %d: object %g", p, o);
        cr_assert_eq(m, o, "pixel %d: each shape has its own BSDF, so its own material", p);
        seen[(int)o]++;
    }
    cr_expect(seen[1] > 0 && seen[2] > 0, "floor %d, sphere %d pixels", seen[1], seen[2]);
    exr_planes_free(&e);
}

/* The sphere scene with the given film (width, height, filter, crop). */
static void write_film_scene(const char *name, const char *film, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f,
            "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
            "<lookat origin=\"0.3,0.2,4\" target=\"0,0,0\" up=\"0,1,0\"/></transform>"
            "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>"
            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"30\"/>"
            "%s</film></sensor>"
            "<emitter type=\"point\"><point name=\"position\" x=\"2\" y=\"3\" z=\"3\"/>"
            "<rgb name=\"intensity\" value=\"20,20,20\"/></emitter>"
            "<shape type=\"sphere\"><bsdf type=\"roughplastic\"/></shape></scene>\n",
            film);
    fclose(f);
}

/* Pixel (x, y) of the crop is pixel (x + X, y + Y) of the full render with
 * the same seed: the same sample streams, through a box filter bit for bit,
 * through a Gaussian (samples from outside the window reach in) within
 * float rounding; hdrfilm's crop_* parameters and --crop agree. */
Test(render_outputs, a_crop_is_the_window_of_the_full_render, .timeout = 120)
{
    static const struct {
        const char *filter;
        double tol;
    } filters[] = {{"<rfilter type=\"box\"/>", 0.0}, {"<rfilter type=\"gaussian\"/>", 1e-5}};
    enum { X = 13, Y = 7, W = 17, H = 11 };
    for (int k = 0; k < 2; k++) {
        char full_scene[128], crop_scene[128], film[256], full[160], crop[160], cropped[160];
        write_film_scene("full.xml", filters[k].filter, full_scene, sizeof full_scene);
        snprintf(film, sizeof film,
                 "%s<integer name=\"crop_offset_x\" value=\"%d\"/><integer name=\"crop_offset_y\" value=\"%d\"/>"
                 "<integer name=\"crop_width\" value=\"%d\"/><integer name=\"crop_height\" value=\"%d\"/>",
                 filters[k].filter, X, Y, W, H);
        write_film_scene("crop.xml", film, crop_scene, sizeof crop_scene);
        snprintf(full, sizeof full, "%s/full.exr", dir);
        snprintf(crop, sizeof crop, "%s/crop.exr", dir);
        snprintf(cropped, sizeof cropped, "%s/cropped.exr", dir);
        render_ok((const char *[]){"render", full_scene, "-o", full, "--seed", "5", NULL});
        render_ok((const char *[]){"render", full_scene, "-o", crop, "--seed", "5", "--crop", "13,7,17,11", NULL});
        render_ok((const char *[]){"render", crop_scene, "-o", cropped, "--seed", "5", NULL});
        exr_planes a, b, c;
        read_exr(full, &a), read_exr(crop, &b), read_exr(cropped, &c);
        cr_assert(b.width == W && b.height == H && c.width == W && c.height == H);
        double worst = 0.0, lit = 0.0;
        for (int ch = 0; ch < 3; ch++)
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    double want = a.planes[ch][(y + Y) * a.width + x + X], got = b.planes[ch][y * W + x];
                    worst = fmax(worst, fabs(got - want) / fmax(fabs(want), 1e-3));
                    lit += want;
                    cr_assert_eq(got, c.planes[ch][y * W + x], "--crop and crop_* differ at (%d, %d)", x, y);
                }
        cr_expect_gt(lit, 0.0, "the window is black");
        cr_expect(worst <= filters[k].tol, "%s: the crop differs from the window by %g", filters[k].filter, worst);
        exr_planes_free(&a), exr_planes_free(&b), exr_planes_free(&c);
    }
}

/* Header values as numbers. */
static double header_number(const char *path, const char *name)
{
    char text[64];
    header_string(path, name, text, sizeof text);
    cr_assert(text[0], "%s: no %s", path, name);
    return atof(text);
}

/* --time: passes (of 64 spp here) until the budget is spent, recorded;
 * --preview: the image so far, rewritten after every pass (every 0 s). */
Test(render_outputs, a_time_budget_renders_passes_until_it_is_spent, .timeout = 120)
{
    char scene[128], out[160], preview[160];
    write_film_scene("timed.xml", "<rfilter type=\"box\"/>", scene, sizeof scene);
    snprintf(out, sizeof out, "%s/timed.exr", dir);
    snprintf(preview, sizeof preview, "%s/preview.png", dir);
    const double budget = 2.0;
    double t0 = now();
    render_ok((const char *[]){"render", scene, "-o", out, "--spp", "1000000", "--res", "24x16", "--time", "2",
                               "--preview", preview, "--preview-every", "0", "--threads", "2", NULL});
    double wall = now() - t0;
    double passes = header_number(out, "celadon/passes"), done = header_number(out, "celadon/sppDone");
    double seconds = header_number(out, "celadon/renderSeconds");
    cr_log_info("--time 2: %g passes, %g spp, %.2f s of rendering, %.2f s in all", passes, done, seconds, wall);
    cr_expect_geq(passes, 2, "one pass of 64 spp on 24x16 pixels takes well under a second");
    cr_expect_eq(done, 64 * passes, "sppDone %g is not the passes' %g", done, 64 * passes);
    cr_expect(seconds <= 2 * budget && seconds >= 0.5 * budget, "rendered %.2f s for a budget of %g", seconds, budget);
    char interrupted[8];
    header_string(out, "celadon/interrupted", interrupted, sizeof interrupted);
    cr_expect_str_eq(interrupted, "no", "a spent budget is no interruption");
    image_t img;
    char why[256];
    cr_assert_eq(image_read(preview, &img, why, sizeof why), 0, "no preview: %s", why);
    cr_expect(img.width == 24 && img.height == 16);
    image_free(&img);
}

/* How Blender's compositor splits an EXR channel name into layer, pass
 * and channel (docs/rendering.md, "How Blender reads these names"): a
 * one-letter name is a channel of the default layer, R, G, B, A of the
 * Combined pass, Z of Depth (unless X, Y and Z are all channels), another
 * letter of the pass of that name; otherwise, from the right, the last
 * '.'-token is the channel, the one before it the pass, the rest the layer.
 * The channel token must be one letter (Blender also knows a few longer
 * spellings, "red", "alpha", ..., which we never write): Blender 3.4 drops
 * any other channel ("unknown channel token"), a dotless name longer than
 * one letter among them. Returns 0 for a dropped name. */
static int blender_split(const char *name, int has_xyz, char *layer, char *pass, char *chan)
{
    const char *last = strrchr(name, '.');
    layer[0] = pass[0] = chan[0] = '\0';
    if (!name[0])
        return 0;
    if (!name[1]) {
        snprintf(chan, 32, "%s", name);
        if (strchr("RGBA", name[0]))
            snprintf(pass, 32, "Combined");
        else if (name[0] == 'Z' && !has_xyz)
            snprintf(pass, 32, "Depth");
        else
            snprintf(pass, 32, "%s", name);
        return 1;
    }
    if (!last || strlen(last + 1) != 1 || last == name)
        return 0;
    snprintf(chan, 32, "%s", last + 1);
    const char *p = last;
    while (p > name && p[-1] != '.')
        p--;
    snprintf(pass, 32, "%.*s", (int)(last - p), p);
    if (p > name)
        snprintf(layer, 32, "%.*s", (int)(p - 1 - name), name);
    return 1;
}

/* The rule on the names of Blender's own multilayer EXRs, then on a
 * render with every AOV: each channel lands in the pass a compositor user
 * expects (Combined, Depth, N, albedo, IndexOB, IndexMA, variance, spp,
 * Cycles' Denoising Depth, Normal and Albedo, half, specular, specular
 * half, Denoising Mirror), in the default layer,
 * with its channel letter. */
Test(render_outputs, aov_names_open_as_blender_passes, .timeout = 60)
{
    char layer[32], pass[32], chan[32];
    blender_split("ViewLayer.Combined.R", 0, layer, pass, chan);
    cr_expect(!strcmp(layer, "ViewLayer") && !strcmp(pass, "Combined") && !strcmp(chan, "R"));
    blender_split("ViewLayer.Depth.Z", 0, layer, pass, chan);
    cr_expect(!strcmp(layer, "ViewLayer") && !strcmp(pass, "Depth") && !strcmp(chan, "Z"));
    blender_split("Z", 1, layer, pass, chan);
    cr_expect(!strcmp(pass, "Z"), "Z of an X, Y, Z colour is not Depth");
    cr_expect(!blender_split("variance", 0, layer, pass, chan), "Blender 3.4 drops a dotless long name");
    cr_expect(blender_split("variance.X", 0, layer, pass, chan) && !strcmp(pass, "variance"));

    char scene[128], out[160];
    scratch_write_file(dir, "floor.xml", lit_floor_xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/passes.exr", dir);
    render_ok((const char *[]){"render", scene, "-o", out, "--aov",
                               "depth,normal,albedo,index,variance,spp,denoising,half,specular",
                               "--spp", "2", NULL});
    exr_planes e;
    read_exr(out, &e);
    /* Each pass, its channel letters, how many. */
    static const struct {
        const char *pass, *chans;
        int n;
    } want[] = {{"Combined", "RGB", 3},        {"Depth", "Z", 1},
                {"N", "XYZ", 3},               {"albedo", "RGB", 3},
                {"IndexOB", "X", 1},           {"IndexMA", "X", 1},
                {"variance", "X", 1},          {"spp", "X", 1},
                {"Denoising Depth", "Z", 1},   {"Denoising Normal", "XYZ", 3},
                {"Denoising Albedo", "RGB", 3}, {"half", "RGBA", 4},
                {"specular", "RGB", 3},        {"specular half", "RGB", 3},
                {"Denoising Mirror", "RGB", 3}};
    enum { NPASS = sizeof want / sizeof want[0] };
    int has_xyz = exr_planes_has(&e, "X") && exr_planes_has(&e, "Y") && exr_planes_has(&e, "Z");
    int found[NPASS] = {0};
    for (int c = 0; c < e.nch; c++) {
        cr_expect(blender_split(e.names[c], has_xyz, layer, pass, chan), "%s: Blender drops it", e.names[c]);
        cr_expect_str_empty(layer, "%s: in layer '%s', not the default one", e.names[c], layer);
        size_t k = 0;
        while (k < NPASS && strcmp(want[k].pass, pass))
            k++;
        cr_expect_lt(k, NPASS, "%s: pass '%s' is none of Blender's", e.names[c], pass);
        if (k == NPASS)
            continue;
        cr_expect(strlen(chan) == 1 && strchr(want[k].chans, chan[0]), "%s: channel '%s' in pass %s", e.names[c], chan, pass);
        found[k]++;
    }
    for (int k = 0; k < NPASS; k++)
        cr_expect_eq(found[k], want[k].n, "pass %s has %d channels", want[k].pass, found[k]);
    exr_planes_free(&e);
}

/* On an X, Y, Z film the depth is Depth.Z: the colour keeps X, Y and Z, the
 * depth opens as Blender's Depth pass (it used to be a second Z, and the
 * EXR could not be written after the whole render). */
Test(render_outputs, depth_on_an_xyz_film_is_depth_z, .timeout = 60)
{
    char xml[sizeof lit_floor_xml + 64], scene[128], out[160], layer[32], pass[32], chan[32];
    const char *film = strstr(lit_floor_xml, "<rfilter");
    snprintf(xml, sizeof xml, "%.*s<string name=\"pixel_format\" value=\"xyz\"/>%s", (int)(film - lit_floor_xml),
             lit_floor_xml, film);
    scratch_write_file(dir, "xyz.xml", xml, scene, sizeof scene);
    snprintf(out, sizeof out, "%s/xyz.exr", dir);
    render_ok((const char *[]){"render", scene, "-o", out, "--aov", "depth", "--spp", "1", NULL});
    exr_planes e;
    read_exr(out, &e);
    cr_expect_eq(e.nch, 4);
    cr_expect(exr_planes_has(&e, "X") && exr_planes_has(&e, "Y") && exr_planes_has(&e, "Z"));
    cr_assert(exr_planes_has(&e, "Depth.Z"));
    blender_split("Depth.Z", 1, layer, pass, chan);
    cr_expect(!strcmp(pass, "Depth") && !strcmp(chan, "Z"));
    float near = INFINITY;
    const float *z = e.planes[plane_index(&e, "Depth.Z")];
    for (int p = 0; p < e.width * e.height; p++)
        near = z[p] > 0 && z[p] < near ? z[p] : near;
    cr_expect(fabsf(near - 2.0f) < 0.05f, "nearest depth %g: the sphere's top is 2 below the camera", near);
    exr_planes_free(&e);
}

/* With the independent sampler, sample k of a pixel is the same whatever
 * the count, so the first half of an 8-spp render is the 4-spp render: the
 * half AOV unpremultiplied (half.RGB / half.A) is that render, and the
 * other half, (RGB - half.RGB) / (1 - half.A), is twice the 8-spp render
 * less the 4-spp one (box filter: each sample weighs 1). */
Test(render_outputs, half_aov_is_the_first_half_of_the_samples, .timeout = 60)
{
    char scene[128], eight[160], four[160];
    scratch_write_file(dir, "floor.xml", lit_floor_xml, scene, sizeof scene);
    snprintf(eight, sizeof eight, "%s/eight.exr", dir);
    snprintf(four, sizeof four, "%s/four.exr", dir);
    render_ok((const char *[]){"render", scene, "-o", eight, "--spp", "8", "--aov", "half", NULL});
    render_ok((const char *[]){"render", scene, "-o", four, "--spp", "4", NULL});
    exr_planes e, f;
    read_exr(eight, &e), read_exr(four, &f);
    int a = plane_index(&e, "half.A");
    double worst = 0, spread = 0;
    for (int c = 0; c < 3; c++) {
        const char *rgb = (const char *[]){"R", "G", "B"}[c], *half = (const char *[]){"half.R", "half.G", "half.B"}[c];
        const float *all = e.planes[plane_index(&e, rgb)], *h = e.planes[plane_index(&e, half)];
        const float *first = f.planes[plane_index(&f, rgb)];
        for (int p = 0; p < e.width * e.height; p++) {
            cr_assert_float_eq(e.planes[a][p], 0.5f, 1e-6f, "pixel %d: the half's share %g", p, e.planes[a][p]);
            double second = (all[p] - h[p]) / (1.0 - e.planes[a][p]);
            worst = fmax(worst, fabs(h[p] / e.planes[a][p] - first[p]) / fmax(first[p], 1e-3));
            worst = fmax(worst, fabs(second - (2.0 * all[p] - first[p])) / fmax(first[p], 1e-3));
            spread = fmax(spread, fabs(second - first[p]) / fmax(first[p], 1e-3));
        }
    }
    cr_expect_lt(worst, 1e-5, "relative difference %.3g", worst);
    cr_expect_gt(spread, 0.05, "the halves differ (noise): %.3g", spread);
    exr_planes_free(&e), exr_planes_free(&f);
}

/* A channel's value in every pixel, within tol. */
typedef struct {
    const char *name;
    float want, tol;
} plane_value;

static void expect_planes(const exr_planes *e, const plane_value *check, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        const float *v = e->planes[plane_index(e, check[k].name)];
        for (int p = 0; p < e->width * e->height; p++)
            cr_expect_float_eq(v[p], check[k].want, check[k].tol, "pixel %d: %s %g, not %g", p, check[k].name, v[p],
                               check[k].want);
    }
}

/* A camera looking straight at a perfect mirror at 2 m, tilted 45 degrees
 * so that it shows a diffuse wall 3 m to its side: the plain AOVs are the
 * mirror's (depth 2, within the 7% the tilt makes across the 4-degree
 * view, its normal, albedo 1), the denoising ones the wall's, seen in it
 * (the path's length 2 + 3 alike, the wall's normal and reflectance). */
/* An 8x8 camera at the origin looking down -z through a 4-degree view,
 * 4 independent samples a pixel, a box filter, under a white sky. */
#define NARROW_VIEW_XML                                                                                              \
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"                        \
    "<lookat origin=\"0,0,0\" target=\"0,0,-1\" up=\"0,1,0\"/></transform><float name=\"fov\" value=\"4\"/>"   \
    "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>"                        \
    "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"        \
    "<rfilter type=\"box\"/></film></sensor>"                                                                      \
    "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1,1,1\"/></emitter>"

static const char mirror_xml[] =
    NARROW_VIEW_XML
    "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate y=\"1\" angle=\"45\"/>"
    "<translate z=\"-2\"/></transform><bsdf type=\"conductor\"/></shape>"
    "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"3\"/><rotate y=\"1\" angle=\"-90\"/>"
    "<translate x=\"3\" z=\"-2\"/></transform>"
    "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2,0.4,0.6\"/></bsdf></shape></scene>\n";

Test(render_outputs, denoising_aovs_see_through_a_mirror, .timeout = 60)
{
    exr_planes e;
    render_aovs(mirror_xml, "depth,normal,albedo,denoising", &e);
    static const plane_value check[] = {{"Z", 2.0f, 0.15f},
                 {"N.X", 0.70710678f, 1e-4f},
                 {"N.Z", 0.70710678f, 1e-4f},
                 {"albedo.G", 1.0f, 1e-4f},
                 {"Denoising Depth.Z", 5.0f, 0.35f},
                 {"Denoising Normal.X", -1.0f, 1e-4f},
                 {"Denoising Normal.Y", 0.0f, 1e-4f},
                 {"Denoising Albedo.R", 0.2f, 1e-4f},
                 {"Denoising Albedo.G", 0.4f, 1e-4f},
                 {"Denoising Albedo.B", 0.6f, 1e-4f}};
    expect_planes(&e, check, sizeof check / sizeof check[0]);
    exr_planes_free(&e);
}

/* A plane filling the view under a white sky, lit by it alone: coated
 * (plastic) over a black base, all it shows is the sky in its coat, a
 * delta lobe's: the specular part is the whole colour, bit for bit, and
 * so are their halves, and the light in the mirror direction is the
 * sky's, 1; diffuse, the specular part and the mirror light are 0 in
 * every pixel. */
static void coated_plane_xml(const char *bsdf, char *xml, size_t len)
{
    snprintf(xml, len,
             NARROW_VIEW_XML "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate y=\"1\" angle=\"30\"/>"
             "<translate z=\"-2\"/></transform>%s</shape></scene>\n",
             bsdf);
}

Test(render_outputs, specular_aov_is_what_leaves_the_first_rough_vertex_by_a_glossy_lobe, .timeout = 60)
{
    static const char *const bsdfs[2] = {
        "<bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0,0,0\"/></bsdf>",
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5,0.5,0.5\"/></bsdf>"};
    for (int diffuse = 0; diffuse < 2; diffuse++) {
        char xml[2048];
        coated_plane_xml(bsdfs[diffuse], xml, sizeof xml);
        exr_planes e;
        render_aovs(xml, "half,specular", &e);
        for (int c = 0; c < 3; c++) {
            const float *rgb = e.planes[plane_index(&e, (const char *[]){"R", "G", "B"}[c])],
                        *spec = e.planes[plane_index(&e, (const char *[]){"specular.R", "specular.G", "specular.B"}[c])],
                        *half = e.planes[plane_index(&e, (const char *[]){"half.R", "half.G", "half.B"}[c])],
                        *spec_half = e.planes[plane_index(
                            &e, (const char *[]){"specular half.R", "specular half.G", "specular half.B"}[c])];
            for (int p = 0; p < e.width * e.height; p++) {
                cr_expect_gt(rgb[p], 0.02f, "pixel %d lit", p);
                cr_expect_eq(spec[p], diffuse ? 0.0f : rgb[p], "%s, pixel %d: specular %g, colour %g",
                             diffuse ? "diffuse" : "coated", p, spec[p], rgb[p]);
                cr_expect_eq(spec_half[p], diffuse ? 0.0f : half[p], "%s, pixel %d: specular half %g, half %g",
                             diffuse ? "diffuse" : "coated", p, spec_half[p], half[p]);
                float mirror = e.planes[plane_index(&e, (const char *[]){"Denoising Mirror.R", "Denoising Mirror.G",
                                                                         "Denoising Mirror.B"}[c])][p];
                cr_expect_float_eq(mirror, diffuse ? 0.0f : 1.0f, 1e-6f, "pixel %d: mirror light %g", p, mirror);
            }
        }
        exr_planes_free(&e);
    }
}

/* A thin glass sheet 1 m in front of the camera, a diffuse wall 2 m
 * behind it, the sky all around: the samples that the glass reflects (to
 * the sky) take the denoising features of the wall behind it as those it
 * lets through do, so every pixel's Denoising Albedo is the wall's
 * reflectance and its Denoising Depth 3 (they used to be speckled with
 * the sky's 0 where a sample took the glass's reflection). */
Test(render_outputs, denoising_aovs_see_through_a_sheet_whichever_way_the_path_goes, .timeout = 60)
{
    static const char xml[] =
        NARROW_VIEW_XML
        "<shape type=\"rectangle\"><transform name=\"to_world\"><translate z=\"-1\"/></transform>"
        "<bsdf type=\"thindielectric\"/></shape>"
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"3\"/><translate z=\"-3\"/></transform>"
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2,0.4,0.6\"/></bsdf></shape></scene>\n";
    exr_planes e;
    render_aovs(xml, "denoising", &e);
    static const plane_value check[] = {{"Denoising Albedo.R", 0.2f, 1e-4f},
                                        {"Denoising Albedo.G", 0.4f, 1e-4f},
                                        {"Denoising Albedo.B", 0.6f, 1e-4f},
                                        {"Denoising Depth.Z", 3.0f, 0.01f}};
    expect_planes(&e, check, sizeof check / sizeof check[0]);
    exr_planes_free(&e);
}
