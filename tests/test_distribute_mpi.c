/* `celadon render` under mpirun (distribute.h): the ranks' image is the
 * one-process image of the same seed within float rounding, a stopped rank
 * does not hold the others, SIGINT to mpirun leaves the partial image, the
 * plan's units cover every sample of every pixel once, and a job on one node
 * is given shared memory. The MPI tests skip when celadon was built without
 * MPI or mpirun is missing. */
#include <criterion/criterion.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "celadon/distribute.h"
#include "render/distribute_plan.h"
#include "test_distribute_support.h"

extern char **environ;

/* Every (sample, row) of the range is in exactly one unit; units are within
 * the size bounds unless the whole render is smaller; passes come first. */
Test(distribute_plan, units_cover_every_sample_once)
{
    static const int cases[][5] = {
        /* s0, s1, width, height, ranks */
        {0, 96, 64, 48, 1},      {0, 96, 64, 48, 3},     {5, 9, 64, 48, 2},         {0, 1, 7, 5, 4},
        {0, 1024, 3840, 2160, 64}, {0, 4, 3840, 2160, 64}, {0, 100000, 160, 90, 2}, {0, 16, 1000, 1, 3},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const int *k = cases[c];
        distribute_plan p = distribute_plan_make(k[0], k[1], k[2], k[3], k[4]);
        long long spp = k[1] - k[0], covered = 0, total = spp * k[3];
        char *seen = calloc((size_t)total, 1);
        cr_assert_not_null(seen);
        int last_s0 = k[0];
        for (int u = 0; u < p.units; u++) {
            int s0, s1, y0, y1;
            distribute_plan_unit(&p, u, &s0, &s1, &y0, &y1);
            cr_assert(s0 >= k[0] && s1 <= k[1] && s0 < s1 && y0 >= 0 && y1 <= k[3] && y0 < y1, "case %zu unit %d",
                      c, u);
            cr_assert_geq(s0, last_s0, "case %zu: unit %d goes back to sample %d", c, u, s0);
            last_s0 = s0;
            long long size = (long long)(s1 - s0) * (y1 - y0) * k[2];
            cr_assert(size <= 2 * DISTRIBUTE_MAX_UNIT || s1 - s0 == 1, "case %zu: unit of %lld samples", c, size);
            cr_assert(size >= DISTRIBUTE_MIN_UNIT / 2 || p.units == 1 || (s1 == k[1] || y1 == k[3]),
                      "case %zu: unit of %lld samples", c, size);
            for (int s = s0; s < s1; s++)
                for (int y = y0; y < y1; y++) {
                    long long i = (long long)(s - k[0]) * k[3] + y;
                    cr_assert_eq(seen[i], 0, "case %zu: sample %d of row %d twice", c, s, y);
                    seen[i] = 1, covered++;
                }
        }
        cr_assert_eq(covered, total, "case %zu: %lld of %lld covered", c, covered, total);
        free(seen);
    }
}

/* The launcher's environment: shared memory is chosen for a job on one node
 * only, and never over a transport the user chose. (Criterion runs each
 * test in a process of its own: the environment changed here stays here.) */
Test(distribute_env, shared_memory_only_for_one_node_and_no_choice)
{
    static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_LOCAL_SIZE", "OMPI_MCA_pml",
                                       "OMPI_MCA_btl", "OMPI_MCA_mtl"};
    for (int i = 0; i < 5; i++)
        unsetenv(vars[i]);
    cr_expect_eq(distribute_prefer_shared_memory(), 0, "not under Open MPI");
    setenv("OMPI_COMM_WORLD_SIZE", "4", 1);
    setenv("OMPI_COMM_WORLD_LOCAL_SIZE", "2", 1);
    cr_expect_eq(distribute_prefer_shared_memory(), 0, "ranks on two nodes");
    cr_expect_null(getenv("OMPI_MCA_pml"));
    setenv("OMPI_COMM_WORLD_LOCAL_SIZE", "4", 1);
    setenv("OMPI_MCA_mtl", "psm2", 1);
    cr_expect_eq(distribute_prefer_shared_memory(), 0, "the user chose an MTL");
    cr_expect_null(getenv("OMPI_MCA_pml"));
    unsetenv("OMPI_MCA_mtl");
    cr_expect_eq(distribute_prefer_shared_memory(), 1, "every rank on this node");
    cr_expect_str_eq(getenv("OMPI_MCA_pml"), "ob1");
    cr_expect_str_eq(getenv("OMPI_MCA_btl"), "self,vader");
}

