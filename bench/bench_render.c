/* Rendering benchmark (docs/BENCHMARKS.md, "Rendering"): the showcase scene
 * at 640x360 with 16 spp, its SORs analytic and revolved into 360 segments,
 * on 1 and 2 threads (seconds and Msamples/s, and the share of the threads'
 * time an idle machine would spend waiting for the last tile of a pass:
 * render_stats), then the cross-check error table of the same scene at
 * N = 16, 64, 256, 1024.
 *
 *   bench_render [SCENE.xml] [--threads-only]
 *       (default scenes/showcase/scene.xml; run from the repository root;
 *       images go to out/bench/; --threads-only: no cross-check) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "celadon/crosscheck.h"
#include "celadon/render.h"
#include "celadon/scene.h"

enum { WIDTH = 640, HEIGHT = 360, SPP = 16, MESH_SEGMENTS = 360 };

static scene_options build_options(int segments)
{
    scene_options bo = scene_options_default();
    bo.width = WIDTH, bo.height = HEIGHT, bo.spp = SPP, bo.seed = 1;
    bo.mesh_segments = segments;
    return bo;
}

/* CPU seconds of the whole process (all threads): on a shared machine wall
 * time counts waits for a core, CPU time does not. */
static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One render; prints a table row. Returns its seconds, or -1. */
static double timed_render(const char *scene_path, int segments, int threads)
{
    char err[2048];
    scene_options bo = build_options(segments);
    scene_t *s = scene_create_from_file(scene_path, NULL, 0, &bo, err, sizeof err);
    if (!s) {
        fprintf(stderr, "bench_render: %s\n", err);
        return -1.0;
    }
    render_options ro = {.threads = threads};
    film_t film;
    render_stats st;
    double cpu0 = cpu_seconds();
    int rc = render_scene(s, &ro, &film, &st, err, sizeof err);
    double cpu = cpu_seconds() - cpu0;
    long long tris = scene_triangle_count(s);
    scene_destroy(s);
    if (rc != 0) {
        fprintf(stderr, "bench_render: %s\n", err);
        return -1.0;
    }
    film_free(&film);
    char geo[32];
    snprintf(geo, sizeof geo, segments ? "mesh:%d" : "analytic", segments);
    printf("| %-9s | %7d | %9lld | %7.2f | %10.3f | %11.2f | %14.3f | %8.3f%% |\n", geo, threads, tris, st.seconds,
           1e-6 * (double)st.samples / st.seconds, cpu, 1e-6 * (double)st.samples / cpu,
           100.0 * st.idle_cpu_seconds / (st.busy_cpu_seconds + st.idle_cpu_seconds));
    fflush(stdout);
    return st.seconds;
}

int main(int argc, char **argv)
{
    const char *scene = "scenes/showcase/scene.xml";
    int threads_only = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--threads-only"))
            threads_only = 1;
        else
            scene = argv[i];
    }
    printf("scene %s, %dx%d, %d spp\n\n", scene, WIDTH, HEIGHT, SPP);
    printf("| geometry  | threads | triangles | seconds | Msamples/s | CPU seconds | Msamples/CPU-s | tile wait |\n");
    printf("|-----------|---------|-----------|---------|------------|-------------|----------------|-----------|\n");
    double t[2][2];
    for (int th = 1; th <= 2; th++)
        for (int g = 0; g < 2; g++)
            if ((t[th - 1][g] = timed_render(scene, g ? MESH_SEGMENTS : 0, th)) < 0)
                return 1;
    printf("\nanalytic / meshed time: %.2f (1 thread), %.2f (2 threads)\n\n", t[0][0] / t[0][1],
           t[1][0] / t[1][1]);
    if (threads_only)
        return 0;

    static const int segments[] = {16, 64, 256, 1024};
    crosscheck_params p = {.scene_path = scene, .build = build_options(0), .threads = 2, .segments = segments,
                           .nsegments = 4, .geo_grid = 4};
    crosscheck_result res;
    char err[2048];
    mkdir("out", 0755);
    mkdir("out/bench", 0755);
    mkdir("out/bench/crosscheck", 0755);
    if (crosscheck_run(&p, "out/bench/crosscheck", &res, err, sizeof err) != 0 ||
        crosscheck_write_report(&res, &p, "out/bench/crosscheck/report.json", err, sizeof err) != 0 ||
        crosscheck_write_plot(&res, "out/bench/crosscheck/convergence.png", 900, 600, err, sizeof err) != 0) {
        fprintf(stderr, "bench_render: %s\n", err);
        crosscheck_result_free(&res);
        return 1;
    }
    printf("cross-check (2 threads, %dx%d rays per pixel for the geometry metrics), analytic %.2f s:\n\n",
           res.geo_grid, res.geo_grid, res.analytic_seconds);
    printf("| N    | seconds | rel_mse   | mean_abs_diff | coverage px | coverage area px | depth_rel_err | normal err deg |\n");
    printf("|------|---------|-----------|---------------|-------------|------------------|---------------|----------------|\n");
    for (int i = 0; i < res.nrows; i++) {
        const crosscheck_row *r = &res.rows[i];
        printf("| %4d | %7.2f | %9.3e | %13.3e | %11lld | %16.2f | %13.3e | %14.4f |\n", r->segments, r->seconds,
               r->rel_mse, r->mean_abs_diff, r->coverage_pixels, r->coverage_area, r->depth_rel_err,
               r->normal_err_deg);
    }
    printf("\nfitted slopes:");
    for (int m = 0; m < CROSSCHECK_METRIC_COUNT; m++)
        printf(" %s %.2f%s", crosscheck_metric_name(m), res.fits[m].slope, m + 1 < CROSSCHECK_METRIC_COUNT ? "," : "\n");
    printf("%s between successive N:", crosscheck_metric_name(CROSSCHECK_PRIMARY_METRIC));
    for (int i = 1; i < res.nrows; i++)
        printf(" %.2f", crosscheck_local_slope(res.rows, i, CROSSCHECK_PRIMARY_METRIC));
    printf("\n");
    printf("report and images: out/bench/crosscheck/\n");
    crosscheck_result_free(&res);
    return 0;
}
