/* celadon render: a Mitsuba 3 scene rendered with the path tracer to EXR
 * (float32, optional AOV channels) or PNG/JPEG (sRGB, 8-bit); under mpirun
 * shared among the ranks (distribute.h), as one part of several (parts.h),
 * and over a range of frames. */
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/denoise.h"
#include "celadon/distribute.h"
#include "celadon/parts.h"
#include "celadon/render.h"
#include "celadon/scene.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

enum { MAX_DEFINES = 64, MAX_FRAMES = 1000000, DEFAULT_PREVIEW_SECONDS = 10 };
_Static_assert(MAX_DEFINES == 64, "the -D limit's usage error names it");

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon render SCENE.xml -o OUT.{exr,hdr,tif,png,jpg} [--spp N] [--res WxH]\n"
               "                      [--geometry analytic|mesh:N] [--threads N] [--seed S]\n"
               "                      [--sampler NAME] [-D name=value]... [-a DIR]... [--aov LIST]\n"
               "                      [--part K/N] [--frames A:B[:S]] [--exposure STOPS] [--view standard|filmic]\n"
               "                      [--depth 8|16|32] [--crop X,Y,W,H] [--time SECONDS]\n"
               "                      [--preview FILE [--preview-every SECONDS]]\n\n"
               "Renders a Mitsuba 3 scene (docs/scene-format.md) with its integrator (`path`\n"
               "by default).\n"
               "SORs are intersected exactly unless --geometry mesh:N revolves them into N\n"
               "angular segments traced by Embree (same sampler seeds otherwise).\n\n"
               "  -o OUT          .exr (float32, the film's pixel_format + AOV channels), .hdr\n"
               "                  (Radiance), .tif (float32, or 8/16-bit with --depth), .png (8 or\n"
               "                  16-bit) or .jpg; every one with the render's metadata\n"
               "  --exposure S    PNG/JPEG/8-16-bit TIFF: values times 2^S first (default 0)\n"
               "  --view V        PNG/JPEG/8-16-bit TIFF: standard (sRGB, clipped; default) or\n"
               "                  filmic (highlights roll off over 6.5 stops above middle grey)\n"
               "  --depth B       bits per channel: PNG 8 or 16, TIFF 8, 16 or 32 (default: 8, TIFF 32)\n"
               "  --crop X,Y,W,H  render only that window of the film (its pixels as the full render's)\n"
               "  --time S        render passes until S seconds are spent (or the spp reached)\n"
               "  --preview FILE  write the image so far to FILE after a pass, every 10 s\n"
               "                  (--preview-every S) and at the end\n"
               "  --denoise       denoise the colour by a regression on the albedo, normal and\n"
               "                  depth, diffuse and specular apart, from two half renders\n"
               "                  (--denoise adds those AOVs, denoising, half, specular and\n"
               "                  variance, to an EXR)\n"
               "  --spp N         samples per pixel (default: the scene's sampler); also the\n"
               "                  value of $spp where the scene has no <default> for it\n"
               "  --res WxH       film size (default: the scene's film; at most 65536 on a side, 1e9 pixels)\n"
               "  --geometry G    analytic (default) or mesh:N, N >= 3\n"
               "  --threads N     OpenMP threads (default: all cores; per rank under mpirun)\n"
               "  --seed S        sampler seed (default: the scene's)\n"
               "  --sampler NAME  sampler plugin instead of the scene's, with its sample count and seed:\n"
               "                  independent, stratified, multijitter, orthogonal, ldsampler, zsobol\n"
               "  -D name=value   sets a scene <default> parameter\n"
               "  -a DIR, --append DIR\n"
               "                  one more folder to look for the scene's files in, after those the\n"
               "                  scene gives (Mitsuba's -a; DIR1;DIR2 gives two)\n"
               "  --aov LIST      extra EXR channels: depth (Z), normal (N.X/Y/Z), albedo (albedo.R/G/B),\n"
               "                  index (IndexOB.X, IndexMA.X), variance (variance.X), spp (spp.X),\n"
               "                  denoising (Denoising Albedo.R/G/B, Denoising Normal.X/Y/Z, Denoising\n"
               "                  Depth.Z: past mirrors and glass), half (half.R/G/B/A),\n"
               "                  specular (specular.R/G/B; with half, specular half.R/G/B)\n"
               "  --part K/N      render the K-th of N shares of the samples into OUT.exr, for\n"
               "                  `celadon merge` (docs/distributed.md)\n"
               "  --frames A:B:S  render frames A, A+S, ... below B (S defaults to 1), setting\n"
               "                  -D frame=F; each # run in OUT becomes the zero-padded frame\n"
               "Under mpirun (or srun) the ranks share the work and rank 0 writes OUT.\n"
               "Ctrl-C (or SIGHUP) finishes the pass under way and writes the image so far,\n"
               "labelled as interrupted (a second Ctrl-C stops at once); SIGTERM stops at once\n"
               "and writes it too.\n");
}