/* mpirun's command line for `celadon ARGS` on np ranks. */
static int mpirun_argv(const char *np, const char *const *args, const char **argv)
{
#ifndef CELADON_HAVE_MPI
    cr_skip_test("celadon was built without MPI");
#endif
    if (system("command -v mpirun >/dev/null 2>&1") != 0)
        cr_skip_test("mpirun is not installed (make deps installs openmpi-bin)");
    /* Open MPI 4.1 unloads its components in MPI_Finalize, so LeakSanitizer
     * cannot name (nor be told to ignore) their one-time allocations: the
     * ranks run without leak checks. The render loop and the parts they
     * share with one process are leak-checked by the other tests. */
    const char *asan = getenv("ASAN_OPTIONS");
    if (asan) {
        char opts[1024];
        snprintf(opts, sizeof opts, "%s:detect_leaks=0", asan);
        setenv("ASAN_OPTIONS", opts, 1);
    }
    int n = 0;
    argv[n++] = "mpirun";
    argv[n++] = "-q";
    argv[n++] = "--oversubscribe";
    if (geteuid() == 0)
        argv[n++] = "--allow-run-as-root";
    argv[n++] = "-np";
    argv[n++] = np;
    argv[n++] = cli_bin();
    for (; *args; args++)
        argv[n++] = *args;
    argv[n] = NULL;
    return n;
}

static int run_mpi(const render_fixture *f, const char *np, const char *const *args, char *err, size_t errlen)
{
    const char *argv[40];
    mpirun_argv(np, args, argv);
    cli_result r = cli_run_argv(f->dir, argv);
    snprintf(err, errlen, "%s", r.err);
    cli_result_free(&r);
    return r.status;
}

/* The numbers after label in rank 0's balance line ("distribute: units per
 * rank: a b c; CPU s before rendering per rank: x y z; ..."); returns how
 * many it lists. */
static int per_rank(const char *err, const char *label, double *v, int max)
{
    const char *p = strstr(err, label);
    cr_assert_not_null(p, "no \"%s\" in: %s", label, err);
    p += strlen(label);
    int n = 0, len;
    while (n < max && sscanf(p, " %lf%n", &v[n], &len) == 1)
        n++, p += len;
    return n;
}

/* The units each rank took. */
static int units_per_rank(const char *err, int *units, int max)
{
    double v[8];
    int n = per_rank(err, "units per rank:", v, max < 8 ? max : 8);
    for (int r = 0; r < n; r++)
        units[r] = (int)v[r];
    return n;
}

static double children_cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_CHILDREN, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * (double)ru.ru_stime.tv_usec;
}

Test(distribute_mpi, two_and_three_ranks_give_the_single_image, .timeout = 600)
{
    render_fixture f;
    char scene[256], single[256], out[256], err[8192];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *a1[] = {"render", scene, "-o", fixture_path(&f, "single.exr", single, sizeof single), "--aov",
                        "normal", NULL};
    cr_assert_eq(run_celadon(&f, a1, err, sizeof err), 0, "%s", err);
    image_t s = read_image(single);
    const char *nps[] = {"2", "3"};
    for (int i = 0; i < 2; i++) {
        const char *a[] = {"render", scene, "-o", fixture_path(&f, "ranks.exr", out, sizeof out), "--threads", "1",
                           "--aov", "normal", NULL};
        double cpu0 = children_cpu_seconds();
        cr_assert_eq(run_mpi(&f, nps[i], a, err, sizeof err), 0, "%s", err);
        double job_cpu = children_cpu_seconds() - cpu0;
        int units[8], n = units_per_rank(err, units, 8), sum = 0;
        cr_expect_eq(n, atoi(nps[i]), "%s", err);
        for (int r = 0; r < n; r++)
            sum += units[r];
        cr_expect_eq(sum, distribute_plan_make(0, 96, 64, 48, n).units, "%s", err);
        /* Each rank's fixed cost (start, MPI_Init, build) is some CPU time,
         * and together less than the job's, which also rendered. */
        double ready[8], ready_sum = 0.0;
        cr_expect_eq(per_rank(err, "CPU s before rendering per rank:", ready, 8), n, "%s", err);
        for (int r = 0; r < n; r++) {
            cr_expect_gt(ready[r], 0.0, "rank %d: %s", r, err);
            ready_sum += ready[r];
        }
        cr_expect_lt(ready_sum, job_cpu, "the ranks' fixed cost %g s of a job of %g s", ready_sum, job_cpu);
        image_t m = read_image(out);
        double worst;
        cr_expect(same_within_rounding(&s, &m, &worst), "%s ranks differ from one process by %g", nps[i], worst);
        image_free(&m);
    }
    image_free(&s);
    render_fixture_close(&f);
}

