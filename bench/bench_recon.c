/* Reconstruction benchmark: per-stage timings (median of repeated runs) on a
 * drawn 900x1200 catalogue-like photo, meshes of 90k to 400k faces, and the
 * batch throughput of `celadon reconstruct` on 32 photos in one call.
 * Run by `make bench`; docs/BENCHMARKS.md ("Reconstruction") explains it.
 * The photo and its cleaned mask are also written to out/bench/ so that
 * bench/opencv_recon.py times OpenCV on the very same pixels. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#include "../tests/support/synth_vessel.h"
#include "celadon/mesh.h"
#include "celadon/overlay.h"
#include "core/core.h"
#include "celadon/reconstruct.h"
#include "recon/recon_internal.h"

#define REPS 21

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* CPU time of the calling thread, s: unlike wall time, it does not count the
 * time other processes hold the (shared) cores. */
static double thread_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Times `body` REPS times (after one warm-up run) and prints the medians of
 * wall time and thread CPU time in ms. */
#define TIME_STAGE(label, reps, setup, body)                                                                           \
    do {                                                                                                               \
        double t_[REPS], c_[REPS];                                                                                     \
        for (int r_ = -1; r_ < (reps); r_++) {                                                                        \
            setup;                                                                                                     \
            double t0_ = now_seconds(), c0_ = thread_cpu_seconds();                                                    \
            body;                                                                                                      \
            if (r_ >= 0) {                                                                                             \
                t_[r_] = 1e3 * (now_seconds() - t0_);                                                                  \
                c_[r_] = 1e3 * (thread_cpu_seconds() - c0_);                                                           \
            }                                                                                                          \
        }                                                                                                              \
        printf("  %-40s %9.3f %9.3f\n", label, median(t_, (reps)), median(c_, (reps)));                               \
    } while (0)

static void die(const char *what)
{
    fprintf(stderr, "bench_recon: %s\n", what);
    exit(1);
}

