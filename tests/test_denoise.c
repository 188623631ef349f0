/* The denoiser (celadon/denoise.h; docs/rendering.md, "Denoising"):
 * synthetic images with a known clean truth, a piecewise-smooth function
 * of the features plus noise of known variance, where it must reduce the
 * error by a stated factor and keep a feature-marked step sharp; images
 * exactly linear in the features, which first-order regression keeps;
 * `celadon denoise` end to end and on bad inputs. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/denoise.h"
#include "celadon/film.h"
#include "celadon/rng.h"
#include "support/cli_run.h"
#include "support/exr_planes.h"
#include "support/scratch_dir.h"

static char dir[64];

static void open_dir(void) { scratch_dir_make(dir, sizeof dir, "denoise"); }
static void close_dir(void) { scratch_dir_remove(dir); }

TestSuite(denoise, .init = open_dir, .fini = close_dir);

enum { W = 48, H = 36, C = DENOISE_HALF_CHANNELS };

/* A standard normal deviate (Box-Muller). */
static double gauss(rng_t *r)
{
    double u = rng_next_double(r), v = rng_next_double(r);
    return sqrt(-2.0 * log(1.0 - u)) * cos(2.0 * M_PI * v);
}

/* Two surfaces meeting at a vertical edge at x = EDGE + 0.4 (so column
 * EDGE mixes them 40 / 60, in colour as in features, as a render's pixel
 * does): each a smooth shading times its own albedo, with its own normal
 * and depth, the left one under a coat that adds a smooth reflection of
 * its own (grey, not times the albedo: the specular part). truth gets the
 * clean colour, img (C channels a pixel) the features and the clean
 * colour plus noise of standard deviation sigma (its variance channel
 * says sigma^2), the mean of two halves each with independent noise of
 * sigma sqrt(2), the first of which is half.R/G/B (premultiplied by its
 * share, half.A = 1/2); of each, a third of the noise in the specular
 * part (specular.R/G/B, specular half.R/G/B), whose clean value is the
 * mirror light feature (Denoising Mirror.R/G/B). */
#define EDGE 30
static void two_surfaces(double sigma, float *img, float *truth, uint64_t seed)
{
    static const float albedo[2][3] = {{0.7f, 0.5f, 0.3f}, {0.2f, 0.3f, 0.6f}};
    static const float normal[2][3] = {{0, 0, 1}, {0.6f, 0, 0.8f}};
    static const float depth[2] = {2.0f, 3.5f};
    rng_t r;
    rng_seed(&r, seed, 7);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = img + ((size_t)y * W + x) * C, *t = truth + ((size_t)y * W + x) * 3;
            double left = x < EDGE ? 1.0 : x == EDGE ? 0.4 : 0.0, shade[2];
            shade[0] = 0.8 + 0.3 * sin(x / 9.0) * cos(y / 11.0);
            shade[1] = 0.5 + 0.004 * y;
            double coat = left * 0.15 * (1 + cos((x + y) / 12.0));
            for (int c = 0; c < 3; c++) {
                t[c] = (float)(left * albedo[0][c] * shade[0] + (1 - left) * albedo[1][c] * shade[1] + coat);
                /* Each half: diffuse and specular noise, variances 2/3 and
                 * 1/3 of 2 sigma^2. */
                double ea = sqrt(2.0 / 3) * M_SQRT2 * sigma * gauss(&r), eb = sqrt(2.0 / 3) * M_SQRT2 * sigma * gauss(&r);
                double sa = coat + sqrt(1.0 / 3) * M_SQRT2 * sigma * gauss(&r),
                       sb = coat + sqrt(1.0 / 3) * M_SQRT2 * sigma * gauss(&r);
                double a = t[c] - coat + ea + sa, b = t[c] - coat + eb + sb;
                p[c] = (float)(0.5 * (a + b));
                p[11 + c] = (float)(0.5 * a);
                p[15 + c] = (float)(0.5 * (sa + sb));
                p[18 + c] = (float)(0.5 * sa);
                p[21 + c] = (float)coat; /* the light the coat mirrors */
                p[3 + c] = (float)(left * albedo[0][c] + (1 - left) * albedo[1][c]);
                p[6 + c] = (float)(left * normal[0][c] + (1 - left) * normal[1][c]);
            }
            p[9] = (float)(left * depth[0] + (1 - left) * depth[1]);
            p[10] = (float)(sigma * sigma);
            p[14] = 0.5f;
        }
}

