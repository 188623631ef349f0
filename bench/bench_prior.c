/* The learned object prior (src/prior/prior.h) on the dev photographs, one
 * photo at a time: the network's time per photo (wall and process CPU; the
 * network uses every core), and the reconstruction by each segmenter
 * (classic, learned, auto): quality gate, left/right disagreement, wall time,
 * and the mask's IoU against the classical one and, where a mask.png of the
 * truth lies beside the photo (synth-dev), against the truth. Photos: the
 * arguments, else every .jpg of ../shared/data/real-dev and
 * ../shared/data/synth-dev/CASE/photo.png (CELADON_SHARED moves ../shared).
 * Skipped without the network file (`make deps-model`) or the photos.
 * docs/BENCHMARKS.md ("Learned object prior") holds the figures. */
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celadon/reconstruct.h"
#include "prior/prior.h"

static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* IoU of two masks of n pixels (a: bytes 0/1; b: bytes, or floats > 0.5 when fb). */
static double iou(const uint8_t *a, const void *b, int fb, size_t n)
{
    size_t i_ = 0, u = 0;
    for (size_t p = 0; p < n; p++) {
        int x = a[p] != 0, y = fb ? ((const float *)b)[p] > 0.5f : ((const uint8_t *)b)[p] != 0;
        i_ += x && y;
        u += x || y;
    }
    return u ? (double)i_ / u : 1;
}

typedef struct {
    int status, passed, used_prior;
    double lr, seconds;
    uint8_t *mask; /* the full-resolution mask, when the image stages made one */
    size_t n;
} run_t;

static void run(const char *path, reconstruct_segmenter s, run_t *out)
{
    reconstruct_options opt = reconstruct_options_default();
    opt.segmenter = s;
    opt.force = 1;
    reconstruction r;
    char err[1024];
    double t0 = wall_s();
    out->status = reconstruct_photo(path, &opt, &r, err, sizeof err);
    out->seconds = wall_s() - t0;
    out->passed = out->status == 0 && r.quality.passed;
    out->used_prior = r.used_prior;
    out->lr = r.quality.lr_disagreement;
    out->n = (size_t)r.extract.width * r.extract.height;
    out->mask = NULL;
    if (r.extract.mask && (out->mask = malloc(out->n)))
        memcpy(out->mask, r.extract.mask, out->n);
    reconstruction_free(&r);
}

static const char *verdict(const run_t *r) { return r->status ? "refused" : r->passed ? "pass" : "gate"; }

/* The truth mask beside the photo (synth-dev's mask.png), as bytes; NULL when none. */
static uint8_t *truth_mask(const char *path, size_t n)
{
    char m[4096];
    const char *slash = strrchr(path, '/');
    snprintf(m, sizeof m, "%.*smask.png", slash ? (int)(slash - path + 1) : 0, path);
    image_t img;
    char err[256];
    if (image_read(m, &img, err, sizeof err) != 0)
        return NULL;
    uint8_t *out = NULL;
    if ((size_t)img.width * img.height == n && (out = malloc(n)))
        for (size_t p = 0; p < n; p++)
            out[p] = img.data[p * img.channels] > 0.5f;
    image_free(&img);
    return out;
}

