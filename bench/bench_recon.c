/* Reconstruction benchmark: the CPU time of each stage of the image pipeline
 * (segmentation steps, refinement, outline, axis, caps, parts), of the whole
 * recon_extract and of the whole reconstruct_photo, median of repeated runs,
 * on a drawn 900x1200 catalogue-like vase, on three drawn museum photos
 * (tests/support/synth_scene.h, 600x800) and, when the folders are there, on
 * the synth-dev and real-dev photos; then meshes of 90k to 400k faces and the batch
 * throughput of `celadon reconstruct` on 32 photos in one call.
 * Run by `make bench`; docs/BENCHMARKS.md ("Reconstruction") explains it.
 *
 *     build/bench/bench_recon [--stages] [REAL_DEV_DIR]
 *
 * --stages: the stage tables only (no meshes, no batch). REAL_DEV_DIR
 * defaults to $CELADON_SHARED/data/real-dev, else ../shared/data/real-dev;
 * the synth-dev photos are its sibling folder synth-dev (CASE/photo.png).
 * The vase and its vessel mask go to out/bench/ (bench_recon_{photo,mask}.png)
 * and the drawn museum photos to out/bench/NAME.png. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>

#include "../tests/support/synth_scene.h"
#include "../tests/support/synth_vessel.h"
#include "celadon/mesh.h"
#include "celadon/overlay.h"
#include "celadon/reconstruct.h"
#include "core/core.h"
#include "recon/recon_internal.h"

enum { REPS_DRAWN = 9, REPS_REAL = 3, MAX_REPS = 9, MAX_REAL = 64 };

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

/* CPU time of the process in ms: unlike wall time, it does not count the
 * time other processes hold the (shared) cores. */
static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return 1e3 * ts.tv_sec + 1e-6 * ts.tv_nsec;
}

static void die(const char *what)
{
    fprintf(stderr, "bench_recon: %s\n", what);
    exit(1);
}

/* ---- the stages */

typedef enum {
    ST_START,
    ST_MODELS,
    ST_DATA,
    ST_CUT,
    ST_SEGMENT,
    ST_SELECT,
    ST_SUPPORT,
    ST_REFINE,
    ST_CONTOUR,
    ST_EDGES,
    ST_AXIS,
    ST_CAPS,
    ST_PARTS,
    ST_EXTRACT,
    ST_PHOTO,
    ST_COUNT
} stage;

static const char *const STAGE_NAME[ST_COUNT] = {
    "downsample + backdrop fit",
    "GMM fits (3 rounds)",
    "data terms (3 rounds)",
    "min-cut (3 rounds)",
    "  segmentation, all",
    "object selection",
    "support hypotheses",
    "full-resolution refinement",
    "contour (Suzuki-Abe)",
    "sub-pixel edges, both sides",
    "axis symmetry",
    "caps",
    "parts",
    "recon_extract, whole",
    "reconstruct_photo, whole",
};

/* Times every stage once, in the order recon_extract runs them (the
 * segmentation's steps as recon_segment and segment_vessel in extract.c
 * call them; the later stages on recon_extract's own result). */