/* Starts `mpirun ARGS` with stderr into dir/errname; returns its pid. */
static pid_t spawn_mpi(const render_fixture *f, const char *const *argv, const char *errname)
{
    char errpath[256];
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, fixture_path(f, errname, errpath, sizeof errpath),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], &fa, NULL, (char *const *)argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    return pid;
}

static char *read_text(const char *path)
{
    FILE *fp = fopen(path, "rb");
    cr_assert_not_null(fp, "%s", path);
    static char buf[16384];
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    buf[n] = '\0';
    fclose(fp);
    return buf;
}

/* The largest percentage of rank 0's progress lines ("render: 40% ETA ...")
 * in text, or -1. */
static int progress_percent(const char *text)
{
    int best = -1;
    for (const char *p = strstr(text, "render: "); p; p = strstr(p + 1, "render: ")) {
        int pct, len = 0;
        if (sscanf(p, "render: %d%%%n", &pct, &len) == 1 && len > 0 && pct > best)
            best = pct;
    }
    return best;
}

/* Waits (at most limit seconds) until path holds needle, or (needle NULL)
 * until its progress lines reach percent. */
static int wait_for_text(const char *path, const char *needle, int percent, double limit)
{
    for (double t = 0; t < limit; t += 0.05) {
        FILE *fp = fopen(path, "rb");
        if (fp) {
            char buf[16384];
            size_t n = fread(buf, 1, sizeof buf - 1, fp);
            buf[n] = '\0';
            fclose(fp);
            if (needle ? strstr(buf, needle) != NULL : progress_percent(buf) >= percent)
                return 1;
        }
        usleep(50000);
    }
    return 0;
}

/* Ctrl-C: mpirun turns SIGINT into SIGTERM to every rank; they stop, and
 * rank 0 writes what all of them finished. */
Test(distribute_mpi, sigint_to_mpirun_writes_the_partial_image, .timeout = 600)
{
    render_fixture f;
    char scene[256], out[256], errpath[256];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *args[] = {"render", scene, "-o", fixture_path(&f, "partial.exr", out, sizeof out), "--threads", "1",
                          "-D", "spp=1000000", NULL};
    const char *argv[40];
    mpirun_argv("2", args, argv);
    pid_t pid = spawn_mpi(&f, argv, "stderr.txt");
    /* Rank 0 says when the ranks start rendering. */
    cr_assert(wait_for_text(fixture_path(&f, "stderr.txt", errpath, sizeof errpath), "distribute:", 0, 300),
              "no start: %s", read_text(errpath));
    usleep(500000);
    kill(pid, SIGINT);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    const char *err = read_text(errpath);
    cr_expect_not_null(strstr(err, "wrote the partial image"), "%s", err);
    image_t img = read_image(out);
    /* R, G, B, and spp where the pixels' counts differ (issue 28) */
    cr_expect(img.width == 64 && img.height == 48 && (img.channels == 3 || img.channels == 4), "%d channels",
              img.channels);
    size_t n = (size_t)img.width * img.height * img.channels, lit = 0;
    for (size_t i = 0; i < n; i++) {
        cr_assert(isfinite(img.data[i]) && img.data[i] >= 0.0f);
        lit += img.data[i] > 0.0f;
    }
    cr_expect_gt(lit, 0, "the partial image is black");
    image_free(&img);
    render_fixture_close(&f);
}

