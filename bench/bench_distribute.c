/* Distributed rendering benchmark (docs/BENCHMARKS.md, "Distributed
 * rendering"; docs/distributed.md):
 *
 *  1. the showcase at 480x270, 32 spp under mpirun on 1 and 2 ranks of one
 *     thread, beside one process of 1 and 2 threads: wall and CPU seconds
 *     (all processes), and the load average around each run;
 *  2. in this process: the showcase's scene build, its CPU cost per sample
 *     in each of 16 bands of rows, and the write of a 4K film as EXR;
 *  3. under `mpirun -np 2` (this program again, --probe): the sum of two
 *     4K films with MPI_Reduce as distribute_mpi.c does it, the plain
 *     addition of such arrays in one core, and the hand-out round trip of a
 *     unit (rank 0 polling with 1 ms sleeps, as its coordinator does);
 *  4. from those, a simulation of 4K at 1024 spp on 16 and 64 nodes: the
 *     units of the plan (distribute_plan.c) handed to whichever rank is free,
 *     plus the scene build, the reduction and the write; and one node at
 *     half speed, handed out dynamically and split statically.
 *
 *   CELADON_BIN=build/celadon build/bench/bench_distribute   (from the
 *   repository root; images go to out/bench/) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "celadon/render.h"
#include "celadon/scene.h"
#include "render/distribute_plan.h"
#include "render/render_loop.h"

#ifdef CELADON_HAVE_MPI
#include <mpi.h>
#endif

static const char *const SCENE = "scenes/showcase/scene.xml";
enum { W = 480, H = 270, SPP = 32, SLICES = 16, PROBE_W = 3840, PROBE_H = 2160, PROBE_CH = 4 };

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double children_cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

static double load_average(void)
{
    double l = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = NAN;
        fclose(f);
    }
    return l;
}

static const char *mpirun_root_flag(void) { return geteuid() == 0 ? "--allow-run-as-root" : ""; }

/* ------------------------------------------------------------ 1. ranks */

static int timed_command(const char *label, const char *cmd, int samples_run)
{
    double l0 = load_average(), c0 = children_cpu_seconds(), t0 = wall_seconds();
    int rc = system(cmd);
    double wall = wall_seconds() - t0, cpu = children_cpu_seconds() - c0, l1 = load_average();
    if (rc != 0) {
        fprintf(stderr, "bench_distribute: failed: %s\n", cmd);
        return -1;
    }
    printf("| %-28s | %7.2f | %7.2f | %8.3f | %4.1f-%.1f |\n", label, wall, cpu,
           1e-6 * samples_run / cpu, l0, l1);
    fflush(stdout);
    return 0;
}

static int rank_runs(const char *bin)
{
    char cmd[2048];
    const char *common = "--res 480x270 --spp 32 --seed 1";
    printf("showcase %dx%d, %d spp (%.2f M samples); CPU = user + sys of every process\n\n", W, H, SPP,
           1e-6 * W * H * SPP);
    printf("| run                          | wall s  | CPU s   | Ms/CPU-s | load      |\n");
    printf("|------------------------------|---------|---------|----------|-----------|\n");
    for (int t = 1; t <= 2; t++) {
        char label[64];
        snprintf(cmd, sizeof cmd, "%s render %s -o out/bench/dist-t%d.exr %s --threads %d 2>/dev/null", bin, SCENE,
                 t, common, t);
        snprintf(label, sizeof label, "1 process, %d thread%s", t, t > 1 ? "s" : "");
        if (timed_command(label, cmd, W * H * SPP) != 0)
            return -1;
    }
#ifdef CELADON_HAVE_MPI
    for (int r = 1; r <= 2; r++) {
        char label[64];
        snprintf(cmd, sizeof cmd,
                 "mpirun -q --oversubscribe %s -np %d %s render %s -o out/bench/dist-r%d.exr %s --threads 1 "
                 "2>out/bench/dist-r%d.log",
                 mpirun_root_flag(), r, bin, SCENE, r, common, r);
        snprintf(label, sizeof label, "mpirun -np %d, 1 thread each", r);
        if (timed_command(label, cmd, W * H * SPP) != 0)
            return -1;
    }
#endif
    return 0;
}

