/* The render loop: passes of samples over 16x16 tiles shared out to OpenMP
 * threads, each pixel sample with its own stream of the sampler, splatted
 * into the film through the reconstruction filter, a progress bar, and a
 * stop request (SIGINT) honoured after the sample in progress.
 * render_scene is the one-process driver; render_loop.h gives the pieces to
 * the others (distribute_mpi.c).
 *
 * Determinism with splatting: a sample reaches the pixels within the
 * filter's radius, so neighbouring tiles write to shared pixels. Tiles are
 * coloured k x k (k = 2 + floor(2 radius / 16)), so that two tiles of one
 * colour never reach a common pixel; the colours are rendered one after
 * the other, the tiles of a colour in parallel. Every pixel then receives
 * its contributions in an order fixed by the tiles and samples alone,
 * whatever the threads and their schedule. */
#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "render/render_loop.h"
#include "render/scene_impl.h"

enum { TILE = 16, PASS_MAX_SPP = 64 };

/* 0: render on; STOP_AFTER_PASS: finish the pass under way; STOP_NOW: stop
 * after the samples in flight. */
enum { STOP_AFTER_PASS = 1, STOP_NOW = 2 };
static volatile sig_atomic_t stop_requested;

void render_request_stop(void) { stop_requested = stop_requested ? STOP_NOW : STOP_AFTER_PASS; }
void render_request_stop_now(void) { stop_requested = STOP_NOW; }

