/* Denoiser benchmark (docs/BENCHMARKS.md, "Denoising"): on scenes studio,
 * cornell-sor and showcase at 320x180, the relative MSE against a
 * 4096-spp reference of the raw 16-spp render, of the same render through
 * `celadon denoise`, and of the raw 128-spp render; over a window of the
 * film holding the vessels (the reference renders that crop only), and
 * over the pixels along the vessels' silhouettes, found from the exact
 * coverage of each pixel by the SOR shapes (16x16 camera rays per pixel
 * through scene_first_hit, passing glass sheets). The 16- and 128-spp
 * renders take the zsobol sampler: studio's and cornell-sor's ldsampler
 * rounds its count up to a power of 4 and would render 256 for 128.
 *
 * Renders are cached in build/bench-denoise/ (delete it to render them
 * again); the references run at nice 10, one at a time (about 10 minutes
 * each on a quiet 2-core machine). Writes docs/img/denoise-SCENE.png: the
 * window as raw 16 spp | denoised | raw 128 spp | reference.
 *
 *   bench_denoise [SCENE...]   (from the repository root; default: all three;
 *                               CELADON_BIN names the CLI, default build/celadon) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "celadon/film.h"
#include "celadon/image.h"
#include "celadon/scene.h"
#include "render/exr_read.h"

enum { WIDTH = 320, HEIGHT = 180, SPP_LOW = 16, SPP_HIGH = 128, SPP_REF = 4096, REF_SEED = 4096, COVER_N = 16 };
#define CACHE "build/bench-denoise"

typedef struct {
    const char *name;
    int crop[4]; /* x, y, w, h: the window of the film the reference renders */
} bench_scene;

static const bench_scene scenes[] = {
    {"studio", {80, 50, 160, 90}}, {"cornell-sor", {90, 85, 160, 90}}, {"showcase", {0, 50, 320, 50}}};

/* relMSE's epsilon (Rousselle et al. 2011): (x - r)^2 / (r^2 + 0.01). */
static const double REL_EPS = 0.01;

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Runs the command; exits on failure. */
static void run(const char *cmd)
{
    fprintf(stderr, "bench_denoise: %s\n", cmd);
    if (system(cmd) != 0) {
        fprintf(stderr, "bench_denoise: failed: %s\n", cmd);
        exit(1);
    }
}

/* The RGB (and with var, the variance) of an EXR: malloc'd, w * h * 3. */
static float *read_rgb(const char *path, int *w, int *h, float **var)
{
    char err[1024];
    exr_in *e = exr_in_open(path, err, sizeof err);
    if (!e) {
        fprintf(stderr, "bench_denoise: %s\n", err);
        exit(1);
    }
    exr_in_size(e, w, h);
    static const char *const rgb[3] = {"R", "G", "B"}, *const v[1] = {"variance.X"};
    float *px = malloc(sizeof *px * (size_t)*w * *h * 3);
    if (!px || exr_in_read(e, 3, rgb, px, err, sizeof err) != 0) {
        fprintf(stderr, "bench_denoise: %s\n", err);
        exit(1);
    }
    if (var) {
        *var = malloc(sizeof **var * (size_t)*w * *h);
        if (!*var || exr_in_read(e, 1, v, *var, err, sizeof err) != 0) {
            fprintf(stderr, "bench_denoise: %s\n", err);
            exit(1);
        }
    }
    exr_in_close(e);
    return px;
}

/* Each pixel's covered fraction by the scene's SORs (COVER_N^2 stratified
 * camera rays; a glass sheet in front is passed through), over the window. */
