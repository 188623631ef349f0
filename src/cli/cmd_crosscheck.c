/* celadon crosscheck: a scene rendered analytic and meshed at several segment
 * counts with identical seeds; images, report.json and a convergence plot in
 * one folder, which appears whole or not at all (built in a hidden sibling
 * folder and renamed into place). */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/crosscheck.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

enum { MAX_DEFINES = 64, MAX_SEGMENTS = 32, PLOT_W = 900, PLOT_H = 600 };
_Static_assert(MAX_DEFINES == 64, "the -D limit's usage error names it");

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon crosscheck SCENE.xml --segments N1,N2,... -o DIR [--spp N] [--res WxH]\n"
               "                          [--threads N] [--seed S] [--grid K] [--fit-from N]\n"
               "                          [-D name=value]... [-a DIR[;DIR]]... [--part K/N | --merge PARTDIR...]\n\n"
               "Renders the scene with its SORs intersected exactly and revolved into each N\n"
               "angular segments (same sampler seeds), and measures how the meshed images and\n"
               "first hits converge to the analytic ones (docs/crosscheck.md). DIR receives\n"
               "analytic.{exr,png}, mesh-N.{exr,png}, report.json and convergence.png.\n\n"
               "  --segments L    at least two increasing segment counts >= 3 (e.g. 16,64,256,1024)\n"
               "  -o DIR          output folder (new, empty, or an earlier crosscheck's, replaced)\n"
               "  --spp N         samples per pixel (default: the scene's sampler)\n"
               "  --res WxH       film size (default: the scene's film)\n"
               "  --threads N     OpenMP threads (default: all cores)\n"
               "  --seed S        sampler seed shared by every render (default: the scene's)\n"
               "  --grid K        K x K primary rays per pixel for the geometry metrics (default 4)\n"
               "  --fit-from N    fit the slopes over the segment counts >= N only (default: all),\n"
               "                  e.g. to leave out coarse meshes outside the asymptotic range\n"
               "  -D name=value   sets a scene <default> parameter\n"
               "  -a DIR[;DIR]    more folders to look for the scene's files in (Mitsuba's -a)\n"
               "  --part K/N      render only the K-th of N shares of every render's samples into\n"
               "                  DIR (analytic.exr, mesh-N.exr parts: docs/distributed.md)\n"
               "  --merge DIR...  merge the renders from the folders of all N parts, then measure\n");
}

/* "16,64,256": strictly increasing counts from 3 to 1000000. */
static int parse_segments(const char *s, int *out, int *n)
{
    char buf[512];
    if (snprintf(buf, sizeof buf, "%s", s) >= (int)sizeof buf)
        return -1;
    *n = 0;
    char *save, *tok = strtok_r(buf, ",", &save);
    for (; tok; tok = strtok_r(NULL, ",", &save)) {
        long long v;
        if (*n == MAX_SEGMENTS || cli_parse_int(tok, 3, 1000000, &v) != 0 || (*n > 0 && v <= out[*n - 1]))
            return -1;
        out[(*n)++] = (int)v;
    }
    return *n >= 2 ? 0 : -1;
}

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_tree(const char *dir) { nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

/* 0: dir does not exist; 1: empty; 2: holds a report.json or an
 * analytic.exr (an earlier crosscheck, or part of one); -1: something else
 * is there. */
static int out_dir_state(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) != 0)
        return errno == ENOENT ? 0 : -1;
    if (!S_ISDIR(st.st_mode))
        return -1;
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int entries = 0, report = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            entries++;
            report |= !strcmp(e->d_name, "report.json") || !strcmp(e->d_name, "analytic.exr");
        }
    closedir(d);
    return !entries ? 1 : report ? 2 : -1;
}

/* A hidden sibling folder of dir to build the outputs in. */
static int make_staging(const char *dir, char *out, size_t outlen)
{
    char a[4096], b[4096];
    snprintf(a, sizeof a, "%s", dir);
    snprintf(b, sizeof b, "%s", dir);
    if (snprintf(out, outlen, "%s/.%s.crosscheck-XXXXXX", dirname(a), basename(b)) >= (int)outlen)
        return -1;
    if (!mkdtemp(out))
        return -1;
    mode_t mask = umask(0); /* mkdtemp makes it 0700; give it a plain folder's mode */
    umask(mask);
    return chmod(out, 0777 & ~mask);
}

