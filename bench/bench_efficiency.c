/* Rendering efficiency (docs/BENCHMARKS.md, "Noise per CPU second"): each
 * scene rendered by a celadon binary at a few sample counts and seeds, its
 * error measured against a long reference, and its CPU time:
 *
 *   efficiency = 1 / (MSE x CPU seconds),
 *
 * the number of squared-error units removed per CPU second (higher is
 * better; halving the noise at equal time is 4x). The MSE is measured two
 * ways: against a long reference (which adds the reference's own noise),
 * and from two renders with different seeds, MSE = mean((a - b)^2) / 2,
 * which for an unbiased renderer is its variance, with no reference at all
 * (the efficiency uses this one; the reference also checks the mean). The
 * CPU time of a render
 * is counted as spp x (CPU seconds per sample per pixel), the slope of a
 * least-squares line through every run's CPU time (user + sys of the child
 * process, so it holds under load) against its spp: the fixed cost of
 * starting the program and building the scene, which the line's intercept
 * takes, is left out, as the Cycles comparison leaves Blender's out.
 *
 *   bench_efficiency [--bin CELADON] [--scenes DIR] [--scene NAME]... [--res WxH]
 *                    [--spp N,N,...] [--repeat R] [--ref-spp N] [--sampler NAME] [--threads T]
 *                    [--scene-filter]
 *
 * Defaults: the binary $CELADON_BIN (else build/celadon), scenes studio,
 * cornell-sor and showcase (DIR/NAME/scene.xml, DIR = scenes, from the
 * repository root; an older binary wants its own commit's scenes), 320x180, 4,16,64 spp, 2 seeds each, 2 threads, the scene's own
 * sampler. The reference (2048 spp, zsobol, rendered once by build/celadon
 * and kept in out/bench/efficiency/) is the same for every binary, so an
 * older binary (--bin) is measured against the same truth ("before").
 * Every render has a 1-pixel box filter, as Cycles' in the comparison
 * (box_filtered_scene); --scene-filter keeps the scene's own, for a binary
 * older than the reconstruction filters (whose film was such a box) or to
 * see the filter's effect. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "celadon/image.h"

extern char **environ;

enum { MAX_SCENES = 8, MAX_SPP = 8, MAX_REPEAT = 8 };

typedef struct {
    const char *bin, *ref_bin, *sampler, *scene_dir;
    const char *scenes[MAX_SCENES];
    int nscenes;
    int width, height, threads, repeat, ref_spp;
    int scene_filter; /* render with the scene's own filter, not a box */
    int spp[MAX_SPP], nspp;
} options;

/* Runs argv; returns the child's CPU seconds (user + sys), or -1. */
static double run_cpu(char *const argv[])
{
    pid_t pid;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    int rc = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        fprintf(stderr, "bench_efficiency: cannot run %s: %s\n", argv[0], strerror(rc));
        return -1.0;
    }
    int status;
    struct rusage ru;
    if (wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "bench_efficiency: %s %s %s failed\n", argv[0], argv[1], argv[2]);
        return -1.0;
    }
    return (double)ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
           1e-6 * ru.ru_stime.tv_usec;
}

/* DIR/NAME/scene.xml with a 1-pixel box filter in its film (the bundled
 * scenes take hdrfilm's default Gaussian, which blurs the noise over
 * neighbouring pixels: a smaller MSE that is not a cleaner estimate, and not
 * what Cycles' box is compared with), written beside it as
 * DIR/NAME/.efficiency-box.xml so that its relative file names still
 * resolve. Its path in path, 0; or -1 when the scene cannot be read or
 * already names a filter. */
static int box_filtered_scene(const char *dir, const char *scene, char *path, size_t n)
{
    char src[512];
    snprintf(src, sizeof src, "%s/%s/scene.xml", dir, scene);
    snprintf(path, n, "%s/%s/.efficiency-box.xml", dir, scene);
    FILE *f = fopen(src, "rb");
    char *xml = f ? malloc(1 << 20) : NULL;
    size_t len = xml ? fread(xml, 1, (1 << 20) - 1, f) : 0;
    if (f)
        fclose(f);
    if (!xml) {
        fprintf(stderr, "bench_efficiency: cannot read %s\n", src);
        return -1;
    }
    xml[len] = '\0';
    char *film = strstr(xml, "<film"), *end = film ? strchr(film, '>') : NULL;
    int rc = -1;
    if (!end || end[-1] == '/' || strstr(xml, "<rfilter"))
        fprintf(stderr, "bench_efficiency: %s: no <film> to give a box filter, or a filter already\n", src);
    else if ((f = fopen(path, "wb"))) {
        fwrite(xml, 1, (size_t)(end + 1 - xml), f);
        fputs("<rfilter type=\"box\"/>", f);
        fputs(end + 1, f);
        rc = fclose(f) == 0 ? 0 : -1;
    }
    free(xml);
    return rc;
}