typedef struct {
    const char *scene_path, *out;
    scene_options bo;
    render_options ro;
    scene_define defs[MAX_DEFINES + 2]; /* + $spp's fallback + the frame's */
    int ndefs;
    char *dirs[CLI_MAX_SEARCH_DIRS]; /* -a folders, malloc'd */
    int ndirs;
    const char *spp; /* --spp's text, or NULL */
    render_part part; /* n == 0: the whole render */
    int frame_from, frame_to, frame_step, frames; /* frames == 0: no --frames */
    film_output output; /* --exposure, --view, --depth */
    int denoise;        /* --denoise */
    char command_line[2048];
} render_args;

static int is_exr(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && !(slash && dot < slash) && !strcasecmp(dot, ".exr");
}

/* "A:B" or "A:B:S": frames A, A+S, ... below B. */
static int parse_frames(const char *s, render_args *a)
{
    int from, to, step = 1, n = 0;
    if (sscanf(s, "%d:%d%n", &from, &to, &n) != 2)
        return -1;
    if (s[n] == ':') {
        int m = 0;
        if (sscanf(s + n + 1, "%d%n", &step, &m) != 1)
            return -1;
        n += 1 + m;
    }
    if (s[n] || step < 1 || to <= from || ((long long)to - from + step - 1) / step > MAX_FRAMES)
        return -1;
    a->frame_from = from, a->frame_to = to, a->frame_step = step;
    a->frames = (int)(((long long)to - from + step - 1) / step);
    return 0;
}