static double *sor_coverage(const char *scene_path, const int *crop)
{
    scene_options so = scene_options_default();
    so.width = WIDTH, so.height = HEIGHT, so.spp = 1;
    char err[2048];
    scene_t *s = scene_create_from_file(scene_path, NULL, 0, &so, err, sizeof err);
    if (!s) {
        fprintf(stderr, "bench_denoise: %s\n", err);
        exit(1);
    }
    int cw = crop[2], ch = crop[3];
    double *cov = calloc((size_t)cw * ch, sizeof *cov);
    if (!cov)
        abort();
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < ch; y++)
        for (int x = 0; x < cw; x++) {
            int hits = 0;
            for (int k = 0; k < COVER_N * COVER_N; k++) {
                double tmin, tmax;
                ray3 r = scene_camera_ray(s, crop[0] + x, crop[1] + y, (k % COVER_N + 0.5) / COVER_N,
                                          (k / COVER_N + 0.5) / COVER_N, &tmin, &tmax);
                scene_hit hit;
                while (scene_first_hit(s, &r, tmin, tmax, &hit) && hit.sheet)
                    tmin = hit.t + hit.eps;
                hits += scene_first_hit(s, &r, tmin, tmax, &hit) && !strcmp(hit.shape_type, "sor");
            }
            cov[(size_t)y * cw + x] = (double)hits / (COVER_N * COVER_N);
        }
    scene_destroy(s);
    return cov;
}

/* The silhouette band: pixels within one pixel of one partly covered. */
static unsigned char *silhouette_band(const double *cov, int w, int h, int *count)
{
    unsigned char *band = calloc((size_t)w * h, 1);
    if (!band)
        abort();
    *count = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int near = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < w && yy < h) {
                        double c = cov[(size_t)yy * w + xx];
                        near |= c > 0 && c < 1;
                    }
                }
            band[(size_t)y * w + x] = (unsigned char)near;
            *count += near;
        }
    return band;
}

/* relMSE of the full-film image img over the window against ref (the
 * window's own pixels), over the pixels where mask is set (NULL: all). */
static double rel_mse(const float *img, const float *ref, const int *crop, const unsigned char *mask)
{
    double sum = 0;
    long n = 0;
    for (int y = 0; y < crop[3]; y++)
        for (int x = 0; x < crop[2]; x++) {
            size_t q = (size_t)y * crop[2] + x, p = (size_t)(crop[1] + y) * WIDTH + crop[0] + x;
            if (mask && !mask[q])
                continue;
            for (int c = 0; c < 3; c++) {
                double r = ref[q * 3 + c], e = img[p * 3 + c] - r;
                sum += e * e / (r * r + REL_EPS);
            }
            n += 3;
        }
    return n ? sum / n : 0.0;
}

/* The reference's own noise in the same measure: its variance (of the
 * luminance estimate, taken for each channel) over r^2 + eps. */
static double ref_noise(const float *ref, const float *var, const int *crop)
{
    double sum = 0;
    size_t n = (size_t)crop[2] * crop[3];
    for (size_t q = 0; q < n; q++)
        for (int c = 0; c < 3; c++)
            sum += var[q] / ((double)ref[q * 3 + c] * ref[q * 3 + c] + REL_EPS);
    return sum / (3.0 * n);
}

/* The window of each image side by side (the reference is the window
 * already), sRGB 8-bit, into path. */
static void write_strip(const char *path, const float *const *imgs, int nimg, const int *crop)
{
    int w = crop[2], h = crop[3], sw = w * nimg;
    uint8_t *px = malloc((size_t)sw * h * 3);
    if (!px)
        abort();
    for (int i = 0; i < nimg; i++)
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int c = 0; c < 3; c++) {
                    int full = i < nimg - 1;
                    size_t src = full ? ((size_t)(crop[1] + y) * WIDTH + crop[0] + x) * 3 + c : ((size_t)y * w + x) * 3 + c;
                    px[((size_t)y * sw + i * w + x) * 3 + c] = film_srgb8(imgs[i][src]);
                }
    char err[1024];
    if (image_write_u8(path, sw, h, 3, px, err, sizeof err) != 0)
        fprintf(stderr, "bench_denoise: %s\n", err);
    free(px);
}

/* Whether scene is among the names (none: every scene is). */
static int wanted(const char *scene, int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], scene))
            return 1;
    return argc < 2;
}