/* One render of scene to out (box-filtered unless --scene-filter); its CPU
 * seconds or -1. */
static double render(const options *o, const char *bin, const char *scene, int spp, int seed, const char *sampler,
                     const char *out)
{
    char path[512], spp_s[32], res_s[64], thr_s[32], seed_s[32];
    const char *dir = bin == o->ref_bin ? "scenes" : o->scene_dir;
    if (o->scene_filter)
        snprintf(path, sizeof path, "%s/%s/scene.xml", dir, scene);
    else if (box_filtered_scene(dir, scene, path, sizeof path) != 0)
        return -1.0;
    snprintf(spp_s, sizeof spp_s, "%d", spp);
    snprintf(res_s, sizeof res_s, "%dx%d", o->width, o->height);
    snprintf(thr_s, sizeof thr_s, "%d", o->threads);
    snprintf(seed_s, sizeof seed_s, "%d", seed);
    char *argv[] = {(char *)bin, "render", path,   "-o",     (char *)out, "--spp",          spp_s,
                    "--res",     res_s,    "--threads", thr_s, "--seed",    seed_s, "--sampler", (char *)sampler,
                    NULL};
    if (!sampler)
        argv[13] = NULL;
    double cpu = run_cpu(argv);
    if (!o->scene_filter)
        unlink(path);
    return cpu;
}

static int read_rgb(const char *path, image_t *img)
{
    char err[512];
    if (image_read(path, img, err, sizeof err) != 0) {
        fprintf(stderr, "bench_efficiency: %s\n", err);
        return -1;
    }
    return img->channels >= 3 ? 0 : -1;
}

/* Mean squared error over RGB of a against the reference; its mean in *mean. */
static double mse(const image_t *a, const image_t *ref, double *mean)
{
    double e = 0.0, m = 0.0;
    size_t n = (size_t)ref->width * ref->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double r = ref->data[i * ref->channels + c], d = a->data[i * a->channels + c] - r;
            e += d * d, m += r;
        }
    *mean = m / (3.0 * n);
    return e / (3.0 * n);
}

static double loadavg(void)
{
    double l = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1.0;
        fclose(f);
    }
    return l;
}

/* The reference of a scene: rendered once, then kept. */
static int reference(const options *o, const char *scene, image_t *ref)
{
    char path[512];
    snprintf(path, sizeof path, "out/bench/efficiency/%s-%dx%d-%d%s.exr", scene, o->width, o->height, o->ref_spp,
             o->scene_filter ? "" : "-box");
    struct stat st;
    if (stat(path, &st) != 0) {
        printf("(rendering the %d-spp reference of %s with %s ...)\n", o->ref_spp, scene, o->ref_bin);
        fflush(stdout);
        double cpu = render(o, o->ref_bin, scene, o->ref_spp, 1000003, "zsobol", path);
        if (cpu < 0.0)
            return -1;
        printf("(reference: %.0f CPU seconds)\n", cpu);
    }
    return read_rgb(path, ref);
}

