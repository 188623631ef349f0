/* The reconstruction on drawn museum photographs with exact truth
 * (tests/support/synth_scene.h): a maebyeong and an ewer under a small mouth
 * and a rounded shoulder, a cast shadow and a stand cut at the foot,
 * handles left out of the profile, a lid and its knob kept; an object cut by
 * the border, two vessels and an empty backdrop refused; the quality gate.
 * Everything runs through the library pipeline (reconstruct.h) on the photo
 * written as a file, as the command line runs it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/reconstruct.h"
#include "prior/prior.h"
#include "support/synth_scene.h"

enum { W = 600, H = 800 };

typedef struct {
    int status;
    char err[512];
    reconstruction r;
    synth_scene_truth t;
} run_t;

/* Draws the named case (optionally changed by `edit`), writes it to a PNG
 * and runs the pipeline on it with the segmenter given. */
static void run_case_by(const char *name, void (*edit)(synth_scene_params *), int force, reconstruct_segmenter seg,
                        run_t *out)
{
    synth_scene_params p;
    cr_assert_eq(synth_scene_case(name, W, H, &p), 0, "no case %s", name);
    if (edit)
        edit(&p);
    image_t img;
    cr_assert_eq(synth_scene_draw(&p, &img, NULL, &out->t), 0);
    char path[128], err[256];
    snprintf(path, sizeof path, "/tmp/celadon-hard-%d-%s.png", (int)getpid(), name);
    image_t *pimg = &img;
    /* write as 8-bit like a photo */
    int c = pimg->channels;
    uint8_t *px = malloc((size_t)pimg->width * pimg->height * c);
    cr_assert_not_null(px);
    for (size_t i = 0; i < (size_t)pimg->width * pimg->height * c; i++) {
        float v = pimg->data[i];
        px[i] = (uint8_t)lrintf(255.0f * (v < 0 ? 0 : (v > 1 ? 1 : v)));
    }
    cr_assert_eq(image_write_u8(path, pimg->width, pimg->height, c, px, err, sizeof err), 0, "%s", err);
    free(px);
    image_free(&img);
    reconstruct_options opt = reconstruct_options_default();
    opt.force = force;
    opt.segmenter = seg;
    out->status = reconstruct_photo(path, &opt, &out->r, out->err, sizeof out->err);
    unlink(path);
    /* Whatever is written must revolve: r >= 0 at every control point (a
     * knob or a mouth closing on the axis may not undershoot it). */
    for (int i = 0; out->status == 0 && i < out->r.curve.n_ctrl; i++)
        cr_expect_geq(out->r.curve.ctrl[i].x, 0, "%s: control point %d at r = %g", name, i, out->r.curve.ctrl[i].x);
}

/* The same with the default segmenter (auto). */
static void run_case(const char *name, void (*edit)(synth_scene_params *), int force, run_t *out)
{
    run_case_by(name, edit, force, RECONSTRUCT_SEGMENTER_AUTO, out);
}

/* r of the fitted curve at height h (px along the image axis), by
 * bisection on the curve's h (monotonic for these profiles). */
static double curve_r_at(const bspline_t *c, double h)
{
    double lo = c->knots[0], hi = c->knots[bspline_n_knots(c) - 1];
    for (int i = 0; i < 60; i++) {
        double mid = 0.5 * (lo + hi);
        if (bspline_eval(c, mid).y < h)
            lo = mid;
        else
            hi = mid;
    }
    return bspline_eval(c, 0.5 * (lo + hi)).x;
}

typedef struct {
    double mean, max, at; /* |r - r_true| px, and the height of the worst */
} profile_error;

/* The fitted profile against the drawn body's outline (the silhouette: the
 * profile in image space, which is the meridian only for a level camera)
 * over [f0, f1] of the height between the drawn base and rim centres,
 * skipping the image rows [skip0, skip1] (none when skip0 > skip1). The
 * truth's half-width on the row through the profile's height h, the
 * difference measured across the outline. */
