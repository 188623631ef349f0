/* The render loop: passes of samples over 16x16 tiles shared out to OpenMP
 * threads, each pixel sample with its own stream of the sampler, a progress
 * bar, and a stop request (SIGINT) honoured after the sample in progress. */
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celadon/render.h"
#include "core/core.h"
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

int render_scene(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                 size_t errlen)
{
    const camera_t *cam = &s->camera;
    film_aov list[3];
    int naov = 0;
    if (opt->aovs & RENDER_AOV_DEPTH)
        list[naov++] = (film_aov){"depth", 1};
    if (opt->aovs & RENDER_AOV_NORMAL)
        list[naov++] = (film_aov){"normal", 3};
    if (opt->aovs & RENDER_AOV_ALBEDO)
        list[naov++] = (film_aov){"albedo", 3};
    if (film_init(film, cam->width, cam->height, list, naov, err, errlen) != 0)
        return -1;
    int spp = scene_spp(s);
    int tiles_x = (cam->width + TILE - 1) / TILE, tiles_y = (cam->height + TILE - 1) / TILE;
    int ntiles = tiles_x * tiles_y;
    /* About eight passes, so an interrupted render has every pixel sampled. */
    int pass_spp = spp < 8 ? 1 : (spp + 7) / 8;
    int threads = opt->threads > 0 ? opt->threads : omp_get_max_threads();
    uint64_t total = (uint64_t)spp * (uint64_t)cam->width * (uint64_t)cam->height, done = 0;
    progress_t bar;
    if (opt->progress)
        progress_begin(&bar, "render", total);
    double *pass_cpu = calloc((size_t)threads, sizeof *pass_cpu), busy = 0.0, idle = 0.0;
    if (!pass_cpu) {
        film_free(film);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    double t_start = now_seconds();
    for (int s0 = 0; s0 < spp && !stop_requested; s0 += pass_spp) {
        int s1 = s0 + pass_spp < spp ? s0 + pass_spp : spp;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int t = 0; t < ntiles; t++) {
            if (stop_requested)
                continue;
            int tx = (t % tiles_x) * TILE, ty = (t / tiles_x) * TILE;
            double c0 = thread_cpu_seconds();
            uint64_t add = render_tile(s, film, opt->aovs, tx, ty, s0, s1), now;
            pass_cpu[omp_get_thread_num()] += thread_cpu_seconds() - c0;
#pragma omp atomic capture
            now = done += add;
            if (opt->progress && omp_get_thread_num() == 0) {
                char extra[64];
                double el = now_seconds() - t_start;
                snprintf(extra, sizeof extra, "%.2f Msamples/s", el > 0 ? 1e-6 * (double)now / el : 0.0);
                progress_update(&bar, now, extra);
            }
        }
        double most = 0.0;
        for (int i = 0; i < threads; i++)
            most = pass_cpu[i] > most ? pass_cpu[i] : most;
        for (int i = 0; i < threads; i++)
            busy += pass_cpu[i], idle += most - pass_cpu[i], pass_cpu[i] = 0.0;
    }
    free(pass_cpu);
    double secs = now_seconds() - t_start;
    if (opt->progress) {
        if (!stop_requested)
            progress_end(&bar);
        else if (bar.enabled)
            fputc('\n', stderr);
        fprintf(stderr, "render: %dx%d, %d spp, %d threads: %.2f s, %.2f Msamples/s%s\n", cam->width, cam->height,
                spp, threads, secs, secs > 0 ? 1e-6 * (double)done / secs : 0.0,
                stop_requested ? " (interrupted: partial image)" : "");
    }
    if (stats) {
        stats->seconds = secs;
        stats->samples = done;
        stats->interrupted = stop_requested != 0;
        stats->busy_cpu_seconds = busy;
        stats->idle_cpu_seconds = idle;
    }
    stop_requested = 0;
    return 0;
}