static int bench_scene(const options *o, const char *scene)
{
    image_t ref;
    if (reference(o, scene, &ref) != 0)
        return -1;
    double cpu[MAX_SPP][MAX_REPEAT], err[MAX_SPP][MAX_REPEAT], pair[MAX_SPP], img_mean[MAX_SPP], mean = 0.0;
    image_t prev[MAX_SPP];
    double l0 = loadavg();
    for (int r = 0; r < o->repeat; r++) /* the spp innermost: load drifts over all of them alike */
        for (int i = 0; i < o->nspp; i++) {
            const char *out = "out/bench/efficiency/run.exr";
            if ((cpu[i][r] = render(o, o->bin, scene, o->spp[i], 1 + r, o->sampler, out)) < 0.0)
                return -1;
            image_t img;
            if (read_rgb(out, &img) != 0 || img.width != ref.width || img.height != ref.height)
                return -1;
            err[i][r] = mse(&img, &ref, &mean);
            if (r == 0) {
                prev[i] = img;
                continue;
            }
            if (r == 1) /* the seed pair 1, 2 */
                pair[i] = 0.5 * mse(&img, &prev[i], &img_mean[i]);
            image_free(&img);
        }
    for (int i = 0; i < o->nspp; i++)
        image_free(&prev[i]);
    /* CPU = a + b spp, least squares over every run. */
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (int i = 0; i < o->nspp; i++)
        for (int r = 0; r < o->repeat; r++, n++)
            sx += o->spp[i], sy += cpu[i][r], sxx += (double)o->spp[i] * o->spp[i], sxy += o->spp[i] * cpu[i][r];
    double b = (n * sxy - sx * sy) / (n * sxx - sx * sx), a = (sy - b * sx) / n;
    printf("\n%s, %dx%d, %d threads, %s: reference mean %.4f; CPU = %.2f s + %.4f s/spp; load %.1f -> %.1f\n\n",
           scene, o->width, o->height, o->threads, o->bin, mean, a, b, l0, loadavg());
    printf("| spp | mean / reference's | RMSE vs reference | seed-pair RMSE | rel. | CPU s (mean of runs) | "
           "CPU s at %.4f s/spp | efficiency 1/(MSE x CPU s) |\n", b);
    printf("|----:|------:|------:|------:|-----:|------:|------:|------:|\n");
    double lx[MAX_SPP], ly[MAX_SPP];
    for (int i = 0; i < o->nspp; i++) {
        double m = 0.0, c = 0.0;
        for (int r = 0; r < o->repeat; r++)
            m += err[i][r] / o->repeat, c += cpu[i][r] / o->repeat;
        double t = b * o->spp[i], v = o->repeat > 1 ? pair[i] : m;
        printf("| %d | %.4f | %.5f | %.5f | %.4f | %.2f | %.2f | %.4g |\n", o->spp[i],
               o->repeat > 1 ? img_mean[i] / mean : 1.0, sqrt(m), sqrt(v), sqrt(v) / mean, c, t, 1.0 / (v * t));
        lx[i] = log((double)o->spp[i]), ly[i] = 0.5 * log(v);
    }
    if (o->nspp > 1) {
        double mx = 0, my = 0, cxy = 0, cxx = 0;
        for (int i = 0; i < o->nspp; i++)
            mx += lx[i] / o->nspp, my += ly[i] / o->nspp;
        for (int i = 0; i < o->nspp; i++)
            cxy += (lx[i] - mx) * (ly[i] - my), cxx += (lx[i] - mx) * (lx[i] - mx);
        printf("\nseed-pair RMSE ~ spp^%.2f", cxy / cxx);
        for (int i = 1; i < o->nspp; i++)
            printf("%s %d-%d: %.2f", i == 1 ? " (between" : ",", o->spp[i - 1], o->spp[i],
                   (ly[i] - ly[i - 1]) / (lx[i] - lx[i - 1]));
        printf(")\n");
    }
    fflush(stdout);
    image_free(&ref);
    return 0;
}

static int parse_list(const char *s, int *out, int max)
{
    int n = 0;
    for (const char *p = s; *p && n < max;) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end == p || v < 1)
            return -1;
        out[n++] = (int)v;
        p = *end == ',' ? end + 1 : end;
        if (*end && *end != ',')
            return -1;
    }
    return n;
}

int main(int argc, char **argv)
{
    const char *env_bin = getenv("CELADON_BIN");
    options o = {.bin = env_bin ? env_bin : "build/celadon", .ref_bin = "build/celadon", .scene_dir = "scenes", .width = 320,
                 .height = 180, .threads = 2, .repeat = 2, .ref_spp = 2048, .spp = {4, 16, 64}, .nspp = 3};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--scene-filter")) {
            o.scene_filter = 1;
            continue;
        }
        int ok = v != NULL;
        if (ok && !strcmp(a, "--bin"))
            o.bin = v;
        else if (ok && !strcmp(a, "--scene") && o.nscenes < MAX_SCENES)
            o.scenes[o.nscenes++] = v;
        else if (ok && !strcmp(a, "--res"))
            ok = sscanf(v, "%dx%d", &o.width, &o.height) == 2;
        else if (ok && !strcmp(a, "--spp"))
            ok = (o.nspp = parse_list(v, o.spp, MAX_SPP)) > 0;
        else if (ok && !strcmp(a, "--repeat"))
            ok = (o.repeat = atoi(v)) >= 1 && o.repeat <= MAX_REPEAT;
        else if (ok && !strcmp(a, "--ref-spp"))
            ok = (o.ref_spp = atoi(v)) >= 1;
        else if (ok && !strcmp(a, "--scenes"))
            o.scene_dir = v;
        else if (ok && !strcmp(a, "--sampler"))
            o.sampler = v;
        else if (ok && !strcmp(a, "--threads"))
            ok = (o.threads = atoi(v)) >= 1;
        else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "bench_efficiency: bad option %s (see the comment atop bench/bench_efficiency.c)\n", a);
            return 2;
        }
        i++;
    }
    if (o.nscenes == 0) {
        o.scenes[0] = "studio", o.scenes[1] = "cornell-sor", o.scenes[2] = "showcase";
        o.nscenes = 3;
    }
    mkdir("out", 0755);
    mkdir("out/bench", 0755);
    mkdir("out/bench/efficiency", 0755);
    for (int s = 0; s < o.nscenes; s++)
        if (bench_scene(&o, o.scenes[s]) != 0)
            return 1;
    return 0;
}