static void run_stages(const image_t *img, const char *path, double ms[ST_COUNT])
{
    char err[512];
    double t;
    memset(ms, 0, ST_COUNT * sizeof *ms);
    recon_segmentation seg;
    t = cpu_ms();
    if (recon_segment_start(img, NULL, &seg) != 0)
        die("segmentation failed");
    ms[ST_START] = cpu_ms() - t;
    for (int r = 0; r < 3; r++) {
        t = cpu_ms();
        if (recon_segment_models(&seg) != 0)
            die("no object in a benchmark photo");
        ms[ST_MODELS] += cpu_ms() - t;
        t = cpu_ms();
        recon_segment_data_terms(&seg);
        ms[ST_DATA] += cpu_ms() - t;
        t = cpu_ms();
        if (recon_segment_cut(&seg) != 0)
            die("out of memory");
        ms[ST_CUT] += cpu_ms() - t;
    }
    ms[ST_SEGMENT] = ms[ST_START] + ms[ST_MODELS] + ms[ST_DATA] + ms[ST_CUT];
    recon_excluded parts[RECON_MAX_EXCLUDED], stand;
    int n_parts = 0, dropped;
    char why[256];
    t = cpu_ms();
    if (recon_select_object(seg.object, seg.w, seg.h, &dropped, &stand, why, sizeof why) != RECON_OK)
        die(why);
    ms[ST_SELECT] = cpu_ms() - t;
    t = cpu_ms();
    seg.have_axis = recon_mask_axis(seg.object, seg.w, seg.h, &seg.axis_x0, &seg.axis_slope) == 0;
    if (recon_cut_support(&seg, seg.object, parts, RECON_MAX_EXCLUDED, &n_parts) != 0 ||
        recon_colour_model_prepare(&seg.model) != 0 ||
        recon_mask_axis(seg.object, seg.w, seg.h, &seg.axis_x0, &seg.axis_slope) != 0)
        die("support hypotheses failed");
    ms[ST_SUPPORT] = cpu_ms() - t;
    const int w = img->width, h = img->height;
    uint8_t *mask = malloc((size_t)w * h);
    if (!mask)
        die("out of memory");
    t = cpu_ms();
    if (recon_refine_mask(img, &seg, seg.object, mask) != 0)
        die("out of memory");
    ms[ST_REFINE] = cpu_ms() - t;
    recon_segmentation_free(&seg);

    recon_result res;
    t = cpu_ms();
    if (recon_extract(img, NULL, &res, err, sizeof err) != RECON_OK)
        die(err);
    ms[ST_EXTRACT] = cpu_ms() - t;
    recon_border_set bs = {0};
    t = cpu_ms();
    if (recon_border_follow(res.mask, w, h, &bs) != 0)
        die("out of memory");
    ms[ST_CONTOUR] = cpu_ms() - t;
    recon_border_set_free(&bs);
    /* The edge search on every row's outermost mask pixel on each side, on
     * the photo's colours (one channel for a gray photo). */
    const int ch = img->channels >= 3 ? 3 : 1;
    float *row = malloc((size_t)w * ch * sizeof *row);
    if (!row)
        die("out of memory");
    t = cpu_ms();
    for (int j = 0; j < h; j++) {
        const uint8_t *m = res.mask + (size_t)j * w, *a = memchr(m, 1, (size_t)w);
        if (!a)
            continue;
        const uint8_t *b = memrchr(m, 1, (size_t)w);
        for (int i = 0; i < w; i++)
            for (int c = 0; c < ch; c++) {
                float v = img->data[((size_t)j * w + i) * img->channels + c];
                row[(size_t)i * ch + c] = v > 0 ? (v < 1 ? v : 1) : 0;
            }
        recon_signal sig = {row, w, ch};
        recon_subpixel_edge(&sig, (int)(a - m), -1, 0.0, 0.02);
        recon_subpixel_edge(&sig, (int)(b - m), 1, 0.0, 0.02);
    }
    ms[ST_EDGES] = cpu_ms() - t;
    free(row);
    /* The axis from the mask's (as recon_extract starts), refined on the
     * result's outlines. */
    double x0, slope;
    if (recon_mask_axis(res.mask, w, h, &x0, &slope) != 0)
        die("no axis");
    vec2 o = v2(x0 + slope * h, h), d = v2_norm(v2(-slope, -1));
    int washed;
    t = cpu_ms();
    recon_symmetry_fit fit = {0, res.edge_noise_px[0], 0};
    recon_axis_symmetry(res.silhouette[0], res.n_silhouette[0], res.silhouette[1], res.n_silhouette[1], &o, &d,
                        0.05 * h, 0.95 * h, &fit, &washed);
    ms[ST_AXIS] = cpu_ms() - t;
    int base_is_cut = 0;
    for (int i = 0; i < res.n_excluded; i++)
        base_is_cut |= res.excluded[i].what == RECON_PART_STAND || res.excluded[i].what == RECON_PART_SHADOW;
    vec2 corners[CORNER_COUNT];
    t = cpu_ms();
    const vec2 *const outline[2] = {res.silhouette[0], res.silhouette[1]};
    if (recon_find_caps(res.contour, res.n_contour, outline, res.n_silhouette, res.axis_origin, res.axis_direction,
                        base_is_cut, corners) != 0)
        die("out of memory");
    ms[ST_CAPS] = cpu_ms() - t;
    /* The parts on the result's outlines (their gap flags are not kept:
     * no handle windows here). */
    vec2 ao = res.axis_origin, ad = res.axis_direction;
    double H = 0.5 * (v2_dot(v2_sub(res.corners[CORNER_RIM_LEFT], ao), ad) +
                      v2_dot(v2_sub(res.corners[CORNER_RIM_RIGHT], ao), ad));
    int s = res.side_used == RECON_SIDE_RIGHT;
    recon_outline_point *pts = malloc((size_t)2 * h * sizeof *pts);
    uint8_t *gap = calloc((size_t)h, 1);
    if (!pts || !gap)
        die("out of memory");
    int nm = recon_outline_points(res.silhouette[s], gap, res.n_silhouette[s], ao, ad, s ? 1 : -1, H, pts);
    int no = recon_outline_points(res.silhouette[1 - s], gap, res.n_silhouette[1 - s], ao, ad, s ? -1 : 1, H, pts + h);
    recon_excluded ex[RECON_MAX_EXCLUDED];
    int n_ex = 0;
    double dis, frac;
    t = cpu_ms();
    if (recon_resolve_parts(pts, nm, pts + h, no, s, fmax(2.0, 0.02 * res.r_max), ex, RECON_MAX_EXCLUDED, &n_ex, &dis,
                            &frac) != 0)
        die("out of memory");
    ms[ST_PARTS] = cpu_ms() - t;
    free(pts);
    free(gap);
    recon_result_free(&res);
    free(mask);

    reconstruct_options opt = reconstruct_options_default();
    opt.force = 1;
    reconstruction rec = {0};
    t = cpu_ms();
    if (reconstruct_photo(path, &opt, &rec, err, sizeof err) != 0)
        die(err);
    ms[ST_PHOTO] = cpu_ms() - t;
    reconstruction_free(&rec);
}

