/* The render loop: passes of samples over 16x16 tiles shared out to OpenMP
 * threads, each pixel sample with its own stream of the sampler, a progress
 * bar, and a stop request (SIGINT) honoured after the sample in progress.
 * render_scene is the one-process driver; render_loop.h gives the pieces to
 * the others (distribute_mpi.c). */
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "render/render_loop.h"
#include "render/scene_impl.h"

enum { TILE = 16 };

static volatile sig_atomic_t stop_requested;

void render_request_stop(void) { stop_requested = 1; }

int render_aov_parse(const char *list, unsigned *mask)
{
    *mask = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    char *save, *tok = strtok_r(buf, ",", &save);
    if (!tok)
        return -1;
    for (; tok; tok = strtok_r(NULL, ",", &save)) {
        if (!strcmp(tok, "depth"))
            *mask |= RENDER_AOV_DEPTH;
        else if (!strcmp(tok, "normal"))
            *mask |= RENDER_AOV_NORMAL;
        else if (!strcmp(tok, "albedo"))
            *mask |= RENDER_AOV_ALBEDO;
        else
            return -1;
    }
    return 0;
}

static double thread_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Film values of one sample: RGB, then the requested AOVs in order. */
static int pack_values(rgb L, const double *aov, unsigned mask, double *out)
{
    int n = 0;
    out[n++] = L.r, out[n++] = L.g, out[n++] = L.b;
    if (mask & RENDER_AOV_DEPTH)
        out[n++] = aov[INTEGRATOR_AOV_DEPTH];
    for (int i = 0; i < 3 && (mask & RENDER_AOV_NORMAL); i++)
        out[n++] = aov[INTEGRATOR_AOV_NORMAL + i];
    for (int i = 0; i < 3 && (mask & RENDER_AOV_ALBEDO); i++)
        out[n++] = aov[INTEGRATOR_AOV_ALBEDO + i];
    return n;
}

/* Samples [s0, s1) of every pixel of a tile; a stop request ends it after
 * the sample in progress. Returns the number of samples taken. */
static uint64_t render_tile(const scene_t *s, film_t *film, unsigned aovs, int tx, int ty, int s0, int s1)
{
    const camera_t *cam = &s->camera;
    integrator_scene sc = {&s->shapes, &s->emitters};
    uint64_t n = 0;
    double aov[INTEGRATOR_AOV_COUNT], vals[3 + INTEGRATOR_AOV_COUNT];
    for (int y = ty; y < ty + TILE && y < cam->height; y++)
        for (int x = tx; x < tx + TILE && x < cam->width; x++)
            for (int k = s0; k < s1; k++) {
                if (stop_requested)
                    return n;
                sampler_stream smp;
                sampler_start(&s->sampler, &smp, (uint32_t)x, (uint32_t)y, (uint32_t)k);
                sampler_seek(&smp, SAMPLER_DIM_FILM);
                vec2 film_pos = sampler_next_2d(&smp);
                camera_ray_t cr = camera_ray(cam, x, y, film_pos.x, film_pos.y);
                rgb L = integrator_li(s->integrator, &sc, &cr.ray, cr.tmin, cr.tmax, &smp, aovs ? aov : NULL);
                pack_values(L, aov, aovs, vals);
                film_add(film, x, y, vals, 1.0);
                n++;
            }
    return n;
}

int render_film_init(const scene_t *s, unsigned aovs, film_t *film, char *err, size_t errlen)
{
    /* The channels as Mitsuba's aov integrator names them. */
    static const char *const t[1] = {"T"}, *const xyz[3] = {"X", "Y", "Z"}, *const rgb[3] = {"R", "G", "B"};
    film_aov list[3];
    int naov = 0;
    if (aovs & RENDER_AOV_DEPTH)
        list[naov++] = (film_aov){"depth", 1, t};
    if (aovs & RENDER_AOV_NORMAL)
        list[naov++] = (film_aov){"normal", 3, xyz};
    if (aovs & RENDER_AOV_ALBEDO)
        list[naov++] = (film_aov){"albedo", 3, rgb};
    return film_init(film, s->camera.width, s->camera.height, list, naov, err, errlen);
}

void render_sample_range(const scene_t *s, const render_options *opt, int *s0, int *s1)
{
    int all = opt->sample_begin == 0 && opt->sample_end == 0;
    *s0 = all ? 0 : opt->sample_begin;
    *s1 = all ? scene_spp(s) : opt->sample_end;
}