static profile_error compare_profile(const run_t *x, double f0, double f1, double skip0, double skip1)
{
    double Himg = v2_len(v2_sub(x->t.rim_center, x->t.base_center));
    profile_error e = {0, 0, 0};
    int n = 0;
    for (double f = f0; f <= f1; f += 0.005) {
        double h = f * Himg;
        vec2 p = v2_add(x->t.base_center, v2_scale(x->t.axis_direction, h));
        double xl, xr;
        if ((p.y >= skip0 && p.y <= skip1) || !synth_scene_outline_x(&x->t, p.y, &xl, &xr))
            continue;
        /* our h of that row: from our base along our axis */
        double hh = v2_dot(v2_sub(p, x->r.extract.axis_origin), x->r.extract.axis_direction);
        /* across the outline: a row's difference times cos of the truth's
         * slope (a shoulder turning flat moves many pixels per row) */
        double xl0, xr0, xl1, xr1, cosa = 1;
        if (synth_scene_outline_x(&x->t, p.y - 1, &xl0, &xr0) && synth_scene_outline_x(&x->t, p.y + 1, &xl1, &xr1)) {
            double s = 0.25 * ((xr1 - xl1) - (xr0 - xl0));
            cosa = 1 / sqrt(1 + s * s);
        }
        double d = cosa * fabs(curve_r_at(&x->r.curve, hh) - 0.5 * (xr - xl));
        e.mean += d;
        if (d > e.max) {
            e.max = d;
            e.at = f;
        }
        n++;
    }
    e.mean /= n > 0 ? n : 1;
    return e;
}

static const recon_excluded *find_part(const recon_result *x, recon_part_kind what)
{
    for (int i = 0; i < x->n_excluded; i++)
        if (x->excluded[i].what == what)
            return &x->excluded[i];
    return NULL;
}

/* The image row of the profile's base (h = 0). */
static double base_row(const run_t *x) { return x->r.extract.axis_origin.y; }

/* ---- shapes the former rules refused */

static void expect_profile(const char *name, double mean, double max)
{
    run_t x;
    run_case(name, NULL, 0, &x);
    cr_assert_eq(x.status, 0, "%s refused: %s", name, x.err);
    profile_error e = compare_profile(&x, 0.03, 0.97, 1, 0);
    cr_log_info("%-22s profile mean %.3f max %.3f px (at %.0f%%)", name, e.mean, e.max, 100 * e.at);
    cr_expect_leq(e.mean, mean, "%s: profile mean %.3f px", name, e.mean);
    cr_expect_leq(e.max, max, "%s: profile max %.3f px at %.0f%% of the height", name, e.max, 100 * e.at);
    reconstruction_free(&x.r);
}

/* The bounds are what the reconstruction achieves (docs/algorithms-recon.md,
 * "Accuracy"): in one flat colour the outline is exact; under studio light
 * the painted rings meet the edge just inside its dark shaded limb, as light
 * as the backdrop (max 0.80 px; 3.2-4.5 px when the edge took the ring's
 * colour for the glaze's under the edge). */
Test(recon_hard, maebyeong_and_ewer_shapes_reconstruct, .timeout = 120)
{
    expect_profile("maebyeong_flat", 0.2, 1.0);
    expect_profile("maebyeong_studio", 0.4, 1.5);
    expect_profile("maebyeong_high", 0.2, 1.0);
    expect_profile("ewer_neck", 0.3, 1.0);
}

/* A line as light as the backdrop painted round the neck cuts the vessel in
 * two across its whole width; it is still one vessel (the neck and mouth
 * joined across the line, docs/algorithms-recon.md section 3), not "two
 * objects" or a vessel without its mouth. */
Test(recon_hard, a_line_in_the_backdrop_colour_does_not_cut_the_vessel, .timeout = 60)
{
    expect_profile("vase_backdrop_line", 0.3, 1.5);
}

/* ---- cut at the foot */

static void expect_foot_cut(const char *name, void (*edit)(synth_scene_params *), recon_part_kind kind)
{
    run_t x;
    run_case(name, edit, 0, &x);
    cr_assert_eq(x.status, 0, "%s refused: %s", name, x.err);
    cr_assert(isfinite(x.t.foot_y), "%s has a foot row", name);
    double d = fabs(base_row(&x) - x.t.foot_y);
    cr_log_info("%-22s foot at row %.1f, drawn %.1f", name, base_row(&x), x.t.foot_y);
    cr_expect_leq(d, 2.0, "%s: the foot is cut %.1f px from the drawn one", name, d);
    (void)kind;
    reconstruction_free(&x.r);
}

/* The footed bowl's pillar in dark lacquer: a stand no colour model takes
 * for backdrop or shadow, so the cut at the foot must find it, and it is
 * taller than the bowl (the vessel's seeds, the object's upper half, fell on
 * it; support.c takes them above the column that rises from the border). */
static void lacquer_stand(synth_scene_params *p)
{
    static const float c[3] = {0.16f, 0.10f, 0.08f};
    memcpy(p->stand.colour, c, sizeof c);
}

