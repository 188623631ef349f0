/* The reconstruction on the real museum photographs of ../shared/data/real-dev
 * (17 photos from The Met, no ground truth; skipped without the folder). The
 * yardstick of docs/algorithms-recon.md,
 * "Accuracy": at least 14 of the 17 pass the quality gate (16 with the
 * learned object prior, which the default segmenter, auto, runs on the
 * photos the classical segmentation leaves refused), the median
 * left/right disagreement of those is at most 1% of the largest radius, and
 * every result that passes is a profile the renderer builds (r >= 0, a valid
 * surface of revolution) from its shape (profile_shape: the meridian when
 * the camera gave one). Against the hand-checked truth masks
 * (tests/support/realdev_truth.h): every photo that passes lies on the true
 * outline (none accepted wrong; issue 25), as many as measured
 * (docs/gallery-real.md). */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_statistics_double.h>

#include "celadon/reconstruct.h"
#include "celadon/sor.h"
#include "prior/prior.h"
#include "support/realdev_truth.h"
#include "support/test_build.h"

static int is_jpeg(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return n > 4 && strcmp(e->d_name + n - 4, ".jpg") == 0;
}

Test(recon_realdev, most_real_photos_pass_and_build, .timeout = 1800)
{
    const char *shared = getenv("CELADON_SHARED");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/data/real-dev", shared && *shared ? shared : "../shared");
    struct dirent **list;
    int n = scandir(dir, &list, is_jpeg, alphasort);
    if (n <= 0)
        cr_skip_test("real-dev photos not found at %s (set CELADON_SHARED)", dir);
    double *lr = calloc((size_t)n, sizeof *lr);
    cr_assert_not_null(lr);
    /* The sanitized build reconstructs every other photo for its checks;
     * the counts and the median are the optimised build's (every photo). */
    int passed = 0, on_outline = 0, step = test_build_case_step(2);
    for (int i = 0; i < n; i++) {
        if (i % step) {
            free(list[i]);
            continue;
        }
        char path[2048], err[512];
        snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name);
        reconstruct_options opt = reconstruct_options_default();
        reconstruction r;
        int st = reconstruct_photo(path, &opt, &r, err, sizeof err);
        cr_log_info("%-50s %s%s%s", list[i]->d_name, st == 0 ? "passed" : err,
                    st != 0 ? "" : reconstruction_is_perspective(&r) ? ", perspective camera" : ", orthographic",
                    r.used_prior ? ", with the object prior" : "");
        realdev_truth t;
        if (st == 0 && realdev_truth_load(path, &t) == 0) {
            double off = realdev_truth_outline(&t, &r.extract), over = realdev_truth_overreach(&t, &r.extract);
            int on = realdev_truth_on_outline(&t, &r.extract);
            cr_log_info("%-50s mask IoU %.4f, outline %.2f%%, beyond the body %.2f%% of its height",
                        list[i]->d_name, realdev_truth_iou(&t, r.extract.mask), 100 * off, 100 * over);
            if (!on)
                cr_log_info("%s passes off the true outline", list[i]->d_name);
            on_outline += on;
            realdev_truth_free(&t);
        }
        /* the not-a-vessel rule never refuses a vessel */
        cr_expect(st == 0 || !strstr(err, "not a vessel"), "%s: %s", list[i]->d_name, err);
        if (st == 0) {
            lr[passed++] = r.quality.lr_disagreement;
            profile_t p;
            reconstruction_profile(&r, path, &p);
            const double *domains;
            int n_domains;
            const bspline_t *shape = profile_shape(&p, &domains, &n_domains);
            /* The 3D profile is as wide as the outline says, within what a
             * camera's view changes (the meridian of a fit that blew up
             * reached 13 heights out on the high-view pyxis) */
            double wide = bspline_largest(shape, 0) / bspline_largest(shape, 1);
            double outline = bspline_largest(&r.curve, 0) / bspline_largest(&r.curve, 1);
            cr_expect_leq(wide, 1.5 * outline, "%s: the profile reaches %.2f heights from the axis, its outline %.2f",
                          list[i]->d_name, wide, outline);
            sor_t *s = sor_create(shape, 1.0, SOR_CAPS_ALL, err, sizeof err);
            cr_expect_not_null(s, "%s: the renderer cannot build the profile: %s", list[i]->d_name, err);
            sor_destroy(s);
        }
        reconstruction_free(&r);
        free(list[i]);
    }
    free(list);
    double median = passed ? gsl_stats_median(lr, 1, (size_t)passed) : NAN;
    cr_log_info("%d of %d pass, %d of them on the true outline; median left/right disagreement %.2f%%", passed, n,
                on_outline, 100 * median);
    if (step > 1) {
        free(lr);
        return;
    }
    int want = object_prior_available() ? 16 : 14;
    cr_expect_geq(passed, want, "only %d of %d real photos pass the quality gate", passed, n);
    cr_expect_leq(median, 0.01, "median left/right disagreement %.2f%% of the largest radius", 100 * median);
    /* measured (docs/gallery-real.md): every photo that passes lies on the
     * true outline (the Sevres vase's plinth, revolved into its foot before
     * the plinth hypothesis of support.c, is cut off); without the prior the
     * glass beaker and the two-handled jar are refused */
    int want_on = object_prior_available() ? 16 : 14;
    cr_expect_geq(on_outline, want_on, "only %d of the passing photos lie on the true outline", on_outline);
    cr_expect_eq(on_outline, passed, "%d photos pass off the true outline (accepted wrong)", passed - on_outline);
    free(lr);
}