/* Parses the options; -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, render_args *a)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        long long v;
        if (!strcmp(arg, "-h") || !strcmp(arg, "--help")) {
            usage(stdout);
            return 0;
        }
        if (arg[0] != '-' || !arg[1]) {
            if (a->scene_path)
                return cli_usage_error("render", "unexpected argument '%s'", arg);
            a->scene_path = arg;
            continue;
        }
        if (!strcmp(arg, "--denoise")) {
            a->denoise = 1;
            continue;
        }
        if (!val)
            return cli_usage_error("render", "option %s needs a value", arg);
        i++;
        if (!strcmp(arg, "-o")) {
            a->out = val;
        } else if (!strcmp(arg, "--spp")) {
            if (cli_parse_int(val, 1, 1 << 24, &v) != 0)
                return cli_usage_error("render", "--spp wants an integer from 1 to 16777216, not '%s'", val);
            a->bo.spp = (int)v;
            a->spp = val;
        } else if (!strcmp(arg, "--res")) {
            int w, h, n = 0;
            if (sscanf(val, "%dx%d%n", &w, &h, &n) != 2 || val[n] || w < 1 || h < 1 || w > 65536 || h > 65536)
                return cli_usage_error("render", "--res wants WxH with sizes from 1 to 65536, not '%s'", val);
            a->bo.width = w, a->bo.height = h;
        } else if (!strcmp(arg, "--geometry")) {
            if (!strcmp(val, "analytic"))
                a->bo.mesh_segments = 0;
            else if (!strncmp(val, "mesh:", 5) && cli_parse_int(val + 5, 3, 1000000, &v) == 0)
                a->bo.mesh_segments = (int)v;
            else
                return cli_usage_error("render", "--geometry wants analytic or mesh:N with N from 3 to 1000000, not '%s'", val);
        } else if (!strcmp(arg, "--threads")) {
            if (cli_parse_int(val, 1, 1024, &v) != 0)
                return cli_usage_error("render", "--threads wants an integer from 1 to 1024, not '%s'", val);
            a->ro.threads = (int)v;
        } else if (!strcmp(arg, "--seed")) {
            if (cli_parse_int(val, 0, (long long)(~0ull >> 1), &v) != 0)
                return cli_usage_error("render", "--seed wants a non-negative integer, not '%s'", val);
            a->bo.seed = v;
        } else if (!strcmp(arg, "--sampler")) {
            if (!scene_plugin_find(SCENE_SAMPLER, val))
                return cli_usage_error("render", "--sampler wants independent, stratified, multijitter, orthogonal, "
                                                 "ldsampler or zsobol, not '%s'", val);
            a->bo.sampler = val;
        } else if (!strcmp(arg, "-D")) {
            const char *eq = strchr(val, '=');
            if (!eq || eq == val)
                return cli_usage_error("render", "-D wants name=value, not '%s'", val);
            if (a->ndefs == MAX_DEFINES)
                return cli_usage_error("render", "at most 64 -D, not more ('%s')", val);
            char *name = strndup(val, (size_t)(eq - val));
            if (!name)
                return 1;
            a->defs[a->ndefs++] = (scene_define){name, eq + 1, false};
        } else if (!strcmp(arg, "-a") || !strcmp(arg, "--append")) {
            int rc = cli_add_search_dirs("render", val, a->dirs, &a->ndirs);
            if (rc != 0)
                return rc;
        } else if (!strcmp(arg, "--aov")) {
            if (render_aov_parse(val, &a->ro.aovs) != 0)
                return cli_usage_error("render", "--aov wants a list of depth, normal, albedo, index, variance, spp, denoising, half, "
                                                 "specular, "
                                                 "not '%s'", val);
        } else if (!strcmp(arg, "--part")) {
            if (render_part_parse(val, &a->part) != 0)
                return cli_usage_error("render", "--part wants K/N with 1 <= K <= N <= 1000000, not '%s'", val);
        } else if (!strcmp(arg, "--crop")) {
            int x, y, w, h, n = 0;
            if (sscanf(val, "%d,%d,%d,%d%n", &x, &y, &w, &h, &n) != 4 || val[n] || x < 0 || y < 0 || w < 1 || h < 1)
                return cli_usage_error("render", "--crop wants X,Y,W,H with X, Y >= 0 and W, H >= 1, not '%s'", val);
            a->bo.crop_x = x, a->bo.crop_y = y, a->bo.crop_w = w, a->bo.crop_h = h;
        } else if (!strcmp(arg, "--time")) {
            char *end;
            double t = strtod(val, &end);
            if (end == val || *end || !(t > 0 && t <= 1e7))
                return cli_usage_error("render", "--time wants seconds from 0 to 1e7, not '%s'", val);
            a->ro.time_budget = t;
        } else if (!strcmp(arg, "--preview")) {
            a->ro.preview = val;
        } else if (!strcmp(arg, "--preview-every")) {
            char *end;
            double t = strtod(val, &end);
            if (end == val || *end || !(t >= 0 && t <= 1e7))
                return cli_usage_error("render", "--preview-every wants seconds from 0 to 1e7, not '%s'", val);
            a->ro.preview_seconds = t;
        } else if (!strcmp(arg, "--exposure")) {
            char *end;
            double e = strtod(val, &end);
            if (end == val || *end || !(e >= -32 && e <= 32))
                return cli_usage_error("render", "--exposure wants stops from -32 to 32, not '%s'", val);
            a->output.exposure = e;
        } else if (!strcmp(arg, "--view")) {
            if (film_view_parse(val, &a->output.view) != 0)
                return cli_usage_error("render", "--view wants standard or filmic, not '%s'", val);
        } else if (!strcmp(arg, "--depth")) {
            if (cli_parse_int(val, 8, 32, &v) != 0 || (v != 8 && v != 16 && v != 32))
                return cli_usage_error("render", "--depth wants 8, 16 or 32, not '%s'", val);
            a->output.depth = (int)v;
        } else if (!strcmp(arg, "--frames")) {
            if (parse_frames(val, a) != 0)
                return cli_usage_error("render", "--frames wants A:B or A:B:S with A < B and S >= 1, not '%s'", val);
        } else {
            return cli_usage_error("render", "unknown option '%s'", arg);
        }
    }
    /* --spp N is also $spp where the scene leaves it to the command line. */
    int has_spp = 0;
    for (int i = 0; i < a->ndefs; i++)
        has_spp |= !strcmp(a->defs[i].name, "spp");
    if (a->spp && !has_spp && !(a->defs[a->ndefs++] = (scene_define){strdup("spp"), a->spp, true}).name)
        return 1;
    char why[1200];
    if (!a->scene_path)
        return cli_usage_error("render", "%s", "missing SCENE.xml");
    if (!a->out)
        return cli_usage_error("render", "%s", "missing -o OUT");
    if (film_output_check(a->out, a->output.depth, why, sizeof why) != 0)
        return cli_usage_error("render", "%s", why);
    if (a->ro.aovs && !is_exr(a->out))
        return cli_usage_error("render", "--aov needs an .exr output, not '%s'", a->out);
    if (a->ro.preview && film_output_check(a->ro.preview, 0, why, sizeof why) != 0)
        return cli_usage_error("render", "--preview: %s", why);
    if (a->ro.preview && !strcmp(a->ro.preview, a->out))
        return cli_usage_error("render", "%s", "--preview names the output itself");
    if (a->part.n && (a->ro.time_budget > 0 || a->ro.preview))
        return cli_usage_error("render", "%s", "--part renders a fixed share of the samples: no --time or --preview");
    if (a->part.n && !is_exr(a->out))
        return cli_usage_error("render", "--part writes an .exr (its header names the part), not '%s'", a->out);
    if (a->part.n && a->denoise)
        return cli_usage_error("render", "%s", "--part writes a share of the samples: denoise the merged image "
                                               "(celadon denoise)");
    if (a->denoise)
        a->ro.aovs |= RENDER_AOV_DENOISING | RENDER_AOV_HALF | RENDER_AOV_SPECULAR | RENDER_AOV_VARIANCE;
    if (a->frames && !strchr(a->out, '#'))
        return cli_usage_error("render", "--frames needs a run of # in the output name for the frame, not '%s'",
                               a->out);
    for (int i = 0; i < a->ndefs && a->frames; i++)
        if (!strcmp(a->defs[i].name, "frame"))
            return cli_usage_error("render", "%s", "--frames sets -D frame itself");
    return -1;
}

