/* Every refusal of recon_extract, and inputs that must not crash it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/recon.h"
#include "support/synth_vessel.h"

static recon_status run(const image_t *img, char *err, size_t len)
{
    recon_options opt = {-1, RECON_SIDE_AUTO, NULL};
    recon_result r;
    recon_status st = recon_extract(img, &opt, &r, err, len);
    if (st == RECON_OK) {
        cr_assert_gt(r.n_polyline, 2);
        for (int k = 0; k < r.n_polyline; k++)
            cr_assert(isfinite(r.polyline[k].x) && isfinite(r.polyline[k].y));
    } else {
        cr_assert_null(r.mask, "a refused image leaves no result arrays");
        cr_assert_gt(strlen(err), 0, "a refusal says why");
    }
    recon_result_free(&r);
    return st;
}

static image_t uniform(int w, int h, float v)
{
    image_t img = image_alloc(w, h, 3);
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        img.data[i] = v;
    return img;
}

Test(recon_errors, size_limits)
{
    char err[256];
    image_t img = uniform(31, 100, 1);
    cr_expect_eq(run(&img, err, sizeof err), RECON_ERR_SIZE);
    cr_expect(strstr(err, "31x100") != NULL, "%s", err);
    image_free(&img);
    /* Over 100 megapixels: refused before any pixel is read. */
    float dummy[3] = {0};
    image_t big = {20000, 6000, 3, 8, 0, dummy};
    cr_expect_eq(run(&big, err, sizeof err), RECON_ERR_SIZE);
    image_t none = {64, 64, 3, 8, 0, NULL};
    cr_expect_eq(run(&none, err, sizeof err), RECON_ERR_SIZE);
}

Test(recon_errors, no_object)
{
    char err[256];
    image_t img = uniform(64, 64, 0.9f);
    cr_expect_eq(run(&img, err, sizeof err), RECON_ERR_NO_OBJECT);
    for (int i = 0; i < 64 * 64 * 3; i++) /* all foreground is no object against nothing */
        img.data[i] = 0.1f;
    cr_expect_eq(run(&img, err, sizeof err), RECON_ERR_NO_OBJECT);
    image_free(&img);
}

/* A vessel cut by the bottom border is reconstructed, and the contact is
 * reported for the quality gate (which refuses it: test_recon_hard.c). */
Test(recon_errors, border_contact_is_reported)
{
    char err[256];
    synth_params p = synth_defaults(SYNTH_VASE, 200, 240);
    p.base_center.y = 250; /* base below the image */
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    recon_options opt = {-1, RECON_SIDE_AUTO, NULL};
    recon_result r;
    cr_assert_eq(recon_extract(&img, &opt, &r, err, sizeof err), RECON_OK, "%s", err);
    cr_expect_eq(r.border_contact, 2u, "border bits %#x: the bottom only", r.border_contact);
    recon_result_free(&r);
    p.base_center.y = 230; /* a margin of 10 px: no contact */
    image_free(&img);
    cr_assert_eq(synth_draw(&p, &img), 0);
    cr_assert_eq(recon_extract(&img, &opt, &r, err, sizeof err), RECON_OK, "%s", err);
    cr_expect_eq(r.border_contact, 0u, "border bits %#x with a margin", r.border_contact);
    recon_result_free(&r);
    image_free(&img);
}

Test(recon_errors, tiny_objects_do_not_crash)
{
    char err[256];
    image_t img = uniform(64, 64, 0.95f);
    img.data[(30 * 64 + 30) * 3] = img.data[(30 * 64 + 30) * 3 + 1] = img.data[(30 * 64 + 30) * 3 + 2] = 0;
    recon_status st = run(&img, err, sizeof err);
    cr_expect(st == RECON_ERR_SHAPE || st == RECON_ERR_NO_OBJECT, "1-px object: %d %s", st, err);
    for (int x = 10; x < 50; x++) /* a one-pixel line */
        for (int c = 0; c < 3; c++)
            img.data[(40 * 64 + x) * 3 + c] = 0;
    st = run(&img, err, sizeof err);
    cr_expect_neq(st, RECON_ERR_INTERNAL);
    image_free(&img);
}