int render_aov_parse(const char *list, unsigned *mask)
{
    *mask = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    char *save, *tok = strtok_r(buf, ",", &save);
    if (!tok)
        return -1;
    for (; tok; tok = strtok_r(NULL, ",", &save)) {
        if (!strcmp(tok, "depth") || !strcmp(tok, "Z"))
            *mask |= RENDER_AOV_DEPTH;
        else if (!strcmp(tok, "normal") || !strcmp(tok, "N"))
            *mask |= RENDER_AOV_NORMAL;
        else if (!strcmp(tok, "albedo"))
            *mask |= RENDER_AOV_ALBEDO;
        else if (!strcmp(tok, "index"))
            *mask |= RENDER_AOV_INDEX;
        else if (!strcmp(tok, "variance"))
            *mask |= RENDER_AOV_VARIANCE;
        else if (!strcmp(tok, "spp"))
            *mask |= RENDER_AOV_SPP;
        else if (!strcmp(tok, "denoising"))
            *mask |= RENDER_AOV_DENOISING;
        else if (!strcmp(tok, "half"))
            *mask |= RENDER_AOV_HALF;
        else if (!strcmp(tok, "specular"))
            *mask |= RENDER_AOV_SPECULAR;
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

/* What the tiles of a render share. */
typedef struct {
    const scene_t *s;
    film_t *film;
    unsigned aovs;       /* RENDER_AOV_* */
    bool alpha;          /* the film has an A channel */
    int nown;            /* the integrator's own channels */
    int x0, y0, x1, y1;  /* the sampled pixels: the film, and the border with sample_border */
    int border;          /* its width: the sampler numbers pixels from the border's corner */
    const int *material; /* with RENDER_AOV_INDEX: each shape's material number */
    int ox, oy;          /* the crop window's corner: film pixel (x, y) is the output's (x - ox, y - oy) */
    int half_end;        /* with RENDER_AOV_HALF: samples k < half_end make the first half */
} render_job;

/* A shape's BSDF and number, ordered by BSDF, then number. */
typedef struct {
    uintptr_t bsdf;
    int shape;
} bsdf_use;

static int by_bsdf(const void *pa, const void *pb)
{
    const bsdf_use *a = pa, *b = pb;
    if (a->bsdf != b->bsdf)
        return a->bsdf < b->bsdf ? -1 : 1;
    return (a->shape > b->shape) - (a->shape < b->shape);
}

/* Each shape's material number: that of the first shape (from 1) with the
 * same BSDF, so shapes share a number exactly when they share a BSDF. */
static int *material_numbers(const shape_list *l)
{
    int n = l->count;
    bsdf_use *use = malloc(sizeof *use * (size_t)(n > 0 ? n : 1));
    int *num = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    if (!use || !num)
        abort();
    for (int i = 0; i < n; i++)
        use[i] = (bsdf_use){(uintptr_t)l->items[i].bsdf, i};
    qsort(use, (size_t)n, sizeof *use, by_bsdf);
    for (int i = 0; i < n; i++)
        num[use[i].shape] = i > 0 && use[i - 1].bsdf == use[i].bsdf ? num[use[i - 1].shape] : use[i].shape + 1;
    free(use);
    return num;
}

/* The shape and material numbers of the first surface the camera ray
 * meets, into the film's ids of pixel (x, y). */
static void record_ids(const render_job *j, const camera_ray_t *cr, int x, int y)
{
    surface_hit hit;
    double *ids = j->film->ids + 2 * ((size_t)y * j->film->width + x);
    if (shape_list_intersect(&j->s->shapes, &cr->ray, cr->tmin, cr->tmax, &hit)) {
        int k = (int)(hit.shape - j->s->shapes.items);
        ids[0] = k + 1, ids[1] = j->material[k];
    }
}

/* Film values of sample k: RGB, A, then the requested AOVs and the
 * integrator's own channels, in that order. */
static void pack_values(const render_job *j, rgb L, const double *aov, int k, double *out)
{
    int n = 0;
    out[n++] = L.r, out[n++] = L.g, out[n++] = L.b;
    if (j->alpha)
        out[n++] = aov[INTEGRATOR_AOV_ALPHA];
    if (j->aovs & RENDER_AOV_DEPTH)
        out[n++] = aov[INTEGRATOR_AOV_DEPTH];
    for (int i = 0; i < 3 && (j->aovs & RENDER_AOV_NORMAL); i++)
        out[n++] = aov[INTEGRATOR_AOV_NORMAL + i];
    for (int i = 0; i < 3 && (j->aovs & RENDER_AOV_ALBEDO); i++)
        out[n++] = aov[INTEGRATOR_AOV_ALBEDO + i];
    if (j->aovs & RENDER_AOV_DENOISING) {
        out[n++] = aov[INTEGRATOR_AOV_ROUGH_DEPTH];
        for (int i = 0; i < 3; i++)
            out[n++] = aov[INTEGRATOR_AOV_ROUGH_NORMAL + i];
        for (int i = 0; i < 3; i++)
            out[n++] = aov[INTEGRATOR_AOV_ROUGH_ALBEDO + i];
    }
    if (j->aovs & RENDER_AOV_HALF) { /* the film's average makes them premultiplied by the half's share */
        double in = k < j->half_end;
        out[n++] = in * L.r, out[n++] = in * L.g, out[n++] = in * L.b, out[n++] = in;
    }
    for (int i = 0; i < 3 && (j->aovs & RENDER_AOV_SPECULAR); i++)
        out[n++] = aov[INTEGRATOR_AOV_SPECULAR + i];
    if ((j->aovs & RENDER_AOV_SPECULAR) && (j->aovs & RENDER_AOV_HALF)) {
        double in = k < j->half_end;
        for (int i = 0; i < 3; i++)
            out[n++] = in * aov[INTEGRATOR_AOV_SPECULAR + i];
    }
    for (int i = 0; i < 3 && (j->aovs & RENDER_AOV_SPECULAR); i++)
        out[n++] = aov[INTEGRATOR_AOV_MIRROR + i];
    for (int i = 0; i < j->nown; i++)
        out[n++] = aov[INTEGRATOR_AOV_COUNT + i];
}

/* Adds a sample at film position (x, y) to the pixels whose centres lie
 * within the filter's reach, weighted by it; a box adds it to the pixel it
 * falls in, with weight 1. */
static void splat(film_t *film, const rfilter_t *f, int px, int py, double x, double y, const double *vals)
{
    if (rfilter_is_box(f)) {
        if (px >= 0 && py >= 0 && px < film->width && py < film->height)
            film_add(film, px, py, vals, 1.0);
        return;
    }
    double r = f->radius, wx[160], wy[160];
    int ax = (int)ceil(x - 0.5 - r), bx = (int)floor(x - 0.5 + r);
    int ay = (int)ceil(y - 0.5 - r), by = (int)floor(y - 0.5 + r);
    ax = ax < 0 ? 0 : ax, ay = ay < 0 ? 0 : ay;
    bx = bx >= film->width ? film->width - 1 : bx, by = by >= film->height ? film->height - 1 : by;
    for (int i = ax; i <= bx; i++)
        wx[i - ax] = rfilter_eval(f, i + 0.5 - x);
    for (int i = ay; i <= by; i++)
        wy[i - ay] = rfilter_eval(f, i + 0.5 - y);
    for (int v = ay; v <= by; v++)
        for (int u = ax; u <= bx; u++) {
            double w = wx[u - ax] * wy[v - ay];
            if (w != 0.0)
                film_add(film, u, v, vals, w);
        }
}

/* Samples [s0, s1) of every pixel of the tile at (tx, ty); a stop request
 * ends it after the sample in progress. Returns the number of samples
 * taken. */
static uint64_t render_tile(const render_job *j, int tx, int ty, int s0, int s1)
{
    const scene_t *s = j->s;
    const camera_t *cam = &s->camera;
    integrator_scene sc = {&s->shapes, &s->emitters, s->camera_medium};
    size_t naov = INTEGRATOR_AOV_COUNT + (size_t)j->nown;
    double *aov = malloc(sizeof(double) * (naov + j->film->nchannels));
    if (!aov)
        abort();
    double *vals = aov + naov;
    bool need_aov = j->aovs || j->alpha || j->nown > 0;
    uint64_t n = 0;
    for (int y = ty; y < ty + TILE && y < j->y1; y++)
        for (int x = tx; x < tx + TILE && x < j->x1; x++)
            for (int k = s0; k < s1; k++) {
                if (stop_requested == STOP_NOW)
                    goto done;
                sampler_stream smp;
                sampler_start(&s->sampler, &smp, (uint32_t)(x + j->border), (uint32_t)(y + j->border), (uint32_t)k);
                sampler_seek(&smp, SAMPLER_DIM_FILM);
                vec2 film_pos = sampler_next_2d(&smp);
                double sx = x + film_pos.x, sy = y + film_pos.y;
                vec2 lens = v2(0.5, 0.5);
                if (cam->needs_aperture) {
                    sampler_seek(&smp, SAMPLER_DIM_LENS);
                    lens = sampler_next_2d(&smp);
                }
                camera_ray_t cr = camera_ray_at(cam, sx, sy, lens);
                rgb L = integrator_li(s->integrator, &sc, &cr.ray, cr.tmin, cr.tmax, &smp, need_aov ? aov : NULL);
                pack_values(j, L, aov, k, vals);
                int fx = x - j->ox, fy = y - j->oy; /* in the output */
                splat(j->film, &s->film.filter, fx, fy, sx - j->ox, sy - j->oy, vals);
                /* A tile owns its pixels: no other thread counts into them. */
                if (fx >= 0 && fy >= 0 && fx < j->film->width && fy < j->film->height) {
                    film_count_sample(j->film, fx, fy, rgb_luminance(L));
                    if (k == 0 && j->material)
                        record_ids(j, &cr, fx, fy);
                }
                n++;
            }
done:
    free(aov);
    return n;
}

/* The metadata of the EXR header: how the image was made. */
static void describe(const scene_t *s, film_metadata *m)
{
    const camera_t *cam = &s->camera;
    m->spp = scene_spp(s);
    m->seed = scene_seed(s);
    snprintf(m->integrator, sizeof m->integrator, "%s", integrator_type(s->integrator));
    if (strcmp(cam->type, "orthographic") == 0)
        snprintf(m->camera, sizeof m->camera, "%s", cam->type);
    else
        snprintf(m->camera, sizeof m->camera, "%s fov_x=%.6g fov_y=%.6g", cam->type,
                 2.0 * atan(cam->tan_x) * (180.0 / M_PI), 2.0 * atan(cam->tan_y) * (180.0 / M_PI));
    if (strcmp(cam->type, "thinlens") == 0) {
        size_t used = strlen(m->camera);
        snprintf(m->camera + used, sizeof m->camera - used, " aperture_radius=%.6g focus_distance=%.6g",
                 cam->aperture_radius, cam->focus_distance);
    }
    transform4 inv = transform_inverse(&cam->to_world);
    memcpy(m->world_to_camera, inv.m, sizeof m->world_to_camera);
    snprintf(m->sampler, sizeof m->sampler, "%s", s->sampler.plugin);
    const film_settings *fs = &s->film;
    if (fs->crop_w != fs->width || fs->crop_h != fs->height) {
        m->crop[0] = fs->crop_x, m->crop[1] = fs->crop_y, m->crop[2] = fs->crop_w, m->crop[3] = fs->crop_h;
        m->full_width = fs->width, m->full_height = fs->height;
    }
    snprintf(m->scene_digest, sizeof m->scene_digest, "%016" PRIx64, scene_digest(s));
    m->ranks = 1;
}

/* The film's channels beyond R, G, B and A: the requested AOVs (named as
 * Blender's compositor and Nuke read them: Z, N.X/Y/Z, albedo.R/G/B), then
 * the integrator's own ones; the extras written from the pixels' samples. */
int render_film_init(const scene_t *s, unsigned aovs, film_t *film, char *err, size_t errlen)
{
    static const char *const xyz_names[3] = {"X", "Y", "Z"}, *const rgba_names[4] = {"R", "G", "B", "A"};
    static const char *const whole[1] = {""};
    int nown = integrator_channel_count(s->integrator);
    film_aov *list = malloc(sizeof *list * (size_t)(10 + nown));
    if (!list)
        abort();
    int naov = 0;
    /* Z is Blender's Depth pass, unless X, Y and Z are the colour: then
     * Depth.Z, the same pass as Blender reads it. */
    int xyz = s->film.format == FILM_XYZ || s->film.format == FILM_XYZA;
    if (aovs & RENDER_AOV_DEPTH)
        list[naov++] = xyz ? (film_aov){"Depth", 1, xyz_names + 2} : (film_aov){"Z", 1, whole};
    if (aovs & RENDER_AOV_NORMAL)
        list[naov++] = (film_aov){"N", 3, xyz_names};
    if (aovs & RENDER_AOV_ALBEDO)
        list[naov++] = (film_aov){"albedo", 3, rgba_names};
    /* Cycles' names for its denoiser's features, which it takes past
     * specular surfaces too. */
    if (aovs & RENDER_AOV_DENOISING) {
        list[naov++] = (film_aov){"Denoising Depth", 1, xyz_names + 2};
        list[naov++] = (film_aov){"Denoising Normal", 3, xyz_names};
        list[naov++] = (film_aov){"Denoising Albedo", 3, rgba_names};
    }
    if (aovs & RENDER_AOV_HALF)
        list[naov++] = (film_aov){"half", 4, rgba_names};
    if (aovs & RENDER_AOV_SPECULAR)
        list[naov++] = (film_aov){"specular", 3, rgba_names};
    if ((aovs & RENDER_AOV_SPECULAR) && (aovs & RENDER_AOV_HALF))
        list[naov++] = (film_aov){"specular half", 3, rgba_names};
    if (aovs & RENDER_AOV_SPECULAR)
        list[naov++] = (film_aov){"Denoising Mirror", 3, rgba_names};
    for (int i = 0; i < nown; i++)
        list[naov++] = (film_aov){integrator_channel_name(s->integrator, i), 1, whole};
    int rc = film_init_format(film, s->film.crop_w, s->film.crop_h, s->film.format, list, naov, err, errlen);
    free(list);
    if (rc == 0) {
        describe(s, &film->meta);
        film->extras = ((aovs & RENDER_AOV_SPP) ? FILM_EXTRA_SPP : 0u) |
                       ((aovs & RENDER_AOV_VARIANCE) ? FILM_EXTRA_VARIANCE : 0u) |
                       ((aovs & RENDER_AOV_INDEX) ? FILM_EXTRA_INDEX : 0u);
    }
    return rc;
}

/* How far beyond a pixel a sample reaches through the filter, in pixels. */
static int filter_reach(const scene_t *s) { return (int)ceil(s->film.filter.radius - 0.5); }

/* The pixels beyond the film's edge that are sampled too (sample_border). */
static int border_pixels(const scene_t *s) { return s->film.sample_border ? filter_reach(s) : 0; }

/* The sampled pixels [*a, *b) along one axis of the film for the crop
 * window's pixels [lo, hi): the window, the filter's reach around it
 * within the film, and the border beyond the film with sample_border. */
static void sampled_span(const scene_t *s, int lo, int hi, int full, int *a, int *b)
{
    int reach = filter_reach(s), border = border_pixels(s);
    *a = lo - reach < -border ? -border : lo - reach;
    *b = hi + reach > full + border ? full + border : hi + reach;
}

uint64_t render_sample_count(const scene_t *s, int s0, int s1)
{
    const film_settings *fs = &s->film;
    int x0, x1, y0, y1;
    sampled_span(s, fs->crop_x, fs->crop_x + fs->crop_w, fs->width, &x0, &x1);
    sampled_span(s, fs->crop_y, fs->crop_y + fs->crop_h, fs->height, &y0, &y1);
    return (uint64_t)(s1 - s0) * (uint64_t)(x1 - x0) * (uint64_t)(y1 - y0);
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
    const film_settings *fs = &s->film;
    const rfilter_t *filter = &fs->filter;
    int border = border_pixels(s), xa, xb, ya, yb;
    /* Rows [y0, y1) of the crop window, in the film's rows; the first and
     * last bands take the rows around the window that reach into it too. */
    sampled_span(s, fs->crop_x, fs->crop_x + fs->crop_w, fs->width, &xa, &xb);
    sampled_span(s, fs->crop_y + y0, fs->crop_y + y1, fs->height, &ya, &yb);
    render_job job = {s,
                      film,
                      aovs,
                      film_format_has_alpha(s->film.format),
                      integrator_channel_count(s->integrator),
                      xa,
                      y0 == 0 ? ya : fs->crop_y + y0,
                      xb,
                      y1 == fs->crop_h ? yb : fs->crop_y + y1,
                      border,
                      (aovs & RENDER_AOV_INDEX) && s0 == 0 ? material_numbers(&s->shapes) : NULL,
                      fs->crop_x,
                      fs->crop_y,
                      scene_spp(s) / 2};
    int tiles_x = (job.x1 - job.x0 + TILE - 1) / TILE, tiles_y = (job.y1 - job.y0 + TILE - 1) / TILE;
    /* Tiles of one colour are k tiles apart: (k - 1) TILE > 2 radius. */
    int k = rfilter_is_box(filter) ? 1 : 2 + (int)floor(2.0 * filter->radius / TILE);
    double busy = 0.0, idle = 0.0;
    for (int colour = 0; colour < k * k && stop_requested != STOP_NOW; colour++) {
        int cx = colour % k, cy = colour / k;
        int ncx = (tiles_x - cx + k - 1) / k, ncy = (tiles_y - cy + k - 1) / k, ntiles = ncx * ncy, team = 1;
        double spent = 0.0, most = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : spent) reduction(max : most)
        {
            double mine = 0.0; /* this thread's CPU seconds in tiles */
#pragma omp for schedule(dynamic, 1)
            for (int t = 0; t < ntiles; t++) {
                if (stop_requested == STOP_NOW)
                    continue;
                int tx = job.x0 + (cx + k * (t % ncx)) * TILE, ty = job.y0 + (cy + k * (t / ncx)) * TILE;
                double c0 = thread_cpu_seconds();
                uint64_t add = render_tile(&job, tx, ty, s0, s1);
                mine += thread_cpu_seconds() - c0;
                uint64_t now = atomic_fetch_add(&tally->taken, add) + add;
                if (tally->bar && omp_get_thread_num() == 0) {
                    char extra[64];
                    double el = now_seconds() - tally->t_start;
                    snprintf(extra, sizeof extra, "%.2f Msamples/s", el > 0 ? 1e-6 * (double)now / el : 0.0);
                    progress_update(tally->bar, now, extra);
                }
            }
            spent += mine, most = mine;
#pragma omp master
            team = omp_get_num_threads();
        }
        /* Every thread waits at the end of a colour's tiles for the one
         * with the most. */
        busy += spent;
        idle += team * most - spent;
    }
    tally->busy_cpu_seconds += busy;
    tally->idle_cpu_seconds += idle;
    free((int *)job.material);
}

void render_print_summary(const scene_t *s, const render_options *opt, const render_stats *st, const char *who)
{
    int s0, s1, width, height;
    render_sample_range(s, opt, &s0, &s1);
    scene_film_size(s, &width, &height);
    char share[64] = "";
    if (s1 - s0 != scene_spp(s))
        snprintf(share, sizeof share, " (samples %d-%d of %d)", s0, s1 - 1, scene_spp(s));
    double secs = st->seconds;
    fprintf(stderr, "render: %dx%d, %d spp%s, %s: %.2f s, %.2f Msamples/s%s\n", width, height, s1 - s0,
            share, who, secs, secs > 0 ? 1e-6 * (double)st->samples / secs : 0.0,
            st->interrupted ? " (interrupted: partial image)" : "");
}

/* The film so far into the preview file; a failure is said, not fatal. */
static void write_preview(film_t *film, const char *path, double seconds)
{
    char err[1024];
    film->meta.seconds = seconds;
    if (film_write(film, path, err, sizeof err) != 0)
        fprintf(stderr, "celadon: preview: %s\n", err);
}

int render_scene(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                 size_t errlen)
{
    int s0, s1;
    render_sample_range(s, opt, &s0, &s1);
    if (s0 < 0 || s1 > scene_spp(s) || s0 >= s1) {
        snprintf(err, errlen, "samples %d to %d are not a range of the scene's %d", s0, s1, scene_spp(s));
        return -1;
    }
    if (render_film_init(s, opt->aovs, film, err, errlen) != 0)
        return -1;
    /* About eight passes, so an interrupted render has every pixel sampled,
     * of at most PASS_MAX_SPP samples, so that Ctrl-C (which finishes the
     * pass) is heard soon however many samples were asked for. */
    int spp = s1 - s0, pass_spp = spp < 8 ? 1 : (spp + 7) / 8;
    pass_spp = pass_spp > PASS_MAX_SPP ? PASS_MAX_SPP : pass_spp;
    int threads = render_thread_count(opt);
    progress_t bar;
    render_tally tally = {.bar = opt->progress ? &bar : NULL, .t_start = now_seconds()};
    if (opt->progress)
        progress_begin(&bar, "render", render_sample_count(s, s0, s1));
    int passes = 0;
    double last_preview = tally.t_start, pass_seconds = 0.0;
    film->meta.threads = threads;
    for (int p0 = s0; p0 < s1 && !stop_requested; p0 += pass_spp) {
        double t0 = now_seconds();
        if (passes > 0 && opt->time_budget > 0 && t0 + pass_seconds - tally.t_start > opt->time_budget)
            break;
        render_samples(s, threads, opt->aovs, film, p0, p0 + pass_spp < s1 ? p0 + pass_spp : s1, 0, film->height,
                       &tally);
        passes += stop_requested != STOP_NOW;
        pass_seconds = now_seconds() - t0;
        film->meta.passes = passes;
        if (opt->preview && now_seconds() - last_preview >= opt->preview_seconds) {
            write_preview(film, opt->preview, now_seconds() - tally.t_start);
            last_preview = now_seconds();
        }
    }
    render_stats st = {now_seconds() - tally.t_start, atomic_load(&tally.taken),
                       stop_requested != 0 && atomic_load(&tally.taken) < render_sample_count(s, s0, s1),
                       tally.busy_cpu_seconds, tally.idle_cpu_seconds};
    film->meta.seconds = st.seconds, film->meta.interrupted = st.interrupted;
    film->meta.time_budget = opt->time_budget;
    if (opt->preview)
        write_preview(film, opt->preview, st.seconds);
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
