#include "core/progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void progress_begin(progress_t *p, const char *label, uint64_t total)
{
    p->label = label;
    p->total = total ? total : 1;
    p->t_start = now_seconds();
    p->t_last_draw = 0.0;
    p->enabled = isatty(STDERR_FILENO);
    p->lines = 0;
    p->last_tenth = 0;
}

void progress_begin_lines(progress_t *p, const char *label, uint64_t total)
{
    progress_begin(p, label, total);
    p->lines = !p->enabled;
}

static void format_duration(double s, char *buf, size_t n)
{
    long secs = (long)(s + 0.5);
    if (secs >= 3600)
        snprintf(buf, n, "%ldh%02ldm", secs / 3600, (secs / 60) % 60);
    else
        snprintf(buf, n, "%ldm%02lds", secs / 60, secs % 60);
}

/* A line at each tenth of the way (not at the end: the summary follows). */
static void progress_line(progress_t *p, uint64_t done, const char *extra)
{
    int tenth = (int)(10.0 * (double)done / (double)p->total);
    if (tenth <= p->last_tenth || tenth >= 10)
        return;
    p->last_tenth = tenth;
    double elapsed = now_seconds() - p->t_start, frac = (double)done / (double)p->total;
    char eta[32];
    format_duration(elapsed * (1.0 - frac) / frac, eta, sizeof eta);
    fprintf(stderr, "%s: %d%% ETA %s %s\n", p->label, 10 * tenth, eta, extra ? extra : "");
    fflush(stderr);
}

void progress_update(progress_t *p, uint64_t done, const char *extra)
{
    if (p->lines)
        progress_line(p, done, extra);
    if (!p->enabled)
        return;
    double t = now_seconds();
    if (done < p->total && t - p->t_last_draw < 0.1)
        return;
    p->t_last_draw = t;
    double frac = (double)done / (double)p->total;
    if (frac > 1.0)
        frac = 1.0;
    enum { WIDTH = 30 };
    char bar[WIDTH + 1];
    int filled = (int)(frac * WIDTH);
    for (int i = 0; i < WIDTH; i++)
        bar[i] = i < filled ? '#' : '.';
    bar[WIDTH] = 0;
    double elapsed = t - p->t_start;
    char eta[32] = "--";
    if (frac > 0.0)
        format_duration(elapsed * (1.0 - frac) / frac, eta, sizeof eta);
    fprintf(stderr, "\r%s [%s] %5.1f%% ETA %s %s\033[K", p->label, bar, 100.0 * frac, eta, extra ? extra : "");
    fflush(stderr);
}

void progress_end(progress_t *p)
{
    if (!p->enabled)
        return;
    p->t_last_draw = 0.0;
    progress_update(p, p->total, NULL);
    fputc('\n', stderr);
}
