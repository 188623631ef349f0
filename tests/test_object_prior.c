/* The learned object prior (src/prior/prior.h) and the segmentation that
 * takes it as a term of its energy, on drawn photographs with exact truth
 * (tests/support/synth_scene.h). Every test here needs the network file that
 * `make deps-model` obtains, and skips with one line without it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/reconstruct.h"
#include "prior/prior.h"
#include "support/cli_run.h"
#include "support/scratch_dir.h"
#include "support/synth_scene.h"

enum { W = 300, H = 400 };

static void need_network(void)
{
    char path[4096];
    if (!object_prior_available() && object_prior_model_path(path, sizeof path) == 0)
        cr_skip_test("no network at %s (make deps-model): the object prior's tests are skipped", path);
}

/* The named case drawn at W x H, with the body's coverage. */
static void draw(const char *name, image_t *img, image_t *body, synth_scene_truth *t)
{
    synth_scene_params p;
    cr_assert_eq(synth_scene_case(name, W, H, &p), 0, "no case %s", name);
    cr_assert_eq(synth_scene_draw(&p, img, body, t), 0);
}

/* The network's probability over the body's covered pixels and over the
 * pixels at least `margin` px from it, by their mean and their worst. */
Test(object_prior, sees_the_vessel_and_not_the_backdrop, .timeout = 120)
{
    need_network();
    image_t img, body;
    synth_scene_truth t;
    draw("maebyeong_studio", &img, &body, &t);
    float *prob = malloc((size_t)W * H * sizeof *prob);
    char err[256];
    cr_assert_eq(object_prior_compute(&img, prob, err, sizeof err), 0, "%s", err);
    double in = 0, out = 0;
    long n_in = 0, n_out = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float p = prob[(size_t)y * W + x];
            cr_assert(p >= 0 && p <= 1, "probability %g at (%d, %d)", p, x, y);
            if (body.data[(size_t)y * W + x] > 0.99f) {
                in += p;
                n_in++;
            } else if (y < 3 || x < 3 || x >= W - 3 || y >= H - 3) { /* the image border */
                out += p;
                n_out++;
            }
        }
    cr_log_info("mean probability: body %.3f, image border %.4f", in / n_in, out / n_out);
    cr_expect_gt(in / n_in, 0.9);
    cr_expect_lt(out / n_out, 0.05);
    free(prob);
    image_free(&img);
    image_free(&body);
}

/* A dark band along the wall behind the vessel, from the left border to the
 * right one (rows y0..y1 of the backdrop darkened to k times its colour,
 * under the body's coverage), as a museum's wall moulding or the shadow of
 * a shelf: the backdrop's smooth surface cannot explain it, so the classical
 * segmentation takes it for the object, out to both borders. */
static void paint_wall_band(image_t *img, const image_t *body, int y0, int y1, float k)
{
    for (int y = y0; y <= y1; y++)
        for (int x = 0; x < img->width; x++) {
            size_t p = (size_t)y * img->width + x;
            float m = body->data[p], f = m + (1 - m) * k;
            for (int c = 0; c < img->channels; c++)
                img->data[p * img->channels + c] *= f;
        }
}

/* The rows of the mask's extent, outside the body's true outline by more
 * than tol px on either side (0: the mask stays on the vessel). */
static int rows_outside(const recon_result *res, const synth_scene_truth *t, int y0, int y1, double tol)
{
    int bad = 0;
    for (int y = y0; y <= y1; y++) {
        double xl, xr;
        if (!synth_scene_outline_x(t, y + 0.5, &xl, &xr))
            continue;
        const uint8_t *m = res->mask + (size_t)y * res->width;
        int a = 0, b = res->width - 1;
        while (a < res->width && !m[a])
            a++;
        while (b >= 0 && !m[b])
            b--;
        bad += a < xl - tol || b + 1 > xr + tol;
    }
    return bad;
}

/* The flat maebyeong's wall band: rows 25-40% of the height, darkened to 45%. */
#define BAND_Y0 ((int)(0.25 * H))
#define BAND_Y1 ((int)(0.40 * H))
#define BAND_K 0.45f

Test(object_prior, keeps_the_vessel_clear_of_a_wall_band_that_reaches_the_borders, .timeout = 180)
{
    need_network();
    image_t img, body;
    synth_scene_truth t;
    draw("maebyeong_flat", &img, &body, &t);
    paint_wall_band(&img, &body, BAND_Y0, BAND_Y1, BAND_K);
    char err[256];
    recon_options opt = {-1, RECON_SIDE_AUTO, NULL};
    recon_result classic;
    recon_status st = recon_extract(&img, &opt, &classic, err, sizeof err);
    /* the case is hard classically: the band is taken for the object */
    cr_assert(st != RECON_OK || classic.border_contact, "the classical segmentation kept clear of the band");
    recon_result_free(&classic);

    float *prob = malloc((size_t)W * H * sizeof *prob);
    cr_assert_eq(object_prior_compute(&img, prob, err, sizeof err), 0, "%s", err);
    opt.object_prior = prob;
    recon_result res;
    cr_assert_eq(recon_extract(&img, &opt, &res, err, sizeof err), RECON_OK, "%s", err);
    int bad = rows_outside(&res, &t, BAND_Y0, BAND_Y1, 2.0);
    cr_log_info("with the prior: border contact %u, %d band rows off the true outline by over 2 px", res.border_contact,
                bad);
    cr_expect_eq(res.border_contact, 0u);
    cr_expect_eq(bad, 0);
    recon_result_free(&res);
    free(prob);
    image_free(&img);
    image_free(&body);
}