/* The output name of frame f: each run of # replaced by f, zero-padded to
 * the run's length. */
static void frame_path(const char *pattern, int frame, char *out, size_t outlen)
{
    size_t n = 0;
    for (const char *p = pattern; *p && n + 1 < outlen;) {
        size_t run = strspn(p, "#");
        if (run) {
            n += (size_t)snprintf(out + n, outlen - n, "%0*d", (int)run, frame);
            p += run;
        } else {
            out[n++] = *p++;
        }
        if (n >= outlen)
            n = outlen - 1;
    }
    out[n] = '\0';
}

/* The last stopping signal received (0: none). */
static volatile sig_atomic_t stop_signal;

/* SIGINT and SIGHUP finish the pass under way (a second one stops at
 * once); SIGTERM stops after the samples in flight. Either way the image
 * so far is written, labelled as interrupted. */
static void on_stop(int sig)
{
    if (sig == SIGTERM)
        render_request_stop_now();
    else
        render_request_stop();
    stop_signal = sig;
}

/* "celadon render ARGS", each argument that needs it in single quotes:
 * the command line the image's metadata records. */
static void command_line(int argc, char **argv, char *out, size_t outlen)
{
    size_t n = (size_t)snprintf(out, outlen, "celadon");
    for (int i = 0; i < argc && n < outlen; i++) {
        const char *arg = argv[i];
        int plain = arg[0] && strspn(arg, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                          "-_./=:,+%@#") == strlen(arg);
        n += (size_t)snprintf(out + n, outlen - n, plain ? " %s" : " '%s'", arg);
    }
}