/* Medians over reps runs (after a warm-up run) into ms. */
static void time_stages(const image_t *img, const char *path, int reps, double ms[ST_COUNT])
{
    double all[ST_COUNT][MAX_REPS], one[ST_COUNT];
    run_stages(img, path, one);
    for (int r = 0; r < reps; r++) {
        run_stages(img, path, one);
        for (int k = 0; k < ST_COUNT; k++)
            all[k][r] = one[k];
    }
    for (int k = 0; k < ST_COUNT; k++)
        ms[k] = median(all[k], reps);
}

static void print_table(const char *title, int n_cols, char names[][40], double ms[][ST_COUNT])
{
    printf("%s\n  %-30s", title, "stage (CPU ms)");
    for (int c = 0; c < n_cols; c++)
        printf(" %17.17s", names[c]);
    printf("\n");
    for (int k = 0; k < ST_COUNT; k++) {
        printf("  %-30s", STAGE_NAME[k]);
        for (int c = 0; c < n_cols; c++)
            printf(" %17.2f", ms[c][k]);
        printf("\n");
    }
}

/* ---- the photos */

static const char *const MUSEUM_CASES[] = {"maebyeong_studio", "ewer_handle_spout", "lidded_jar"};
enum { N_DRAWN = 4 };

static void draw_photos(char paths[N_DRAWN][128], char names[N_DRAWN][40])
{
    char err[512];
    image_t img;
    synth_params p = synth_defaults(SYNTH_VASE, 900, 1200);
    p.tilt_deg = 1.0;
    p.textured = 1; /* the drawer's default colours */
    snprintf(paths[0], 128, "out/bench/bench_recon_photo.png");
    snprintf(names[0], 40, "vase 900x1200");
    if (synth_draw(&p, &img) != 0 || synth_write(paths[0], &img, 8, err, sizeof err) != 0)
        die("cannot draw the vase");
    image_free(&img);
    for (int i = 0; i < N_DRAWN - 1; i++) {
        synth_scene_params sp;
        snprintf(paths[i + 1], 128, "out/bench/%s.png", MUSEUM_CASES[i]);
        snprintf(names[i + 1], 40, "%s", MUSEUM_CASES[i]);
        if (synth_scene_case(MUSEUM_CASES[i], 600, 800, &sp) != 0 || synth_scene_draw(&sp, &img, NULL, NULL) != 0 ||
            synth_write(paths[i + 1], &img, 8, err, sizeof err) != 0)
            die("cannot draw a museum photo");
        image_free(&img);
    }
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* The real-dev photos (*.jpg, sorted), at most MAX_REAL; 0 without the folder. */
static int list_real(const char *dir, char paths[][1024])
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < MAX_REAL;)
        if (ends_with(e->d_name, ".jpg") && snprintf(paths[n], 1024, "%s/%s", dir, e->d_name) < 1024)
            n++;
    closedir(d);
    qsort(paths, (size_t)n, sizeof paths[0], (int (*)(const void *, const void *))strcmp);
    return n;
}