static void bench_photo(const char *path, double *sum_prior, double *sum_cpu, double *sum_auto, double *sum_classic)
{
    image_t img;
    char err[512];
    if (image_read(path, &img, err, sizeof err) != 0) {
        fprintf(stderr, "bench_prior: %s: %s\n", path, err);
        return;
    }
    float *prob = malloc((size_t)img.width * img.height * sizeof *prob);
    double w0 = wall_s(), c0 = cpu_s();
    int rc = prob ? object_prior_compute(&img, prob, err, sizeof err) : -1;
    double prior_s = wall_s() - w0, prior_cpu = cpu_s() - c0;
    if (rc != 0) {
        fprintf(stderr, "bench_prior: %s: %s\n", path, rc > 0 ? "no network" : err);
        free(prob);
        image_free(&img);
        return;
    }
    run_t c, l, a;
    run(path, RECONSTRUCT_SEGMENTER_CLASSIC, &c);
    run(path, RECONSTRUCT_SEGMENTER_LEARNED, &l);
    run(path, RECONSTRUCT_SEGMENTER_AUTO, &a);
    size_t n = (size_t)img.width * img.height;
    uint8_t *truth = truth_mask(path, n);
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    char shown[80];
    if (!strcmp(name, "photo.png")) { /* synth-dev: the case's folder names it */
        int len = (int)(name - path) - 1, start = len;
        while (start > 0 && path[start - 1] != '/')
            start--;
        snprintf(shown, sizeof shown, "%.*s", len - start, path + start);
    } else {
        snprintf(shown, sizeof shown, "%s", name);
    }
    char iou_cl[16] = "-", iou_ct[16] = "-", iou_lt[16] = "-", iou_pt[16] = "-";
    if (c.mask && l.mask && c.n == n && l.n == n)
        snprintf(iou_cl, sizeof iou_cl, "%.4f", iou(c.mask, l.mask, 0, n));
    if (truth && c.mask && c.n == n)
        snprintf(iou_ct, sizeof iou_ct, "%.4f", iou(c.mask, truth, 0, n));
    if (truth && l.mask && l.n == n)
        snprintf(iou_lt, sizeof iou_lt, "%.4f", iou(l.mask, truth, 0, n));
    if (truth)
        snprintf(iou_pt, sizeof iou_pt, "%.4f", iou(truth, prob, 1, n));
    printf("| %s | %.2f / %.2f | %s %.2f%% %.1f s | %s %.2f%% %.1f s | %s%s %.2f%% %.1f s | %s | %s / %s / %s |\n",
           shown, prior_s, prior_cpu, verdict(&c), 100 * c.lr, c.seconds, verdict(&l), 100 * l.lr, l.seconds,
           verdict(&a), a.used_prior ? " (learned)" : "", 100 * a.lr, a.seconds, iou_cl, iou_ct, iou_lt, iou_pt);
    fflush(stdout);
    *sum_prior += prior_s;
    *sum_cpu += prior_cpu;
    *sum_auto += a.seconds;
    *sum_classic += c.seconds;
    free(c.mask);
    free(l.mask);
    free(a.mask);
    free(truth);
    free(prob);
    image_free(&img);
}

int main(int argc, char **argv)
{
    char path[4096];
    if (!object_prior_available()) {
        object_prior_model_path(path, sizeof path);
        printf("bench_prior: skipped: no network at %s (make deps-model)\n", path);
        return 0;
    }
    glob_t g = {0};
    if (argc < 2) {
        const char *shared = getenv("CELADON_SHARED");
        shared = shared && *shared ? shared : "../shared";
        snprintf(path, sizeof path, "%s/data/real-dev/*.jpg", shared);
        glob(path, 0, NULL, &g);
        snprintf(path, sizeof path, "%s/data/synth-dev/*/photo.png", shared);
        glob(path, g.gl_pathc ? GLOB_APPEND : 0, NULL, &g);
    }
    int n = argc >= 2 ? argc - 1 : (int)g.gl_pathc;
    if (n == 0) {
        printf("bench_prior: skipped: no photos (../shared/data/real-dev or synth-dev)\n");
        return 0;
    }
    /* the network's load, once per process, outside the per-photo figures */
    image_t tiny = image_alloc(64, 64, 3);
    float *p = malloc(64 * 64 * sizeof *p);
    double t0 = wall_s();
    char err[512];
    if (!tiny.data || !p || object_prior_compute(&tiny, p, err, sizeof err) != 0) {
        fprintf(stderr, "bench_prior: the network cannot run: %s\n", err);
        return 1;
    }
    object_prior_model_path(path, sizeof path);
    printf("network: %s, input %d x %d; load and first run %.2f s\n\n", path, OBJECT_PRIOR_SIDE, OBJECT_PRIOR_SIDE,
           wall_s() - t0);
    free(p);
    image_free(&tiny);
    printf("| photo | prior wall / CPU s | classic: gate L/R time | learned | auto | mask IoU classic-learned | "
           "IoU vs truth: classic / learned / network > 0.5 |\n|---|---|---|---|---|---|---|\n");
    double sp = 0, sc = 0, sa = 0, scl = 0;
    for (int i = 0; i < n; i++)
        bench_photo(argc >= 2 ? argv[i + 1] : g.gl_pathv[i], &sp, &sc, &sa, &scl);
    printf("\n%d photos: the network %.2f s wall (%.2f s CPU) per photo; batch per photo: classic %.2f s, auto %.2f s\n",
           n, sp / n, sc / n, scl / n, sa / n);
    globfree(&g);
    return 0;
}