Test(recon_hard, cast_shadow_and_stand_cut_at_the_foot, .timeout = 120)
{
    expect_foot_cut("maebyeong_shadow", NULL, RECON_PART_SHADOW);
    expect_foot_cut("bottle_stand", NULL, RECON_PART_STAND);
    expect_foot_cut("footed_bowl_stand", NULL, RECON_PART_STAND);
    expect_foot_cut("footed_bowl_stand", lacquer_stand, RECON_PART_STAND);
}

/* ---- handles */

static void expect_handle_left_out(const char *name, reconstruct_segmenter seg)
{
    run_t x;
    run_case_by(name, NULL, 0, seg, &x);
    cr_assert_eq(x.status, 0, "%s refused: %s", name, x.err);
    const recon_excluded *h = find_part(&x.r.extract, RECON_PART_HANDLE);
    cr_expect_not_null(h, "%s: no handle reported", name);
    /* The profile within 1 px of the truth over the whole height, the
     * handle's rows included (bridged across both attachments): issue 9's
     * bound for the side a handle leaves. */
    profile_error e = compare_profile(&x, 0.03, 0.97, 1, 0);
    cr_log_info("%-22s profile mean %.3f max %.3f px (at %.0f%%); %d parts", name, e.mean, e.max, 100 * e.at,
                x.r.extract.n_excluded);
    cr_expect_leq(e.max, 1.0, "%s: profile %.2f px off at %.0f%% of the height", name, e.max, 100 * e.at);
    reconstruction_free(&x.r);
}

Test(recon_hard, handles_are_left_out, .timeout = 120)
{
    expect_handle_left_out("ewer_handle_spout", RECONSTRUCT_SEGMENTER_AUTO);
    expect_handle_left_out("amphora_handles", RECONSTRUCT_SEGMENTER_AUTO);
    expect_handle_left_out("jar_handles_bw", RECONSTRUCT_SEGMENTER_AUTO);
}

/* The same with the learned object prior on every photo: the network keeps
 * a handle in its mask, and the energy's other terms still leave it out of
 * the profile (issue 25: the network's mask fed as the photo's alpha broke
 * handle detection). Skipped without the network file. */
Test(recon_hard, handles_are_left_out_with_the_object_prior, .timeout = 240)
{
    char path[4096];
    if (!object_prior_available() && object_prior_model_path(path, sizeof path) == 0)
        cr_skip_test("no network at %s (make deps-model): the object prior's tests are skipped", path);
    expect_handle_left_out("ewer_handle_spout", RECONSTRUCT_SEGMENTER_LEARNED);
    expect_handle_left_out("amphora_handles", RECONSTRUCT_SEGMENTER_LEARNED);
    expect_handle_left_out("jar_handles_bw", RECONSTRUCT_SEGMENTER_LEARNED);
}

/* ---- lids */

/* The flat-colour jar from a level camera: the outline is the profile
 * exactly, the knob's rounded top included. */
static void level_camera(synth_scene_params *p) { p->vessels[0].body.elevation_deg = 0; }
/* The studio jar glazed celadon: its white foot on the pale sweep is lost
 * (docs/algorithms-recon.md, "Known failures"); the lid is what this tests,
 * its flange washed by the highlight on one side (3.35 px). */
static void celadon_glaze(synth_scene_params *p)
{
    static const float c[3] = {0.50f, 0.62f, 0.53f};
    memcpy(p->vessels[0].glaze, c, sizeof c);
}

Test(recon_hard, lid_and_knob_are_kept, .timeout = 60)
{
    struct {
        const char *name;
        void (*edit)(synth_scene_params *);
        double top, max;
    } cases[] = {{"lidded_jar_flat_high", level_camera, 2.0, 1.0}, {"lidded_jar", celadon_glaze, 4.0, 3.5}};
    for (int k = 0; k < 2; k++) {
        run_t x;
        run_case(cases[k].name, cases[k].edit, 0, &x);
        cr_assert_eq(x.status, 0, "%s refused: %s", cases[k].name, x.err);
        double Himg = v2_len(v2_sub(x.t.rim_center, x.t.base_center));
        double top = x.r.curve.ctrl[x.r.curve.n_ctrl - 1].y;
        profile_error e = compare_profile(&x, 0.5, 0.97, 1, 0);
        cr_log_info("%-22s rim at h = %.1f, drawn %.1f; lid and shoulder max %.2f px", cases[k].name, top, Himg, e.max);
        cr_expect_leq(fabs(top - Himg), cases[k].top, "%s: the profile ends at h = %.1f, the knob's top is at %.1f",
                      cases[k].name, top, Himg);
        cr_expect_leq(e.max, cases[k].max, "%s: lid profile %.2f px off at %.0f%%", cases[k].name, e.max, 100 * e.at);
        reconstruction_free(&x.r);
    }
}

/* ---- refusals */