/* The flat maebyeong, with the wall band or without, written as an 8-bit
 * PNG to path. */
static void write_drawn_photo(const char *path, int band)
{
    image_t img, body;
    synth_scene_truth t;
    draw("maebyeong_flat", &img, &body, &t);
    if (band)
        paint_wall_band(&img, &body, BAND_Y0, BAND_Y1, BAND_K);
    size_t n = (size_t)img.width * img.height * img.channels;
    uint8_t *px = malloc(n);
    cr_assert_not_null(px);
    for (size_t i = 0; i < n; i++)
        px[i] = (uint8_t)lrintf(255 * fminf(1, fmaxf(0, img.data[i])));
    char err[256];
    cr_assert_eq(image_write_u8(path, img.width, img.height, img.channels, px, err, sizeof err), 0, "%s", err);
    free(px);
    image_free(&img);
    image_free(&body);
}

static int reconstruct_by(const char *path, reconstruct_segmenter seg, int *used_prior, double *ms_prior)
{
    reconstruct_options opt = reconstruct_options_default();
    opt.segmenter = seg;
    reconstruction r;
    char err[1024];
    int st = reconstruct_photo(path, &opt, &r, err, sizeof err);
    cr_log_info("segmenter %d: %s", (int)seg, st ? err : "passed");
    *used_prior = r.used_prior;
    *ms_prior = r.ms.prior;
    reconstruction_free(&r);
    return st;
}

/* auto's rule: the network runs only where the classical result is refused,
 * and its result is kept when it passes. The wall band's photo is refused
 * classically and passes by auto, with the prior; the clean photo passes
 * classically and auto never runs the network on it. */
Test(object_prior, auto_runs_the_network_only_where_the_classical_result_is_refused, .timeout = 240)
{
    need_network();
    char dir[128], path[256];
    scratch_dir_make(dir, sizeof dir, "prior");
    snprintf(path, sizeof path, "%s/photo.png", dir);
    int used;
    double ms;
    write_drawn_photo(path, 0);
    cr_expect_eq(reconstruct_by(path, RECONSTRUCT_SEGMENTER_AUTO, &used, &ms), 0);
    cr_expect_eq(used, 0, "auto ran the network on a photo the classical segmentation passes");
    cr_expect_eq(ms, 0.0);

    write_drawn_photo(path, 1);
    cr_expect_eq(reconstruct_by(path, RECONSTRUCT_SEGMENTER_CLASSIC, &used, &ms), 2);
    cr_expect_eq(reconstruct_by(path, RECONSTRUCT_SEGMENTER_AUTO, &used, &ms), 0);
    cr_expect_eq(used, 1);
    cr_expect_gt(ms, 0.0);
    scratch_dir_remove(dir);
}

/* Without the network (a machine without `make deps-model`): a batch says
 * once, not once a photo, that the prior is off, and still reconstructs
 * classically; with --segmenter classic it says nothing. The band photo,
 * which only the prior rescues, stays refused. */
Test(object_prior, without_the_network_a_run_says_so_once_and_goes_on_classically, .timeout = 120)
{
    char dir[128], a[256], b[256], out[256];
    scratch_dir_make(dir, sizeof dir, "prior-off");
    snprintf(a, sizeof a, "%s/a.png", dir);
    snprintf(b, sizeof b, "%s/b.png", dir);
    snprintf(out, sizeof out, "%s/out", dir);
    write_drawn_photo(a, 0);
    write_drawn_photo(b, 1);
    setenv("CELADON_PRIOR_MODEL", "/nonexistent/isnet.onnx", 1);
    cli_result r = cli_run(dir, (const char *[]){"reconstruct", a, b, "-o", out, NULL});
    cr_expect_eq(r.status, 2, "the band photo is refused without the prior: %s", r.err);
    cr_expect_eq(r.prior_off_notices, 1, "the notice, once for two photos");
    cr_expect_not_null(strstr(r.err, "b.png: quality gate"), "%s", r.err);
    cr_expect_not_null(strstr(r.err, "1 of 2 photos reconstructed"), "%s", r.err);
    cli_result_free(&r);
    cli_result c = cli_run(dir, (const char *[]){"reconstruct", a, "-o", out, "--segmenter", "classic", NULL});
    cr_expect_eq(c.status, 0, "%s", c.err);
    cr_expect_eq(c.prior_off_notices, 0, "classic asked for: no notice");
    cli_result_free(&c);
    unsetenv("CELADON_PRIOR_MODEL");
    scratch_dir_remove(dir);
}