/* ------------------------------------------------------------ 2. this process */

typedef struct {
    double build_wall, build_cpu;
    double slice_cost[SLICES]; /* CPU seconds per camera sample in each band of rows */
    double write_wall;
} local_costs;

static int measure_local(local_costs *lc)
{
    char err[2048];
    scene_options bo = scene_options_default();
    bo.width = W / 2, bo.height = H / 2, bo.spp = 8, bo.seed = 1;
    double t0 = wall_seconds(), c0 = cpu_seconds();
    scene_t *s = scene_create_from_file(SCENE, NULL, 0, &bo, err, sizeof err);
    lc->build_wall = wall_seconds() - t0, lc->build_cpu = cpu_seconds() - c0;
    if (!s) {
        fprintf(stderr, "bench_distribute: %s\n", err);
        return -1;
    }
    film_t film;
    if (render_film_init(s, 0, &film, err, sizeof err) != 0)
        return -1;
    int h = H / 2;
    for (int i = 0; i < SLICES; i++) {
        int y0 = i * h / SLICES, y1 = (i + 1) * h / SLICES;
        render_tally tally = {0};
        double c = cpu_seconds();
        render_samples(s, 1, 0, &film, 0, 8, y0, y1, &tally);
        lc->slice_cost[i] = (cpu_seconds() - c) / (double)atomic_load(&tally.taken);
    }
    film_free(&film);
    scene_destroy(s);
    /* The 4K image rank 0 writes at the end. */
    if (film_init(&film, PROBE_W, PROBE_H, NULL, 0, err, sizeof err) != 0)
        return -1;
    for (size_t i = 0; i < (size_t)PROBE_W * PROBE_H; i++) {
        for (int c = 0; c < 3; c++)
            film.sum[i * 3 + c] = (double)((i * 7919 + (size_t)c * 104729) % 1000) * 1e-3;
        film.weight[i] = 1.0;
    }
    t0 = wall_seconds();
    int rc = film_write(&film, "out/bench/dist-4k.exr", err, sizeof err);
    lc->write_wall = wall_seconds() - t0;
    film_free(&film);
    return rc;
}

/* ------------------------------------------------------------ 3. the MPI probe */

typedef struct {
    double reduce, add, round_trip;
} probe_costs;

#ifdef CELADON_HAVE_MPI
static void sleep_ms(void)
{
    struct timespec ts = {0, 1000000};
    nanosleep(&ts, NULL);
}