static void expect_refused(const char *name, const char *why)
{
    run_t x;
    run_case(name, NULL, 0, &x);
    cr_log_info("%-22s -> %d %s", name, x.status, x.err);
    cr_expect_eq(x.status, 2, "%s accepted", name);
    cr_expect(strstr(x.err, why) != NULL, "%s: refused for '%s', expected '%s'", name, x.err, why);
    reconstruction_free(&x.r);
}

Test(recon_hard, border_two_vessels_and_nothing_are_refused, .timeout = 120)
{
    expect_refused("vase_cut_bottom", "bottom image border");
    expect_refused("two_vessels", "two objects");
    expect_refused("backdrop_only", "no object");
}

/* ---- clear of the border */

/* Issue 25: the mask ran into the backdrop out to the image border and
 * the photo was refused as "touches the border", the vessel well clear of
 * it: a small bottle in a large frame (a sixth of its height, under a
 * strong vignette, with paper grain), and a jar splashed with a dark glaze
 * on a dark sweep. Both accepted, the profile on the drawn outline: mean
 * at most 0.5% of the vessel's height, as on the real photos, and no row
 * farther than 1.5%. */
static void small_in_a_large_frame(synth_scene_params *p)
{
    synth_body *b = &p->vessels[0].body;
    b->height_px /= 4.5;
    p->backdrop.vignette = 0.35;
    p->backdrop.grain = 0.02;
    p->backdrop.grain_px = 64;
}

static void splashed_on_dark(synth_scene_params *p)
{
    static const float glaze[3] = {0.62f, 0.58f, 0.48f}, splash[3] = {0.18f, 0.12f, 0.20f};
    memcpy(p->vessels[0].glaze, glaze, sizeof glaze);
    memcpy(p->vessels[0].decor_colour, splash, sizeof splash);
    p->vessels[0].decor = SYNTH_DECOR_MEDALLIONS;
    p->backdrop.wall[0] = p->backdrop.wall[1] = p->backdrop.wall[2] = 0.16f;
}

Test(recon_hard, vessels_clear_of_the_border_are_not_refused_for_it, .timeout = 120)
{
    struct {
        const char *name;
        void (*edit)(synth_scene_params *);
    } cases[] = {{"maebyeong_studio", small_in_a_large_frame}, {"white_on_grey", splashed_on_dark}};
    for (int k = 0; k < 2; k++) {
        run_t x;
        run_case(cases[k].name, cases[k].edit, 0, &x);
        cr_assert_eq(x.status, 0, "%s (edited) refused: %s", cases[k].name, x.err);
        double Himg = v2_len(v2_sub(x.t.rim_center, x.t.base_center));
        profile_error e = compare_profile(&x, 0.03, 0.97, 1, 0);
        cr_log_info("%-22s edited: height %.0f px, profile mean %.3f%% max %.3f%% of it", cases[k].name, Himg,
                    100 * e.mean / Himg, 100 * e.max / Himg);
        cr_expect_leq(e.mean, 0.005 * Himg, "%s: profile mean %.2f px", cases[k].name, e.mean);
        cr_expect_leq(e.max, 0.015 * Himg, "%s: profile %.2f px off at %.0f%%", cases[k].name, e.max, 100 * e.at);
        reconstruction_free(&x.r);
    }
}

/* ---- the quality gate */

/* A lump standing out by 4% of the height on one side over 80% of it,
 * from a tenth of it: no side of the outline can be the body's over most of
 * the height. (Down to the base, or standing out by 15%, which moves the
 * body's axis with it, it is refused before the gate as not a vessel: a
 * base that reaches 11-18% of the height farther on one side;
 * docs/algorithms-recon.md, section 15.) */
static void huge_spout(synth_scene_params *p)
{
    p->attachments[0] = (synth_attachment){SYNTH_ATTACH_LUG, 1, 0.5, 0, 0.04, 0.8, {0, 0, 0}};
}

Test(recon_hard, a_result_over_the_limits_is_refused_unless_forced, .timeout = 60)
{
    run_t x;
    run_case("maebyeong_flat", huge_spout, 0, &x);
    cr_log_info("refused: %d %s", x.status, x.err);
    cr_expect_eq(x.status, 2, "a one-sided lump over most of the height passed the gate");
    cr_expect(strstr(x.err, "quality gate") != NULL, "%s", x.err);
    reconstruction_free(&x.r);
    run_case("maebyeong_flat", huge_spout, 1, &x);
    cr_expect_eq(x.status, 0, "--force: %s", x.err);
    cr_expect_eq(x.r.quality.passed, 0, "the figures say it failed");
    reconstruction_free(&x.r);
}