/* The first DENOISE_CHANNELS of each pixel of img (denoise_image's input). */
static float *one_buffer(const float *img)
{
    float *one = malloc(sizeof *one * W * H * DENOISE_CHANNELS);
    cr_assert_not_null(one);
    for (int p = 0; p < W * H; p++)
        memcpy(one + (size_t)p * DENOISE_CHANNELS, img + (size_t)p * C, sizeof *one * DENOISE_CHANNELS);
    return one;
}

/* The mean squared error of the RGB of img (stride C or 3) against truth,
 * over columns [x0, x1). */
static double mse(const float *img, int stride, const float *truth, int x0, int x1)
{
    double s = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++)
            for (int c = 0; c < 3; c++) {
                double e = img[((size_t)y * W + x) * stride + c] - truth[((size_t)y * W + x) * 3 + c];
                s += e * e;
            }
    return s / (3.0 * H * (x1 - x0));
}

/* Noise of sigma 0.05 (about a tenth of the colours): the error falls by
 * more than 8 (a 16-spp image made better than a 128-spp one), and on the
 * three columns at the edge it stays below a fifth of the raw noise's, where
 * a blur across the edge would leave the step's 0.2 to 0.3; from the one
 * buffer and from the two halves. */
Test(denoise, removes_noise_and_keeps_a_feature_edge)
{
    const double sigma = 0.05;
    float *img = malloc(sizeof *img * W * H * C), *truth = malloc(sizeof *truth * W * H * 3),
          *out = malloc(sizeof *out * W * H * 3);
    cr_assert(img && truth && out);
    two_surfaces(sigma, img, truth, 1);
    float *one = one_buffer(img);
    double before = mse(img, C, truth, 0, W), edge_before = mse(img, C, truth, EDGE - 1, EDGE + 2);
    for (int halves = 0; halves < 2; halves++) {
        cr_assert_eq(halves ? denoise_image_halves(W, H, img, out) : denoise_image(W, H, one, out), 0);
        double after = mse(out, 3, truth, 0, W), edge_after = mse(out, 3, truth, EDGE - 1, EDGE + 2);
        cr_expect_lt(after, before / 8, "halves %d: MSE %.3g -> %.3g (ratio %.1f)", halves, before, after,
                     before / after);
        cr_expect_lt(edge_after, edge_before / 5, "halves %d: edge MSE %.3g -> %.3g (ratio %.1f)", halves,
                     edge_before, edge_after, edge_before / edge_after);
    }
    free(img), free(truth), free(out), free(one);
}

/* Colour exactly linear in the screen position, albedo, normal and depth
 * over the whole image (values 0.5 to 2.5), with no noise but a variance
 * that says there is (so the weights are wide): first-order regression
 * gives it back within 1e-3, what the ridge's shrinkage of the slopes of
 * correlated features costs (4e-4 here); a weighted mean (zero order)
 * would be off by tenths. Alike from two (equal) halves. */