/* Run by `mpirun -np 2 bench_distribute --probe`: prints rank 0's timings. */
static int probe_main(void)
{
    MPI_Init(NULL, NULL);
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    size_t n = (size_t)PROBE_W * PROBE_H * PROBE_CH;
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    if (!a || !b)
        MPI_Abort(MPI_COMM_WORLD, 1);
    for (size_t i = 0; i < n; i++)
        a[i] = (double)(i % 977), b[i] = 1.0;
    double best = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        MPI_Barrier(MPI_COMM_WORLD);
        double t0 = MPI_Wtime();
        enum { CHUNK = 1 << 24 }; /* distribute_mpi.c's REDUCE_CHUNK */
        for (size_t off = 0; off < n; off += CHUNK) {
            int count = (int)(n - off < CHUNK ? n - off : CHUNK);
            MPI_Reduce(rank == 0 ? MPI_IN_PLACE : a + off, a + off, count, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        }
        double t = MPI_Wtime() - t0;
        best = t < best ? t : best;
    }
    double t0 = MPI_Wtime();
    for (size_t i = 0; i < n; i++)
        a[i] += b[i];
    double add = MPI_Wtime() - t0;
    volatile double sink = a[n / 2]; /* keeps the addition */
    (void)sink;
    /* Round trips: rank 1 asks, rank 0 answers from a 1 ms polling loop. */
    enum { TRIPS = 200 };
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (int k = 0; k < TRIPS; k++) {
        unsigned long long m = (unsigned long long)k;
        if (rank == 1) {
            MPI_Send(&m, 1, MPI_UNSIGNED_LONG_LONG, 0, 1, MPI_COMM_WORLD);
            MPI_Recv(&m, 1, MPI_UNSIGNED_LONG_LONG, 0, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        } else if (rank == 0) {
            int flag = 0;
            for (MPI_Iprobe(1, 1, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE); !flag;
                 MPI_Iprobe(1, 1, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE))
                sleep_ms();
            MPI_Recv(&m, 1, MPI_UNSIGNED_LONG_LONG, 1, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            MPI_Send(&m, 1, MPI_UNSIGNED_LONG_LONG, 1, 2, MPI_COMM_WORLD);
        }
    }
    double trip = (MPI_Wtime() - t0) / TRIPS;
    if (rank == 0)
        printf("%.6f %.6f %.6f\n", best, add, trip);
    free(a), free(b);
    MPI_Finalize();
    return 0;
}

static int run_probe(const char *self, probe_costs *pc)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "mpirun -q --oversubscribe %s -np 2 %s --probe", mpirun_root_flag(), self);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    int got = fscanf(p, "%lf %lf %lf", &pc->reduce, &pc->add, &pc->round_trip);
    return pclose(p) == 0 && got == 3 ? 0 : -1;
}
#endif

/* ------------------------------------------------------------ 4. simulation */

/* The CPU seconds of a unit of the 4K plan, from the slice costs. */
static double unit_cost(const distribute_plan *p, int u, const local_costs *lc)
{
    int s0, s1, y0, y1;
    distribute_plan_unit(p, u, &s0, &s1, &y0, &y1);
    double per_row = 0.0;
    for (int y = y0; y < y1; y++)
        per_row += lc->slice_cost[(long long)y * SLICES / p->height];
    return per_row * p->width * (s1 - s0);
}

/* Makespan of the units on `ranks` ranks of `cores` cores (perfect thread
 * scaling inside a rank), rank 0 at `speed0` of the others' speed; dynamic:
 * each unit to the rank that frees up first, after a hand-out round trip;
 * static: rank r gets the r-th contiguous share of the units. */
static double makespan(const distribute_plan *p, int ranks, int cores, double speed0, int dynamic,
                       const local_costs *lc, double trip)
{
    double *free_at = calloc((size_t)ranks, sizeof *free_at), end = 0.0;
    if (!free_at)
        abort();
    for (int u = 0; u < p->units; u++) {
        int r = 0;
        if (dynamic) {
            for (int k = 1; k < ranks; k++)
                if (free_at[k] < free_at[r])
                    r = k;
        } else {
            r = (int)((long long)u * ranks / p->units);
        }
        free_at[r] += (dynamic ? trip : 0.0) + unit_cost(p, u, lc) / cores / (r == 0 ? speed0 : 1.0);
    }
    for (int r = 0; r < ranks; r++)
        end = free_at[r] > end ? free_at[r] : end;
    free(free_at);
    return end;
}