int main(int argc, char **argv)
{
    const char *bin = getenv("CELADON_BIN") ? getenv("CELADON_BIN") : "build/celadon";
    mkdir("build", 0777);
    mkdir(CACHE, 0777);
    printf("Denoising: relMSE against %d spp over the window (all) and the SOR silhouette band (edge), %dx%d\n",
           SPP_REF, WIDTH, HEIGHT);
    printf("| scene | window | band px | raw %d all | denoised %d all | raw %d all | raw %d edge | denoised %d edge "
           "| raw %d edge | ref noise | denoise s |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
           SPP_LOW, SPP_LOW, SPP_HIGH, SPP_LOW, SPP_LOW, SPP_HIGH);
    int failures = 0, measured = 0;
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        const bench_scene *sc = &scenes[i];
        const int *cr = sc->crop;
        if (!wanted(sc->name, argc, argv))
            continue;
        char scene[256], ref[256], low[256], high[256], den[256], cmd[2048];
        snprintf(scene, sizeof scene, "scenes/%s/scene.xml", sc->name);
        snprintf(ref, sizeof ref, CACHE "/%s-ref.exr", sc->name);
        snprintf(low, sizeof low, CACHE "/%s-%d.exr", sc->name, SPP_LOW);
        snprintf(high, sizeof high, CACHE "/%s-%d.exr", sc->name, SPP_HIGH);
        snprintf(den, sizeof den, CACHE "/%s-%d-denoised.exr", sc->name, SPP_LOW);
        if (!exists(ref)) {
            snprintf(cmd, sizeof cmd, "nice -n 10 %s render %s -o %s --spp %d --res %dx%d --crop %d,%d,%d,%d --seed %d "
                     "--aov variance", bin, scene, ref, SPP_REF, WIDTH, HEIGHT, cr[0], cr[1], cr[2], cr[3], REF_SEED);
            run(cmd);
        }
        if (!exists(low)) {
            snprintf(cmd, sizeof cmd, "%s render %s -o %s --spp %d --res %dx%d --sampler zsobol "
                     "--aov denoising,half,specular,variance", bin, scene, low, SPP_LOW, WIDTH, HEIGHT);
            run(cmd);
        }
        if (!exists(high)) {
            snprintf(cmd, sizeof cmd, "%s render %s -o %s --spp %d --res %dx%d --sampler zsobol", bin, scene, high,
                     SPP_HIGH, WIDTH, HEIGHT);
            run(cmd);
        }
        snprintf(cmd, sizeof cmd, "%s denoise %s -o %s", bin, low, den);
        double t0 = wall_seconds();
        run(cmd);
        double dt = wall_seconds() - t0;
        int w, h, rw, rh;
        float *rvar, *r = read_rgb(ref, &rw, &rh, &rvar), *a = read_rgb(low, &w, &h, NULL),
                     *d = read_rgb(den, &w, &h, NULL), *b = read_rgb(high, &w, &h, NULL);
        if (rw != cr[2] || rh != cr[3] || w != WIDTH || h != HEIGHT) {
            fprintf(stderr, "bench_denoise: %s: sizes differ from the benchmark's (delete " CACHE ")\n", sc->name);
            return 1;
        }
        double *cov = sor_coverage(scene, cr);
        int nband;
        unsigned char *band = silhouette_band(cov, cr[2], cr[3], &nband);
        double all[3] = {rel_mse(a, r, cr, NULL), rel_mse(d, r, cr, NULL), rel_mse(b, r, cr, NULL)};
        double edge[3] = {rel_mse(a, r, cr, band), rel_mse(d, r, cr, band), rel_mse(b, r, cr, band)};
        printf("| %s | %d,%d,%d,%d | %d | %.6f | %.6f | %.6f | %.6f | %.6f | %.6f | %.6f | %.1f |\n", sc->name, cr[0],
               cr[1], cr[2], cr[3], nband, all[0], all[1], all[2], edge[0], edge[1], edge[2], ref_noise(r, rvar, cr), dt);
        measured++;
        if (!(all[1] < all[2]))
            failures++;
        char png[256];
        snprintf(png, sizeof png, "docs/img/denoise-%s.png", sc->name);
        const float *strip[4] = {a, d, b, r};
        write_strip(png, strip, 4, cr);
        free(r), free(rvar), free(a), free(d), free(b), free(cov), free(band);
    }
    printf("denoised %d spp below raw %d spp (window relMSE): %d of %d scenes\n", SPP_LOW, SPP_HIGH, measured - failures,
           measured);
    return 0;
}
