/* A film's metadata as name/value strings (film_info.h). */
#include "render/film_info.h"

#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "celadon/version.h"

/* Adds "celadon/<name>" with the formatted value, unless it is empty. */
static void add(film_info *info, const char *name, const char *fmt, ...)
{
    if (info->n == FILM_INFO_MAX)
        return;
    char *slot = info->text[info->n];
    int k = snprintf(slot, FILM_INFO_LEN, "celadon/%s", name) + 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(slot + k, (size_t)(FILM_INFO_LEN - k), fmt, ap);
    va_end(ap);
    if (!slot[k])
        return;
    info->attr[info->n++] = (film_attr){slot, slot + k};
}

void film_info_collect(const film_t *f, film_info *info)
{
    info->n = 0;
    info->summary[0] = '\0';
    const film_metadata *m = &f->meta;
    if (m->spp <= 0)
        return;
    double least, most;
    film_sample_range(f, &least, &most);
    char done[64];
    if (least == most)
        snprintf(done, sizeof done, "%.0f", least);
    else
        snprintf(done, sizeof done, "%.0f-%.0f", least, most);
    add(info, "version", "%s", CELADON_VERSION);
    add(info, "scene", "%s", m->scene_path);
    add(info, "sceneDigest", "%s", m->scene_digest);
    add(info, "commandLine", "%s", m->command_line);
    add(info, "seed", "%" PRIu64, m->seed);
    add(info, "sampler", "%s", m->sampler);
    add(info, "integrator", "%s", m->integrator);
    add(info, "sppRequested", "%d", m->spp);
    add(info, "sppDone", "%s", done);
    /* A merge of parts knows no passes, time, threads or ranks of its own. */
    if (m->passes > 0 || m->interrupted)
        add(info, "passes", "%d", m->passes);
    if (m->seconds > 0)
        add(info, "renderSeconds", "%.3f", m->seconds);
    add(info, "interrupted", "%s", m->interrupted ? "yes" : "no");
    if (m->time_budget > 0)
        add(info, "timeBudget", "%g", m->time_budget);
    if (m->crop[2] > 0)
        add(info, "crop", "%d,%d,%d,%d of %dx%d", m->crop[0], m->crop[1], m->crop[2], m->crop[3], m->full_width,
            m->full_height);
    if (m->threads > 0)
        add(info, "threads", "%d", m->threads);
    if (m->ranks > 0)
        add(info, "ranks", "%d", m->ranks);
    add(info, "denoised", "%s", m->denoised);
    snprintf(info->summary, sizeof info->summary, "celadon %s: %s%s%s spp of %d (%s, %s, seed %" PRIu64 "), %.1f s%s%s",
             CELADON_VERSION, m->scene_path, m->scene_path[0] ? ", " : "", done, m->spp, m->integrator, m->sampler,
             m->seed, m->seconds, m->interrupted ? ", interrupted: partial image" : "", m->denoised[0] ? ", denoised" : "");
}