/* The synth-dev photos (each case's photo.png, sorted), at most MAX_REAL; 0
 * without the folder. */
static int list_synth(const char *dir, char paths[][1024])
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    struct stat st;
    for (struct dirent *e; (e = readdir(d)) && n < MAX_REAL;)
        if (e->d_name[0] != '.' && snprintf(paths[n], 1024, "%s/%s/photo.png", dir, e->d_name) < 1024 &&
            stat(paths[n], &st) == 0)
            n++;
    closedir(d);
    qsort(paths, (size_t)n, sizeof paths[0], (int (*)(const void *, const void *))strcmp);
    return n;
}

/* The decoded photo as reconstruct_photo decodes it (upright). */
static void read_photo(const char *path, image_t *img)
{
    char err[512];
    if (image_read(path, img, err, sizeof err) != 0)
        die(err);
}

static void mesh_and_batch(const char *photo, const char *cli);

/* The stage table of n photos of a folder (per stage the median and the
 * largest over the photos), then each photo's segmentation, recon_extract
 * and reconstruct_photo. */
static void time_folder(const char *what, const char *dir, char paths[][1024], int n)
{
    if (n == 0) {
        printf("%s photos: %s not found (or no photo in it): skipped\n", what, dir);
        return;
    }
    static double ms[MAX_REAL][ST_COUNT];
    double col[MAX_REAL], sum[2][ST_COUNT];
    for (int i = 0; i < n; i++) {
        image_t img;
        read_photo(paths[i], &img);
        time_stages(&img, paths[i], REPS_REAL, ms[i]);
        image_free(&img);
    }
    for (int k = 0; k < ST_COUNT; k++) {
        for (int i = 0; i < n; i++)
            col[i] = ms[i][k];
        sum[0][k] = median(col, n);
        sum[1][k] = col[n - 1]; /* sorted by median() */
    }
    char cols[2][40] = {"median of photos", "slowest photo"}, title[1200];
    snprintf(title, sizeof title, "reconstruction stages, %d %s photos (%s), median of %d runs each", n, what, dir,
             REPS_REAL);
    print_table(title, 2, cols, sum);
    printf("  per photo (CPU ms): %-43s %12s %12s %12s\n", "", "segment", "recon_extract", "photo");
    for (int i = 0; i < n; i++)
        printf("  %-63s %12.1f %12.1f %12.1f\n", paths[i] + strlen(dir) + 1, ms[i][ST_SEGMENT], ms[i][ST_EXTRACT],
               ms[i][ST_PHOTO]);
}

int main(int argc, char **argv)
{
    int stages_only = 0;
    const char *real_dir = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--stages") == 0)
            stages_only = 1;
        else
            real_dir = argv[i];
    }
    char real_default[512];
    if (!real_dir) {
        const char *shared = getenv("CELADON_SHARED") ? getenv("CELADON_SHARED") : "../shared";
        snprintf(real_default, sizeof real_default, "%s/data/real-dev", shared);
        real_dir = real_default;
    }
    const char *cli = getenv("CELADON_BIN") ? getenv("CELADON_BIN") : "build/celadon";
    mkdir("out", 0777);
    mkdir("out/bench", 0777);

    /* Drawn photos. */
    char paths[N_DRAWN][128], names[N_DRAWN][40];
    double ms[N_DRAWN][ST_COUNT];
    draw_photos(paths, names);
    for (int i = 0; i < N_DRAWN; i++) {
        image_t img;
        read_photo(paths[i], &img);
        time_stages(&img, paths[i], REPS_DRAWN, ms[i]);
        if (i == 0) { /* the vessel's mask, for bench/opencv_recon.py */
            char err[512];
            recon_result res;
            if (recon_extract(&img, NULL, &res, err, sizeof err) != RECON_OK)
                die(err);
            for (size_t p = 0; p < (size_t)img.width * img.height; p++)
                res.mask[p] = res.mask[p] ? 255 : 0;
            if (image_write_u8("out/bench/bench_recon_mask.png", img.width, img.height, 1, res.mask, err,
                               sizeof err) != 0)
                die(err);
            recon_result_free(&res);
        }
        image_free(&img);
    }
    char title[1024];
    snprintf(title, sizeof title, "reconstruction stages, drawn photos (out/bench/), median of %d runs", REPS_DRAWN);
    print_table(title, N_DRAWN, names, ms);

    /* The photos of synth-dev and real-dev, when there. */
    static char photos[MAX_REAL][1024];
    char synth_dir[1024];
    const char *slash = strrchr(real_dir, '/');
    snprintf(synth_dir, sizeof synth_dir, "%.*s%ssynth-dev", slash ? (int)(slash - real_dir) : 0, real_dir,
             slash ? "/" : "");
    time_folder("synth-dev", synth_dir, photos, list_synth(synth_dir, photos));
    time_folder("real", real_dir, photos, list_real(real_dir, photos));
    if (!stages_only)
        mesh_and_batch(paths[0], cli);
    return 0;
}