/* Rank 1 stopped (SIGSTOP) for a while once the render runs: rank 0 takes
 * the units meanwhile, and the image is still the single one. */
Test(distribute_mpi, a_stopped_rank_does_not_hold_the_others, .timeout = 600)
{
    render_fixture f;
    char scene[256], single[256], out[256], errpath[256], pidpath[256], cmd[1024], err[8192];
    render_fixture_with_scene(&f, "plum", orbit_xml, scene, sizeof scene);
    const char *a1[] = {"render", scene, "-o", fixture_path(&f, "single.exr", single, sizeof single), "--threads",
                        "2", NULL};
    cr_assert_eq(run_celadon(&f, a1, err, sizeof err), 0, "%s", err);
    /* MPMD: rank 1 is a shell that records its pid and becomes celadon. */
    fixture_path(&f, "rank1.pid", pidpath, sizeof pidpath);
    fixture_path(&f, "ranks.exr", out, sizeof out);
    snprintf(cmd, sizeof cmd, "echo $$ > '%s'; exec '%s' render '%s' -o '%s' --threads 1", pidpath, cli_bin(),
             scene, out);
    const char *rank0[] = {"render", scene, "-o", out, "--threads", "1", NULL};
    const char *argv[48];
    int n = mpirun_argv("1", rank0, argv);
    const char *rest[] = {":", "-np", "1", "sh", "-c", cmd, NULL};
    for (int i = 0; rest[i]; i++)
        argv[n++] = rest[i];
    argv[n] = NULL;
    pid_t pid = spawn_mpi(&f, argv, "stderr.txt");
    fixture_path(&f, "stderr.txt", errpath, sizeof errpath);
    cr_assert(wait_for_text(errpath, NULL, 10, 300), "no progress: %s", read_text(errpath));
    FILE *fp = fopen(pidpath, "r");
    cr_assert_not_null(fp);
    int rank1 = 0;
    cr_assert_eq(fscanf(fp, "%d", &rank1), 1);
    fclose(fp);
    kill(rank1, SIGSTOP);
    int waited = wait_for_text(errpath, NULL, 60, 300);
    kill(rank1, SIGCONT);
    cr_assert(waited, "rank 0 made no progress while rank 1 was stopped: %s", read_text(errpath));
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    const char *text = read_text(errpath);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s", text);
    int units[2];
    cr_assert_eq(units_per_rank(text, units, 2), 2);
    cr_expect_gt(units[0], units[1], "rank 0 took %d units, the stopped rank 1 %d", units[0], units[1]);
    image_t s = read_image(single), m = read_image(out);
    double worst;
    cr_expect(same_within_rounding(&s, &m, &worst), "differs from one process by %g", worst);
    image_free(&s), image_free(&m);
    render_fixture_close(&f);
}

/* A bad scene under mpirun: exit 2, one line from rank 0 only. */
Test(distribute_mpi, bad_input_is_one_line_from_rank_0, .timeout = 300)
{
    render_fixture f;
    render_fixture_open(&f);
    char out[256], err[8192];
    const char *a[] = {"render", "/nonexistent/scene.xml", "-o", fixture_path(&f, "x.exr", out, sizeof out), NULL};
    cr_expect_eq(run_mpi(&f, "2", a, err, sizeof err), 2, "%s", err);
    cr_expect_eq(cli_count_lines(err), 1, "%s", err);
    cr_expect_not_null(strstr(err, "scene.xml"), "%s", err);
    const char *b[] = {"render", "--spp", "0", "s.xml", "-o", out, NULL};
    cr_expect_eq(run_mpi(&f, "3", b, err, sizeof err), 2, "%s", err);
    cr_expect_eq(cli_count_lines(err), 1, "%s", err);
    cr_expect_neq(access(out, F_OK), 0);
    render_fixture_close(&f);
}