/* Moves the finished staging folder to dir (replacing an earlier crosscheck). */
static int install(const char staging[4200], const char *dir, int state)
{
    if (state != 2)
        return rename(staging, dir);
    char old[4300];
    snprintf(old, sizeof old, "%s.old", staging);
    if (rename(dir, old) != 0)
        return -1;
    if (rename(staging, dir) != 0) {
        rename(old, dir);
        return -1;
    }
    remove_tree(old);
    return 0;
}

static int run(crosscheck_params *p, render_part part, const char *dir)
{
    if (cli_check_output(dir, 1) != 0)
        return CLI_CANNOT_WRITE;
    int state = out_dir_state(dir);
    if (state < 0) {
        fprintf(stderr, "celadon crosscheck: %s exists and is not empty nor an earlier crosscheck's folder\n", dir);
        return 2;
    }
    char staging[4200], err[2048], path[4400];
    if (make_staging(dir, staging, sizeof staging) != 0) {
        fprintf(stderr, "celadon crosscheck: cannot create a folder next to %s: %s\n", dir, strerror(errno));
        return CLI_CANNOT_WRITE;
    }
    crosscheck_result res = {0};
    int rc = part.n ? crosscheck_render_part(p, part, staging, err, sizeof err)
                    : crosscheck_run(p, staging, &res, err, sizeof err);
    if (rc == 0 && !part.n) {
        snprintf(path, sizeof path, "%s/report.json", staging);
        rc = crosscheck_write_report(&res, p, path, err, sizeof err);
    }
    if (rc == 0 && !part.n) {
        snprintf(path, sizeof path, "%s/convergence.png", staging);
        rc = crosscheck_write_plot(&res, path, PLOT_W, PLOT_H, err, sizeof err);
    }
    if (rc == 0 && install(staging, dir, state) != 0) {
        snprintf(err, sizeof err, "cannot move the results to %s: %s", dir, strerror(errno));
        rc = -1;
    }
    if (rc != 0) {
        remove_tree(staging);
        fprintf(stderr, "celadon: %s\n", err);
    } else if (part.n) {
        printf("crosscheck: wrote part %d/%d of the analytic and the %d meshed renders into %s\n", part.k, part.n,
               p->nsegments, dir);
    } else {
        printf("crosscheck: %dx%d, %d spp, analytic %.2f s; slopes", res.width, res.height, res.spp,
               res.analytic_seconds);
        if (res.fit_from > p->segments[0])
            printf(" over N >= %d", res.fit_from);
        for (int m = 0; m < CROSSCHECK_METRIC_COUNT; m++)
            printf("%s %s %.2f", m ? "," : ":", crosscheck_metric_name(m), res.fits[m].slope);
        printf("\ncrosscheck: %s between successive N:", crosscheck_metric_name(CROSSCHECK_PRIMARY_METRIC));
        for (int i = 1; i < res.nrows; i++)
            printf(" %.2f", crosscheck_local_slope(res.rows, i, CROSSCHECK_PRIMARY_METRIC));
        printf("\ncrosscheck: wrote %s/report.json and %s/convergence.png\n", dir, dir);
        const crosscheck_stall *st = &res.stall;
        if (st->found)
            fprintf(stderr,
                    "crosscheck: note: from N = %d to %d the image error fell as N^%.2f while the depth error fell "
                    "as N^%.2f: something no segment count changes is left in the images: coincident surfaces "
                    "(z-fighting, e.g. a vessel standing exactly in another surface) or the noise of the few "
                    "samples that changed course (more --spp); docs/crosscheck.md\n",
                    st->n_from, st->n_to, st->image_slope, st->depth_slope);
    }
    crosscheck_result_free(&res);
    return rc == 0 ? 0 : rc == -2 ? 2 : 1;
}