/* ---- meshes and the batch */

/* Times `body` REPS_DRAWN times (after one warm-up run) and prints the
 * median CPU time in ms. */
#define TIME_MESH(label, setup, body)                                                                                  \
    do {                                                                                                               \
        double c_[REPS_DRAWN];                                                                                         \
        for (int r_ = -1; r_ < REPS_DRAWN; r_++) {                                                                     \
            setup;                                                                                                     \
            double c0_ = cpu_ms();                                                                                     \
            body;                                                                                                      \
            if (r_ >= 0)                                                                                               \
                c_[r_] = cpu_ms() - c0_;                                                                               \
        }                                                                                                              \
        printf("  %-40s %9.3f\n", label, median(c_, REPS_DRAWN));                                                      \
    } while (0)

static void mesh_and_batch(const char *photo, const char *cli)
{
    char err[512];
    reconstruct_options ropt = reconstruct_options_default();
    reconstruction rec = {0};
    if (reconstruct_photo(photo, &ropt, &rec, err, sizeof err) != 0)
        die(err);
    const bspline_t curve = rec.curve;
    const double *u = rec.domains;
    const int nu = rec.n_domains;
    printf("meshes of the vase (mesh_revolve, base cap, %d rings)         CPU ms\n", nu);
    static const int targets[] = {90000, 200000, 400000};
    for (int k = 0; k < 3; k++) {
        int segments = (int)lround(targets[k] / (2.0 * (nu - 1) + 1.0));
        mesh_t m = {0};
        if (mesh_revolve(&curve, u, nu, 1.0, segments, MESH_CAP_BASE, &m))
            die("mesh failed");
        char label[96];
        snprintf(label, sizeof label, "%d segments, %d faces", segments, m.n_tris);
        TIME_MESH(label, mesh_free(&m),
                  if (mesh_revolve(&curve, u, nu, 1.0, segments, MESH_CAP_BASE, &m)) die("mesh failed"));
        mesh_free(&m);
    }
    uint8_t *ov = NULL;
    TIME_MESH("overlay", free(ov), ov = overlay_render(&rec.photo, &rec.extract, &rec.curve));
    free(ov);
    reconstruction_free(&rec);

    /* Batch: 32 copies of the photo in one call (dynamic OpenMP over photos). */
    enum { BATCH = 32 };
    char cmd[8192];
    int len = snprintf(cmd, sizeof cmd, "rm -rf out/bench/batch && %s reconstruct -o out/bench/batch", cli);
    for (int i = 0; i < BATCH; i++)
        len += snprintf(cmd + len, sizeof cmd - (size_t)len, " out/bench/batch_in/p%02d.png", i);
    snprintf(cmd + len, sizeof cmd - (size_t)len, " 2>/dev/null");
    mkdir("out/bench/batch_in", 0777);
    for (int i = 0; i < BATCH; i++) {
        char copy[512];
        snprintf(copy, sizeof copy, "cp %s out/bench/batch_in/p%02d.png", photo, i);
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
        double used = (after.ru_utime.tv_sec - before.ru_utime.tv_sec) +
                      (after.ru_stime.tv_sec - before.ru_stime.tv_sec) +
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
}