/* Writes the image (or the part) of a finished render: 0, 1 on failure,
 * 128 + the signal when one stopped it. */
static int write_result(const render_args *a, const scene_t *scene, film_t *film, const render_stats *st,
                        const char *out)
{
    char err[2048];
    snprintf(film->meta.scene_path, sizeof film->meta.scene_path, "%s", a->scene_path);
    snprintf(film->meta.command_line, sizeof film->meta.command_line, "%s", a->command_line);
    if (a->denoise && denoise_film(film, err, sizeof err) != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return 1;
    }
    int rc = a->part.n ? render_part_write(film, scene, a->part, !st->interrupted, out, err, sizeof err)
                       : film_write_as(film, out, &a->output, err, sizeof err);
    if (rc != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return 1;
    }
    if (st->interrupted)
        fprintf(stderr, "celadon: interrupted; wrote the partial %s %s\n", a->part.n ? "part" : "image", out);
    return stop_signal ? 128 + stop_signal : 0;
}

/* The frame the i-th render of the command shows (0 without --frames). */
static int frame_number(const render_args *a, int i) { return a->frames ? a->frame_from + i * a->frame_step : 0; }

/* The scene of the i-th render (with -D frame=F under --frames) and, with
 * --part, its share of the samples: NULL with the reason in err. */
static scene_t *build_scene(render_args *a, int i, int *s0, int *s1, char *err, size_t errlen)
{
    char value[16];
    if (a->frames) {
        snprintf(value, sizeof value, "%d", frame_number(a, i));
        a->defs[a->ndefs++] = (scene_define){"frame", value, false};
    }
    scene_t *scene = scene_create_from_file(a->scene_path, a->defs, a->ndefs, &a->bo, err, errlen);
    if (a->frames)
        a->ndefs--;
    *s0 = *s1 = 0;
    if (scene && a->part.n && render_part_samples(a->part, scene_spp(scene), s0, s1) != 0) {
        snprintf(err, errlen, "%s: part %d/%d of a render of %d spp gets no samples: use at most %d parts",
                 a->scene_path, a->part.k, a->part.n, scene_spp(scene), scene_spp(scene));
        scene_destroy(scene);
        scene = NULL;
    }
    return scene;
}

/* The first render's scene, built in a thread of its own while the main
 * thread joins the MPI job (MPI_Init waits for every rank to start:
 * 0.15-0.4 s of wall time and little CPU, docs/distributed.md). */
typedef struct {
    render_args *a;
    scene_t *scene;
    int s0, s1;
    char err[2048];
    pthread_t thread;
} scene_build;

static void *scene_build_main(void *arg)
{
    scene_build *b = arg;
    b->scene = build_scene(b->a, 0, &b->s0, &b->s1, b->err, sizeof b->err);
    return NULL;
}

/* Renders b's scene (built on every rank; NULL with the reason in b->err
 * when it could not be), and rank 0 writes out; frees the scene. */