Test(denoise, keeps_an_image_linear_in_the_features)
{
    float *img = malloc(sizeof *img * W * H * C), *out = malloc(sizeof *out * W * H * 3);
    cr_assert(img && out);
    rng_t r;
    rng_seed(&r, 3, 1);
    for (int p = 0; p < W * H; p++) {
        float *v = img + (size_t)p * C;
        int x = p % W, y = p / W;
        /* Features that wander smoothly plus a little per-pixel jitter. */
        for (int c = 0; c < 3; c++) {
            v[3 + c] = (float)(0.4 + 0.1 * sin(x / (7.0 + c) + y / 13.0) + 0.02 * rng_next_double(&r));
            v[6 + c] = (float)(0.5 * cos(y / (9.0 + c) - x / 17.0) + 0.02 * rng_next_double(&r));
        }
        v[9] = (float)(3.0 + 0.02 * x + 0.3 * rng_next_double(&r));
        for (int c = 0; c < 3; c++)
            v[c] = (float)(0.2 + 0.1 * c + 0.003 * x - 0.002 * y + (0.5 + c) * v[3 + c] - 0.3 * v[6 + (c + 1) % 3] +
                           0.05 * (c + 1) * v[9]);
        v[10] = 0.01f;
        for (int c = 0; c < 3; c++)
            v[11 + c] = 0.5f * v[c], v[15 + c] = v[18 + c] = v[21 + c] = 0.0f;
        v[14] = 0.5f;
    }
    float *one = one_buffer(img);
    for (int halves = 0; halves < 2; halves++) {
        cr_assert_eq(halves ? denoise_image_halves(W, H, img, out) : denoise_image(W, H, one, out), 0);
        double worst = 0;
        for (int p = 0; p < W * H; p++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(out[(size_t)p * 3 + c] - img[(size_t)p * C + c]));
        cr_expect_lt(worst, 1e-3, "halves %d: largest change %.3g of a linear image", halves, worst);
    }
    free(img), free(out), free(one);
}

/* Fireflies: twelve pixels where one half drew a path of weight 100 (the
 * whole pixel then about 50 above its colour of at most 1): from the
 * halves they are cut down to what the other half shows around them, and
 * the denoised image stays within 0.1 of the truth in every pixel (a
 * firefly kept would leave about 50 in its pixel, or spread over its
 * neighbours several tenths). */
Test(denoise, a_firefly_in_one_half_is_cut)
{
    float *img = malloc(sizeof *img * W * H * C), *truth = malloc(sizeof *truth * W * H * 3),
          *out = malloc(sizeof *out * W * H * 3);
    cr_assert(img && truth && out);
    two_surfaces(0.02, img, truth, 5);
    for (int k = 0; k < 12; k++) {
        float *v = img + ((size_t)(3 + 2 * k) * W + 4 + 3 * k) * C;
        for (int c = 0; c < 3; c++)
            v[c] += 50.0f, v[11 + c] += 50.0f; /* half.RGB: 0.5 x 100 */
    }
    cr_assert_eq(denoise_image_halves(W, H, img, out), 0);
    double worst = 0;
    for (int p = 0; p < W * H; p++)
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(out[(size_t)p * 3 + c] - truth[(size_t)p * 3 + c]));
    cr_expect_lt(worst, 0.1, "largest error %.3g", worst);
    free(img), free(truth), free(out);
}

/* An image too large for memory (2^40 pixels: 12 TB a colour plane) is
 * refused with -1, not abort(); the input is never read. ASan's allocator
 * aborts on such a request unless told otherwise: the test runs in the
 * other builds. */
Test(denoise, out_of_memory_returns_an_error)
{
#if defined(__SANITIZE_ADDRESS__)
    cr_skip_test("ASan's allocator aborts on a 12 TB request");
#else
    static const float nothing[DENOISE_HALF_CHANNELS];
    float out[3];
    cr_expect_eq(denoise_image(1 << 20, 1 << 20, nothing, out), -1);
    cr_expect_eq(denoise_image_halves(1 << 20, 1 << 20, nothing, out), -1);
#endif
}

/* Writes the two surfaces as a render's EXR (with an extra channel and a
 * header attribute the output must keep) into dir/name. */
static void write_render_exr(const char *name, const char *const *names, int nch, char *path, size_t len)
{
    float *img = malloc(sizeof *img * W * H * C), *truth = malloc(sizeof *truth * W * H * 3),
          *px = malloc(sizeof *px * W * H * (C + 1));
    cr_assert(img && truth && px);
    two_surfaces(0.05, img, truth, 2);
    for (int p = 0; p < W * H; p++) {
        for (int k = 0; k < C; k++)
            px[(size_t)p * (C + 1) + k] = img[(size_t)p * C + k];
        px[(size_t)p * (C + 1) + C] = 7.0f; /* "IndexOB.X" */
    }
    /* Keep the channels names asks for, in its order. */
    float *sel = malloc(sizeof *sel * W * H * nch);
    cr_assert_not_null(sel);
    for (int k = 0; k < nch; k++) {
        int from = 0;
        while (from < C && strcmp(denoise_channel_names[from], names[k]))
            from++;
        for (int p = 0; p < W * H; p++)
            sel[(size_t)p * nch + k] = px[(size_t)p * (C + 1) + from];
    }
    snprintf(path, len, "%s/%s", dir, name);
    film_attr attr = {"celadon/scene", "two-surfaces.xml"};
    char err[512];
    cr_assert_eq(exr_write_float_attrs(path, W, H, nch, names, sel, NULL, &attr, 1, err, sizeof err), 0, "%s", err);
    free(img), free(truth), free(px), free(sel);
}