int cmd_crosscheck(int argc, char **argv)
{
    const char *dir = NULL, **part_dirs = calloc((size_t)argc, sizeof *part_dirs);
    int segments[MAX_SEGMENTS], nseg = 0, merge = 0, nextra = 0;
    render_part part = {0, 0};
    if (!part_dirs)
        return 1;
    scene_define defs[MAX_DEFINES];
    char *dirs[CLI_MAX_SEARCH_DIRS];
    int ndirs = 0;
    crosscheck_params p = {.defs = defs, .build = scene_options_default(), .segments = segments, .geo_grid = 4,
                           .progress = 1};
    int rc = -1;
    for (int i = 1; i < argc && rc < 0; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        long long v;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            rc = 0;
        } else if (a[0] != '-' || !a[1]) {
            if (p.scene_path)
                part_dirs[nextra++] = a;
            else
                p.scene_path = a;
        } else if (!strcmp(a, "--merge")) {
            merge = 1;
        } else if (!val) {
            rc = cli_usage_error("crosscheck", "option %s needs a value", a);
        } else if (i++, !strcmp(a, "-o")) {
            dir = val;
        } else if (!strcmp(a, "--segments")) {
            if (parse_segments(val, segments, &nseg) != 0)
                rc = cli_usage_error("crosscheck", "--segments wants at least two increasing counts from 3 to 1000000, not '%s'",
                                 val);
        } else if (!strcmp(a, "--spp")) {
            if (cli_parse_int(val, 1, 1 << 24, &v) != 0)
                rc = cli_usage_error("crosscheck", "--spp wants an integer from 1 to 16777216, not '%s'", val);
            p.build.spp = (int)v;
        } else if (!strcmp(a, "--res")) {
            int w, h, n = 0;
            if (sscanf(val, "%dx%d%n", &w, &h, &n) != 2 || val[n] || w < 1 || h < 1 || w > 65536 || h > 65536)
                rc = cli_usage_error("crosscheck", "--res wants WxH with sizes from 1 to 65536, not '%s'", val);
            p.build.width = w, p.build.height = h;
        } else if (!strcmp(a, "--threads")) {
            if (cli_parse_int(val, 1, 1024, &v) != 0)
                rc = cli_usage_error("crosscheck", "--threads wants an integer from 1 to 1024, not '%s'", val);
            p.threads = (int)v;
        } else if (!strcmp(a, "--seed")) {
            if (cli_parse_int(val, 0, (long long)(~0ull >> 1), &v) != 0)
                rc = cli_usage_error("crosscheck", "--seed wants a non-negative integer, not '%s'", val);
            p.build.seed = v;
        } else if (!strcmp(a, "--grid")) {
            if (cli_parse_int(val, 1, 64, &v) != 0)
                rc = cli_usage_error("crosscheck", "--grid wants an integer from 1 to 64, not '%s'", val);
            p.geo_grid = (int)v;
        } else if (!strcmp(a, "--fit-from")) {
            if (cli_parse_int(val, 3, 1000000, &v) != 0)
                rc = cli_usage_error("crosscheck", "--fit-from wants a segment count from 3 to 1000000, not '%s'", val);
            p.fit_from = (int)v;
        } else if (!strcmp(a, "--part")) {
            if (render_part_parse(val, &part) != 0)
                rc = cli_usage_error("crosscheck", "--part wants K/N with 1 <= K <= N <= 1000000, not '%s'", val);
        } else if (!strcmp(a, "-D")) {
            const char *eq = strchr(val, '=');
            if (!eq || eq == val)
                rc = cli_usage_error("crosscheck", "-D wants name=value, not '%s'", val);
            else if (p.ndefs == MAX_DEFINES)
                rc = cli_usage_error("crosscheck", "at most 64 -D, not more ('%s')", val);
            else if (!(defs[p.ndefs].name = strndup(val, (size_t)(eq - val))))
                rc = 1;
            else
                defs[p.ndefs].fallback = false, defs[p.ndefs++].value = eq + 1;
        } else if (!strcmp(a, "-a") || !strcmp(a, "--append")) {
            rc = cli_add_search_dirs("crosscheck", val, dirs, &ndirs);
            rc = rc == 0 ? -1 : rc;
        } else {
            rc = cli_usage_error("crosscheck", "unknown option '%s'", a);
        }
    }
    if (rc < 0) {
        if (!p.scene_path)
            rc = cli_usage_error("crosscheck", "%s", "missing SCENE.xml");
        else if (!nseg)
            rc = cli_usage_error("crosscheck", "%s", "missing --segments N1,N2,...");
        else if (!dir || !*dir)
            rc = cli_usage_error("crosscheck", "%s", "missing -o DIR");
        else if (nextra && !merge)
            rc = cli_usage_error("crosscheck", "unexpected argument '%s'", part_dirs[0]);
        else if (merge && !nextra)
            rc = cli_usage_error("crosscheck", "%s", "--merge wants the folders of the parts");
        else if (merge && part.n)
            rc = cli_usage_error("crosscheck", "%s", "--part renders a part, --merge merges them: not both");
    }
    if (rc < 0) {
        p.nsegments = nseg;
        p.build.search_dirs = (const char *const *)dirs, p.build.n_search_dirs = ndirs;
        p.part_dirs = part_dirs, p.npart_dirs = nextra;
        rc = run(&p, part, dir);
    }
    free(part_dirs);
    for (int i = 0; i < p.ndefs; i++)
        free((char *)defs[i].name);
    for (int i = 0; i < ndirs; i++)
        free(dirs[i]);
    return rc;
}