int main(int argc, char **argv)
{
    /* --stages: the per-stage table only (no meshes, no batch). */
    const int stages_only = argc > 1 && strcmp(argv[1], "--stages") == 0;
    const char *cli = getenv("CELADON_BIN") ? getenv("CELADON_BIN") : "build/celadon";
    char err[512];
    mkdir("out", 0777);
    mkdir("out/bench", 0777);
    const char *photo = "out/bench/bench_recon_photo.png";

    synth_params p = synth_defaults(SYNTH_VASE, 900, 1200);
    p.tilt_deg = 1.0;
    p.textured = 1; /* the drawer's default colours */
    image_t drawn;
    if (synth_draw(&p, &drawn) != 0 || synth_write(photo, &drawn, 8, err, sizeof err) != 0)
        die("cannot draw the photo");
    image_free(&drawn);

    printf("reconstruction stages, 900x1200 drawn vase (%s), median of %d runs\n", photo, REPS);
    printf("  %-40s %9s %9s\n", "stage", "wall ms", "CPU ms");
    image_t img = {0};
    TIME_STAGE("decode (PNG, OpenImageIO)", REPS, image_free(&img), if (image_read(photo, &img, err, sizeof err))
                                                                          die(err));
    int w = img.width, h = img.height;
    size_t npx = (size_t)w * h;
    float *gray = malloc(npx * sizeof(float)), *tmp = malloc(npx * sizeof(float));
    float *blur = malloc(npx * sizeof(float)), *resp = malloc(npx * sizeof(float));
    uint8_t *mask = malloc(npx);
    if (!gray || !tmp || !blur || !resp || !mask)
        die("out of memory");
    int thr, dropped, holes;
    uint8_t *mask0 = malloc(npx);
    if (!mask0)
        die("out of memory");
    TIME_STAGE("  threshold (gray, background, Otsu)", REPS, , recon_mask_threshold(&img, -1, gray, mask0, &thr));
    TIME_STAGE("  largest object, holes, rows", REPS, memcpy(mask, mask0, npx),
               recon_mask_clean(mask, w, h, &dropped, &holes));
    TIME_STAGE("  closing 9x9", REPS, , recon_mask_close(mask, w, h, 4));
    free(mask0);
    TIME_STAGE("mask (threshold, clean, close, clean)", REPS, , {
        recon_mask_threshold(&img, -1, gray, mask, &thr);
        recon_mask_clean(mask, w, h, &dropped, &holes);
        recon_mask_close(mask, w, h, 4);
        recon_mask_clean(mask, w, h, &dropped, &holes);
    });
    /* The cleaned mask, for the OpenCV reference (bench/opencv_recon.py). */
    uint8_t *mask8 = malloc(npx);
    if (!mask8)
        die("out of memory");
    for (size_t i = 0; i < npx; i++)
        mask8[i] = mask[i] ? 255 : 0;
    if (image_write_u8("out/bench/bench_recon_mask.png", w, h, 1, mask8, err, sizeof err) != 0)
        die(err);
    free(mask8);
    recon_border_set bs = {0};
    TIME_STAGE("contour (Suzuki-Abe)", REPS, recon_border_set_free(&bs), recon_border_follow(mask, w, h, &bs));
    const recon_border *ob = &bs.borders[0];
    int nc = ob->count;
    vec2 *contour = malloc((size_t)nc * sizeof *contour);
    int *keep = malloc((size_t)nc * sizeof *keep);
    if (!contour || !keep)
        die("out of memory");
    for (int i = 0; i < nc; i++)
        contour[i] = v2(bs.points[2 * (ob->start + i)] + 0.5, bs.points[2 * (ob->start + i) + 1] + 0.5);
    int n_approx = 0;
    TIME_STAGE("Douglas-Peucker (eps 1 px)", REPS, , n_approx = recon_douglas_peucker_closed(contour, nc, 1.0, keep));
    /* Full-image filters on the mask (as OpenCV's GaussianBlur and
     * goodFeaturesToTrack would run); recon itself only filters windows. */
    TIME_STAGE("Gaussian 7x7, full image", REPS, for (size_t i = 0; i < npx; i++) blur[i] = mask[i],
               recon_gaussian7(blur, tmp, w, h));
    TIME_STAGE("Shi-Tomasi response, full image", REPS, , if (recon_shi_tomasi(blur, w, h, resp)) die("out of memory"));
    vec2 mean, axes[2];
    double eig[2];
    TIME_STAGE("PCA of the contour", REPS, , recon_pca(contour, nc, &mean, axes, eig));
    vec2 up = fabs(axes[0].y) >= fabs(axes[1].y) ? axes[0] : axes[1];
    if (up.y > 0)
        up = v2_scale(up, -1);
    int cidx[CORNER_COUNT];
    TIME_STAGE("corners (windowed Gaussian+Shi-Tomasi)", REPS, ,
               recon_find_corners(contour, nc, keep, n_approx, mean, up, cidx));
    /* The outermost object pixel of each row and side, where the sub-pixel search starts. */
    int *ext = malloc(2 * (size_t)h * sizeof *ext);
    if (!ext)
        die("out of memory");
    for (int j = 0; j < h; j++) {
        ext[j] = ext[h + j] = -1;
        for (int i = 0; i < w; i++)
            if (mask[(size_t)j * w + i]) {
                if (ext[j] < 0)
                    ext[j] = i;
                ext[h + j] = i;
            }
    }
    double delta = fmax(0.5 * thr, 3.0) / 255;
    TIME_STAGE("sub-pixel silhouette, both sides", REPS, , {
        for (int j = 0; j < h; j++)
            for (int s = 0; s < 2; s++)
                if (ext[s * h + j] >= 0)
                    recon_subpixel_edge(&(recon_signal){gray + (size_t)j * w, w, 1}, ext[s * h + j], s ? 1 : -1, 0.0, delta);
    });
    free(ext);
    /* The whole pipeline as the CLI, the museum and the tests run it: its
     * own per-stage timings, median of REPS runs. */
    reconstruct_options ropt = reconstruct_options_default();
    reconstruction rec = {0};
    double st[7][REPS], cpu_all[REPS];
    static const char *st_name[7] = {"decode",          "image stages (recon_extract)", "B-spline fit (1 px)",
                                     "curvature domains (0.25 px, 0.25 deg)", "Hausdorff errors",
                                     "texture (scanline)", "total (up to the texture)"};
    for (int r = -1; r < REPS; r++) {
        reconstruction_free(&rec);
        double c0 = thread_cpu_seconds();
        if (reconstruct_photo(photo, &ropt, &rec, err, sizeof err) != 0)
            die(err);
        if (r < 0)
            continue;
        cpu_all[r] = 1e3 * (thread_cpu_seconds() - c0);
        const double v[7] = {rec.ms.decode, rec.ms.image, rec.ms.bspline, rec.ms.domains, rec.ms.hausdorff,
                             rec.ms.texture, rec.ms.total};
        for (int k = 0; k < 7; k++)
            st[k][r] = v[k];
    }
    printf("reconstruct_photo (the library pipeline), median of %d runs   wall ms\n", REPS);
    for (int k = 0; k < 7; k++)
        printf("  %-40s %9.3f\n", st_name[k], median(st[k], REPS));
    printf("  %-40s %9s %9.3f\n", "CPU, whole call", "", median(cpu_all, REPS));
    uint8_t *ov = NULL;
    TIME_STAGE("overlay", REPS, free(ov), ov = overlay_render(&rec.photo, &rec.extract, &rec.curve));
    const bspline_t curve = rec.curve;
    const double *u = rec.domains;
    const int nu = rec.n_domains;
    printf("  (%d contour points, %d polyline points, %d control points, %d domain boundaries,\n"
           "   Hausdorff %.3f / %.3f px, texture %dx%d)\n",
           nc, rec.extract.n_polyline, curve.n_ctrl, nu, rec.err_curve_to_polyline, rec.err_polyline_to_curve,
           rec.texture.width, rec.texture.height);

    if (stages_only)
        goto done;
    printf("meshes (mesh_revolve, base cap, %d rings)                 wall ms    CPU ms\n", nu);
    static const int targets[] = {90000, 200000, 400000};
    for (int k = 0; k < 3; k++) {
        int segments = (int)lround(targets[k] / (2.0 * (nu - 1) + 1.0));
        mesh_t m = {0};
        if (mesh_revolve(&curve, u, nu, 1.0, segments, MESH_CAP_BASE, &m))
            die("mesh failed");
        char label[96];
        snprintf(label, sizeof label, "%d segments, %d faces", segments, m.n_tris);
        TIME_STAGE(label, REPS, mesh_free(&m),
                   if (mesh_revolve(&curve, u, nu, 1.0, segments, MESH_CAP_BASE, &m)) die("mesh failed"));
        mesh_free(&m);
    }

    /* Batch: 32 copies of the photo in one call (dynamic OpenMP over photos). */
    enum { BATCH = 32 };
    char cmd[8192];
    int len = snprintf(cmd, sizeof cmd, "rm -rf out/bench/batch && %s reconstruct -o out/bench/batch", cli);
    for (int i = 0; i < BATCH; i++) {
        char name[64];
        snprintf(name, sizeof name, "out/bench/batch_in/p%02d.png", i);
        len += snprintf(cmd + len, sizeof cmd - (size_t)len, " %s", name);
    }
    len += snprintf(cmd + len, sizeof cmd - (size_t)len, " 2>/dev/null");
    mkdir("out/bench/batch_in", 0777);
    for (int i = 0; i < BATCH; i++) {
        char name[64], copy[128];
        snprintf(name, sizeof name, "out/bench/batch_in/p%02d.png", i);
        snprintf(copy, sizeof copy, "cp %s %s", photo, name);
        if (system(copy) != 0)
            die("cannot copy the photo");
    }
    double best = INFINITY, cpu = INFINITY;
    for (int r = 0; r < 2; r++) {
        struct rusage before, after;
        getrusage(RUSAGE_CHILDREN, &before);
        double t0 = now_seconds();
        if (system(cmd) != 0)
            die("the batch reconstruct failed (is build/celadon built?)");
        best = fmin(best, now_seconds() - t0);
        getrusage(RUSAGE_CHILDREN, &after);
        double used = (after.ru_utime.tv_sec - before.ru_utime.tv_sec) + (after.ru_stime.tv_sec - before.ru_stime.tv_sec) +
                      1e-6 * ((after.ru_utime.tv_usec - before.ru_utime.tv_usec) +
                              (after.ru_stime.tv_usec - before.ru_stime.tv_usec));
        cpu = fmin(cpu, used);
    }
    printf("batch: %d photos in one `celadon reconstruct` call (360 segments, all outputs), best of 2:\n"
           "  %.2f s wall, %.1f photos/s; %.0f ms CPU per photo (all threads)\n",
           BATCH, best, BATCH / best, 1e3 * cpu / BATCH);
    /* The batch's outputs are a quarter of a gigabyte: not worth keeping. */
    if (system("rm -rf out/bench/batch out/bench/batch_in") != 0)
        die("cannot remove out/bench/batch");
done:

    free(ov);
    reconstruction_free(&rec);
    free(contour);
    free(keep);
    recon_border_set_free(&bs);
    free(gray), free(tmp), free(blur), free(resp), free(mask);
    image_free(&img);
    return 0;
}