/* What `oiiotool --info -v path` prints (malloc'd). */
static char *oiio_info(const char *path)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "oiiotool --info -v '%s' 2>&1", path);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    char *text = calloc(1, 1 << 16);
    cr_assert_not_null(text);
    size_t n = fread(text, 1, (1 << 16) - 1, p);
    text[n] = '\0';
    pclose(p);
    return text;
}

/* The command keeps every channel and the header, denoises R, G, B only,
 * and says so in celadon/denoised. */
Test(denoise, command_denoises_the_colour_and_keeps_the_rest, .timeout = 60)
{
    const char *names[C + 1];
    memcpy(names, denoise_channel_names, sizeof(char *) * C);
    names[C] = "IndexOB.X";
    char in[128], out[160];
    write_render_exr("render.exr", names, C + 1, in, sizeof in);
    snprintf(out, sizeof out, "%s/denoised.exr", dir);
    cli_result r = cli_run(dir, (const char *[]){"denoise", in, "-o", out, NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);
    exr_planes a, b;
    read_exr(in, &a);
    read_exr(out, &b);
    cr_assert_eq(b.nch, C + 1);
    int changed = 0;
    for (int k = 0; k < C + 1; k++) {
        int ia = plane_index(&a, names[k]), ib = plane_index(&b, names[k]);
        int same = !memcmp(a.planes[ia], b.planes[ib], sizeof(float) * W * H);
        if (k < 3)
            changed += !same;
        else
            cr_expect(same, "channel %s changed", names[k]);
    }
    cr_expect_eq(changed, 3, "R, G, B denoised");
    exr_planes_free(&a), exr_planes_free(&b);
    char *info = oiio_info(out);
    cr_expect(strstr(info, "celadon/denoised") != NULL, "%s", info);
    cr_expect(strstr(info, "two-surfaces.xml") != NULL, "the input's header is kept: %s", info);
    free(info);
}

/* Each bad input: exit 2, one line "celadon: FILE: problem", no output. */
static void expect_refused(const char *in, const char *says)
{
    char out[160];
    snprintf(out, sizeof out, "%s/refused.exr", dir);
    cli_result r = cli_run(dir, (const char *[]){"denoise", in, "-o", out, NULL});
    cr_expect_eq(r.status, 2, "%s: stderr: %s", in, r.err);
    cr_expect_eq(cli_count_lines(r.err), 1, "%s: stderr: %s", in, r.err);
    char head[300];
    snprintf(head, sizeof head, "celadon: %s: ", in);
    cr_expect(!strncmp(r.err, head, strlen(head)), "stderr: %s", r.err);
    cr_expect(strstr(r.err, says) != NULL, "stderr: %s (wanted '%s')", r.err, says);
    cr_expect(access(out, F_OK) != 0, "%s left an output", in);
    cli_result_free(&r);
}

Test(denoise, bad_inputs_exit_2_with_one_line_and_no_file, .timeout = 60)
{
    static const char *const rgb_only[4] = {"R", "G", "B", "IndexOB.X"};
    char path[128], missing[128], text[128], cut[160];
    write_render_exr("plain.exr", rgb_only, 4, path, sizeof path);
    expect_refused(path, "has no channel Denoising Albedo.R, Denoising Albedo.G, Denoising Albedo.B, "
                         "Denoising Normal.X, Denoising Normal.Y, Denoising Normal.Z, Denoising Depth.Z, variance.X, "
                         "half.R, half.G, half.B, half.A, specular.R, specular.G, specular.B, specular half.R, "
                         "specular half.G, specular half.B, Denoising Mirror.R, Denoising Mirror.G, "
                         "Denoising Mirror.B");
    snprintf(missing, sizeof missing, "%s/none.exr", dir);
    expect_refused(missing, "none.exr");
    scratch_write_file(dir, "text.exr", "not an image\n", text, sizeof text);
    expect_refused(text, "OpenEXR");
    /* A whole render's EXR cut short: its header reads, its pixels do not. */
    char whole[128];
    write_render_exr("whole.exr", denoise_channel_names, C, whole, sizeof whole);
    snprintf(cut, sizeof cut, "%s/cut.exr", dir);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "head -c 2000 '%s' > '%s'", whole, cut);
    cr_assert_eq(system(cmd), 0);
    expect_refused(cut, "");
    /* -o naming the input (under another name) is refused; it stays whole. */
    char alias[160];
    snprintf(alias, sizeof alias, "%s/./whole.exr", dir);
    cli_result r = cli_run(dir, (const char *[]){"denoise", whole, "-o", alias, NULL});
    cr_expect_eq(r.status, 2, "stderr: %s", r.err);
    cr_expect(strstr(r.err, "is the input") != NULL, "stderr: %s", r.err);
    cli_result_free(&r);
    exr_planes e;
    read_exr(whole, &e);
    cr_expect_eq(e.nch, C);
    exr_planes_free(&e);
}