Test(recon_errors, noise_and_odd_channels_do_not_crash)
{
    char err[256];
    srand(7);
    image_t img = uniform(80, 90, 0);
    for (int i = 0; i < 80 * 90 * 3; i++)
        img.data[i] = (float)rand() / RAND_MAX;
    cr_expect_neq(run(&img, err, sizeof err), RECON_ERR_INTERNAL);
    image_free(&img);
    /* gray + alpha, opaque everywhere: alpha is ignored, gray is used */
    synth_params p = synth_defaults(SYNTH_JAR, 100, 120);
    image_t rgb;
    cr_assert_eq(synth_draw(&p, &rgb), 0);
    image_t ga = image_alloc(100, 120, 2);
    ga.has_alpha = 1;
    for (int i = 0; i < 100 * 120; i++) {
        ga.data[2 * i] = rgb.data[3 * i + 1];
        ga.data[2 * i + 1] = 1;
    }
    cr_expect_eq(run(&ga, err, sizeof err), RECON_OK, "%s", err);
    image_free(&ga);
    image_free(&rgb);
}

Test(recon_errors, reports_dropped_objects_and_holes)
{
    synth_params p = synth_defaults(SYNTH_JAR, 200, 240);
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    /* a speck away from the vessel and a background-coloured hole inside it */
    for (int y = 10; y < 14; y++)
        for (int x = 10; x < 14; x++)
            for (int c = 0; c < 3; c++)
                img.data[(y * 200 + x) * 3 + c] = 0.1f;
    for (int y = 110; y < 126; y++)
        for (int x = 92; x < 108; x++)
            for (int c = 0; c < 3; c++)
                img.data[(y * 200 + x) * 3 + c] = p.bg[c];
    recon_options opt = {-1, RECON_SIDE_AUTO, NULL};
    recon_result r;
    char err[256];
    cr_assert_eq(recon_extract(&img, &opt, &r, err, sizeof err), RECON_OK, "%s", err);
    cr_expect_eq(r.dropped_objects, 1);
    cr_expect_eq(r.mask[118 * 200 + 100], 1, "the hole is filled");
    cr_expect_eq(r.mask[12 * 200 + 12], 0, "the speck is dropped");
    recon_result_free(&r);
    image_free(&img);
}

Test(recon_errors, forced_threshold_and_polarity)
{
    synth_params p = synth_defaults(SYNTH_VASE, 200, 260);
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    recon_options opt = {128, RECON_SIDE_AUTO, NULL};
    recon_result r;
    char err[256];
    cr_assert_eq(recon_extract(&img, &opt, &r, err, sizeof err), RECON_OK, "%s", err);
    cr_expect_eq(r.mask_mode, RECON_MASK_GRAY_BELOW);
    cr_expect_eq(r.threshold_used, 128);
    recon_result_free(&r);
    /* Inverted photo: the vessel is now lighter than the backdrop. */
    for (int i = 0; i < 200 * 260 * 3; i++)
        img.data[i] = 1 - img.data[i];
    cr_assert_eq(recon_extract(&img, &opt, &r, err, sizeof err), RECON_OK, "%s", err);
    cr_expect_eq(r.mask_mode, RECON_MASK_GRAY_ABOVE);
    recon_result_free(&r);
    image_free(&img);
}

Test(recon_errors, nan_pixels_and_transparent_images)
{
    char err[256];
    synth_params p = synth_defaults(SYNTH_VASE, 120, 160);
    image_t img;
    cr_assert_eq(synth_draw(&p, &img), 0);
    for (int i = 0; i < 120 * 160 * 3; i += 97)
        img.data[i] = i % 2 ? NAN : INFINITY;
    cr_expect_neq(run(&img, err, sizeof err), RECON_ERR_INTERNAL);
    image_free(&img);
    /* RGBA, everything transparent: nothing to reconstruct. */
    image_t clear = image_alloc(64, 64, 4);
    clear.has_alpha = 1;
    cr_expect_eq(run(&clear, err, sizeof err), RECON_ERR_NO_OBJECT);
    image_free(&clear);
}
