/* The reconstruction on the real museum photographs of ../shared/data/real-dev
 * (17 photos from The Met, no ground truth; skipped without the folder). The
 * yardstick of docs/algorithms-recon.md,
 * "Accuracy": at least 14 of the 17 pass the quality gate (16 with the
 * learned object prior, which the default segmenter, auto, runs on the
 * photos the classical segmentation leaves refused), the median
 * left/right disagreement of those is at most 1% of the largest radius, and
 * every result that passes is a profile the renderer builds (r >= 0, a valid
 * surface of revolution) from its shape (profile_shape: the meridian when
 * the camera gave one). */
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
    int passed = 0;
    for (int i = 0; i < n; i++) {
        char path[2048], err[512];
        snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name);
        reconstruct_options opt = reconstruct_options_default();
        reconstruction r;
        int st = reconstruct_photo(path, &opt, &r, err, sizeof err);
        cr_log_info("%-50s %s%s%s", list[i]->d_name, st == 0 ? "passed" : err,
                    st != 0 ? "" : reconstruction_is_perspective(&r) ? ", perspective camera" : ", orthographic",
                    r.used_prior ? ", with the object prior" : "");
        /* the not-a-vessel rule never refuses a vessel */
        cr_expect(st == 0 || !strstr(err, "not a vessel"), "%s: %s", list[i]->d_name, err);
        if (st == 0) {
            lr[passed++] = r.quality.lr_disagreement;
            profile_t p;
            reconstruction_profile(&r, path, &p);
            const double *domains;
            int n_domains;
            sor_t *s = sor_create(profile_shape(&p, &domains, &n_domains), 1.0, SOR_CAPS_ALL, err, sizeof err);
            cr_expect_not_null(s, "%s: the renderer cannot build the profile: %s", list[i]->d_name, err);
            sor_destroy(s);
        }
        reconstruction_free(&r);
        free(list[i]);
    }
    free(list);
    double median = passed ? gsl_stats_median(lr, 1, (size_t)passed) : NAN;
    cr_log_info("%d of %d pass; median left/right disagreement %.2f%%", passed, n, 100 * median);
    int want = object_prior_available() ? 16 : 14;
    cr_expect_geq(passed, want, "only %d of %d real photos pass the quality gate", passed, n);
    cr_expect_leq(median, 0.01, "median left/right disagreement %.2f%% of the largest radius", 100 * median);
    free(lr);
}