/* A lit sphere on a floor, 4 samples per pixel. */
static const char floor_xml[] =
    "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
    "<lookat origin=\"0,2,3\" target=\"0,0.4,0\" up=\"0,1,0\"/></transform>"
    "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>"
    "<film type=\"hdrfilm\"><integer name=\"width\" value=\"32\"/><integer name=\"height\" value=\"24\"/></film>"
    "</sensor><emitter type=\"constant\"><rgb name=\"radiance\" value=\"1,1,1\"/></emitter>"
    "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/>"
    "</transform><bsdf type=\"diffuse\"/></shape>"
    "<shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0.5\" z=\"0\"/><float name=\"radius\" value=\"0.5\"/>"
    "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2,0.6,0.3\"/></bsdf></shape></scene>\n";

/* render --denoise: the same render as without it but for R, G, B, with
 * the features it needed written too, labelled denoised; not for a part. */
Test(denoise, render_denoise_writes_the_denoised_render, .timeout = 60)
{
    char scene[128], raw[160], den[160];
    scratch_write_file(dir, "floor.xml", floor_xml, scene, sizeof scene);
    snprintf(raw, sizeof raw, "%s/raw.exr", dir);
    snprintf(den, sizeof den, "%s/den.exr", dir);
    cli_result r = cli_run(dir, (const char *[]){"render", scene, "-o", raw, "--aov", "denoising,half,specular,variance",
                                                 NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);
    r = cli_run(dir, (const char *[]){"render", scene, "-o", den, "--denoise", NULL});
    cr_assert_eq(r.status, 0, "stderr: %s", r.err);
    cli_result_free(&r);
    exr_planes a, b;
    read_exr(raw, &a);
    read_exr(den, &b);
    cr_assert_eq(a.nch, b.nch);
    for (int k = 0; k < a.nch; k++) {
        int same = !memcmp(a.planes[k], b.planes[plane_index(&b, a.names[k])], sizeof(float) * a.width * a.height);
        int colour = !strcmp(a.names[k], "R") || !strcmp(a.names[k], "G") || !strcmp(a.names[k], "B");
        cr_expect(same != colour, "channel %s %s", a.names[k], same ? "unchanged" : "changed");
    }
    exr_planes_free(&a), exr_planes_free(&b);
    char *info = oiio_info(den);
    cr_expect(strstr(info, "celadon/denoised") != NULL, "%s", info);
    free(info);
    r = cli_run(dir, (const char *[]){"render", scene, "-o", den, "--denoise", "--part", "1/2", NULL});
    cr_expect_eq(r.status, 2, "--part with --denoise: %s", r.err);
    cli_result_free(&r);
}