static void simulate(const local_costs *lc, const probe_costs *pc)
{
    const double net_bytes_per_s = 1.25e9; /* assumed: 10 Gb/s Ethernet between nodes */
    double film_bytes = (double)PROBE_W * PROBE_H * PROBE_CH * 8.0;
    double total_cpu = 0.0;
    distribute_plan one = distribute_plan_make(0, 1024, PROBE_W, PROBE_H, 1);
    for (int u = 0; u < one.units; u++)
        total_cpu += unit_cost(&one, u, lc);
    printf("\n4K (3840x2160) at 1024 spp: %.3g samples, %.0f CPU-s at this machine's measured cost per sample\n",
           (double)PROBE_W * PROBE_H * 1024, total_cpu);
    printf("(scene build %.2f s, 4K EXR write %.2f s, hand-out round trip %.2f ms; the sum of the films over\n"
           "ceil(log2 nodes) steps of a binomial tree, each %.0f MB over 10 Gb/s plus its addition %.3f s)\n\n",
           lc->build_wall, lc->write_wall, 1e3 * pc->round_trip, film_bytes / 1e6, pc->add);
    printf("| nodes x cores | units | ideal s | makespan s | reduction s | total s | efficiency | 1 node at 1/2 speed: dynamic s | static s |\n");
    printf("|---------------|-------|---------|------------|-------------|---------|------------|--------------------------------|----------|\n");
    static const int nodes[] = {16, 64}, cores[] = {2, 32};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            int P = nodes[i], C = cores[j];
            distribute_plan p = distribute_plan_make(0, 1024, PROBE_W, PROBE_H, P);
            double ideal = total_cpu / ((double)P * C);
            double span = makespan(&p, P, C, 1.0, 1, lc, pc->round_trip);
            double steps = ceil(log2((double)P));
            double reduce = steps * (film_bytes / net_bytes_per_s + pc->add);
            double total = lc->build_wall + span + reduce + lc->write_wall;
            double slow_dyn = makespan(&p, P, C, 0.5, 1, lc, pc->round_trip);
            double slow_static = makespan(&p, P, C, 0.5, 0, lc, pc->round_trip);
            printf("| %3d x %-2d       | %5d | %7.1f | %10.1f | %11.2f | %7.1f | %9.1f%% | %30.1f | %8.1f |\n", P, C,
                   p.units, ideal, span, reduce, total, 100.0 * ideal / total, slow_dyn, slow_static);
        }
}

int main(int argc, char **argv)
{
#ifdef CELADON_HAVE_MPI
    if (argc > 1 && !strcmp(argv[1], "--probe"))
        return probe_main();
#endif
    (void)argc;
    const char *bin = getenv("CELADON_BIN") ? getenv("CELADON_BIN") : "build/celadon";
    mkdir("out", 0777);
    mkdir("out/bench", 0777);
    if (rank_runs(bin) != 0)
        return 1;
    local_costs lc;
    if (measure_local(&lc) != 0)
        return 1;
    double mean = 0.0;
    for (int i = 0; i < SLICES; i++)
        mean += lc.slice_cost[i] / SLICES;
    printf("\nper camera sample, one thread: %.2f us on average; by band of rows (top to bottom):", 1e6 * mean);
    for (int i = 0; i < SLICES; i++)
        printf(" %.2f", 1e6 * lc.slice_cost[i]);
    printf("\nscene build: %.2f s wall, %.2f s CPU; 4K EXR write: %.2f s\n", lc.build_wall, lc.build_cpu,
           lc.write_wall);
    probe_costs pc = {0.0, 0.0, 1e-3};
#ifdef CELADON_HAVE_MPI
    if (run_probe(argv[0], &pc) != 0) {
        fprintf(stderr, "bench_distribute: the MPI probe failed\n");
        return 1;
    }
    printf("4K film (%d doubles per pixel) summed by MPI_Reduce on 2 ranks here: %.3f s (%.2f GB/s); one core "
           "adds two such arrays in %.3f s; unit hand-out round trip %.2f ms\n",
           PROBE_CH, pc.reduce, (double)PROBE_W * PROBE_H * PROBE_CH * 8.0 / pc.reduce * 1e-9, pc.add,
           1e3 * pc.round_trip);
#else
    printf("(built without MPI: no ranks, no reduction probe; the simulation assumes a 1 ms hand-out)\n");
#endif
    simulate(&lc, &pc);
    return 0;
}