static int render_one(render_args *a, const distribute_job *job, scene_build *b, const char *out)
{
    int failed = distribute_first_failure(b->scene != NULL);
    if (failed >= 0) {
        if (failed == job->rank && failed != 0)
            fprintf(stderr, "celadon: rank %d: %s\n", job->rank, b->err);
        else if (failed == job->rank)
            fprintf(stderr, "celadon: %s\n", b->err);
        scene_destroy(b->scene);
        b->scene = NULL;
        return 2;
    }
    a->ro.sample_begin = b->s0, a->ro.sample_end = b->s1;
    film_t film;
    render_stats st;
    int rc = distribute_render(b->scene, &a->ro, &film, &st, b->err, sizeof b->err);
    if (rc != 0) {
        if (b->err[0])
            fprintf(stderr, "celadon: %s\n", b->err);
        rc = 1;
    } else {
        if (job->rank == 0) {
            rc = write_result(a, b->scene, &film, &st, out);
            film_free(&film);
        }
        /* Every rank ends (or goes on to the next frame) with rank 0. */
        if (distribute_first_failure(job->rank != 0 || rc == 0) >= 0 && job->rank != 0)
            rc = st.interrupted ? 128 + (stop_signal ? stop_signal : SIGINT) : 1;
    }
    scene_destroy(b->scene);
    b->scene = NULL;
    return rc;
}

/* Every frame in turn (or the one render), until one fails or is stopped;
 * b holds the first one's scene. */
static int render_frames(render_args *a, const distribute_job *job, scene_build *b)
{
    int rc = 0;
    for (int i = 0; i < (a->frames ? a->frames : 1) && rc == 0; i++) {
        char out[4096];
        if (i > 0)
            b->scene = build_scene(a, i, &b->s0, &b->s1, b->err, sizeof b->err);
        if (a->frames)
            frame_path(a->out, frame_number(a, i), out, sizeof out);
        rc = render_one(a, job, b, a->frames ? out : a->out);
    }
    return rc;
}

int cmd_render(int argc, char **argv)
{
    render_args a = {.bo = scene_options_default()};
    /* The launcher's environment gives the rank before MPI_Init. */
    int rank = distribute_launched_rank();
    cli_set_quiet(rank != 0); /* every rank would print the same usage error */
    a.ro.progress = rank == 0;
    a.ro.preview_seconds = DEFAULT_PREVIEW_SECONDS;
    int rc = parse_args(argc, argv, &a);
    a.bo.search_dirs = (const char *const *)a.dirs;
    a.bo.n_search_dirs = a.ndirs;
    if (rc < 0 && cli_check_output(a.out, 0) != 0)
        rc = CLI_CANNOT_WRITE; /* every rank checks: they all stop */
    /* From here Ctrl-C asks for the image so far (an empty one while
     * loading); under mpirun, which turns Ctrl-C into SIGTERM to every rank,
     * SIGTERM does too. */
    struct sigaction sa, old_int, old_term, old_hup;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    sigaction(SIGHUP, &sa, &old_hup);
    scene_build b = {.a = &a};
    int building = rc < 0 && pthread_create(&b.thread, NULL, scene_build_main, &b) == 0;
    if (rc < 0 && !building)
        scene_build_main(&b);
    distribute_job job;
    char err[1024];
    int joined = distribute_begin(&job, err, sizeof err) == 0;
    if (building)
        pthread_join(b.thread, NULL);
    if (!joined) {
        if (err[0])
            fprintf(stderr, "celadon: %s\n", err);
        rc = 2;
    } else if (rc < 0 && job.size > 1 && (a.ro.time_budget > 0 || a.ro.preview)) {
        rc = cli_usage_error("render", "%s", "--time and --preview are for one process, not under mpirun");
    }
    if (rc < 0) {
        command_line(argc, argv, a.command_line, sizeof a.command_line);
        rc = render_frames(&a, &job, &b);
    } else {
        scene_destroy(b.scene);
    }
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    sigaction(SIGHUP, &old_hup, NULL);
    for (int i = 0; i < a.ndefs; i++)
        free((char *)a.defs[i].name);
    for (int i = 0; i < a.ndirs; i++)
        free(a.dirs[i]);
    distribute_end();
    return rc;
}