int render_thread_count(const render_options *opt)
{
    return opt->threads > 0 ? opt->threads : omp_get_max_threads();
}

bool render_stop_requested(void) { return stop_requested != 0; }
void render_stop_clear(void) { stop_requested = 0; }

void render_samples(const scene_t *s, int threads, unsigned aovs, film_t *film, int s0, int s1, int y0, int y1,
                    render_tally *tally)
{
    const camera_t *cam = &s->camera;
    int tiles_x = (cam->width + TILE - 1) / TILE, ty0 = y0 / TILE, tiles_y = (y1 + TILE - 1) / TILE - ty0;
    int ntiles = tiles_x * tiles_y, team = 1;
    double busy = 0.0, most = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : busy) reduction(max : most)
    {
        double mine = 0.0; /* this thread's CPU seconds in tiles */
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < ntiles; t++) {
            if (stop_requested)
                continue;
            int tx = (t % tiles_x) * TILE, ty = (ty0 + t / tiles_x) * TILE;
            double c0 = thread_cpu_seconds();
            uint64_t add = render_tile(s, film, aovs, tx, ty, s0, s1);
            mine += thread_cpu_seconds() - c0;
            uint64_t now = atomic_fetch_add(&tally->taken, add) + add;
            if (tally->bar && omp_get_thread_num() == 0) {
                char extra[64];
                double el = now_seconds() - tally->t_start;
                snprintf(extra, sizeof extra, "%.2f Msamples/s", el > 0 ? 1e-6 * (double)now / el : 0.0);
                progress_update(tally->bar, now, extra);
            }
        }
        busy += mine, most = mine;
#pragma omp master
        team = omp_get_num_threads();
    }
    /* Every thread waits at the end of the pass for the one with the most. */
    tally->busy_cpu_seconds += busy;
    tally->idle_cpu_seconds += team * most - busy;
}

void render_print_summary(const scene_t *s, const render_options *opt, const render_stats *st, const char *who)
{
    const camera_t *cam = &s->camera;
    int s0, s1;
    render_sample_range(s, opt, &s0, &s1);
    char share[64] = "";
    if (s1 - s0 != scene_spp(s))
        snprintf(share, sizeof share, " (samples %d-%d of %d)", s0, s1 - 1, scene_spp(s));
    double secs = st->seconds;
    fprintf(stderr, "render: %dx%d, %d spp%s, %s: %.2f s, %.2f Msamples/s%s\n", cam->width, cam->height, s1 - s0,
            share, who, secs, secs > 0 ? 1e-6 * (double)st->samples / secs : 0.0,
            st->interrupted ? " (interrupted: partial image)" : "");
}

int render_scene(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                 size_t errlen)
{
    const camera_t *cam = &s->camera;
    int s0, s1;
    render_sample_range(s, opt, &s0, &s1);
    if (s0 < 0 || s1 > scene_spp(s) || s0 >= s1) {
        snprintf(err, errlen, "samples %d to %d are not a range of the scene's %d", s0, s1, scene_spp(s));
        return -1;
    }
    if (render_film_init(s, opt->aovs, film, err, errlen) != 0)
        return -1;
    /* About eight passes, so an interrupted render has every pixel sampled. */
    int spp = s1 - s0, pass_spp = spp < 8 ? 1 : (spp + 7) / 8;
    int threads = render_thread_count(opt);
    progress_t bar;
    render_tally tally = {.bar = opt->progress ? &bar : NULL, .t_start = now_seconds()};
    if (opt->progress)
        progress_begin(&bar, "render", (uint64_t)spp * (uint64_t)cam->width * (uint64_t)cam->height);
    for (int p0 = s0; p0 < s1 && !stop_requested; p0 += pass_spp)
        render_samples(s, threads, opt->aovs, film, p0, p0 + pass_spp < s1 ? p0 + pass_spp : s1, 0, cam->height,
                       &tally);
    render_stats st = {now_seconds() - tally.t_start, atomic_load(&tally.taken), stop_requested != 0,
                       tally.busy_cpu_seconds, tally.idle_cpu_seconds};
    if (opt->progress) {
        if (!st.interrupted)
            progress_end(&bar);
        else if (bar.enabled)
            fputc('\n', stderr);
        char who[32];
        snprintf(who, sizeof who, "%d thread%s", threads, threads > 1 ? "s" : "");
        render_print_summary(s, opt, &st, who);
    }
    if (stats)
        *stats = st;
    render_stop_clear();
    return 0;
}
