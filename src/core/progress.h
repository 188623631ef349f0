/* One-line progress bar with ETA on a TTY (stderr); silent otherwise, or,
 * when begun with progress_begin_lines, one line per tenth of the way (for
 * logs: a batch job's, or mpirun's relay of a rank's stderr). */
#ifndef CELADON_PROGRESS_H
#define CELADON_PROGRESS_H

#include <stdint.h>

typedef struct {
    const char *label;
    uint64_t total;
    double t_start, t_last_draw;
    int enabled;    /* 1: the bar on a TTY */
    int lines;      /* 1: a line per tenth of the way, no TTY */
    int last_tenth; /* the last tenth a line was written for */
} progress_t;

double now_seconds(void); /* monotonic clock */

void progress_begin(progress_t *p, const char *label, uint64_t total);
void progress_begin_lines(progress_t *p, const char *label, uint64_t total);
/* Thread-safe to call from one thread at a time; draws at most ~10 times per
 * second. extra (may be NULL) is appended, e.g. "3.1 Msamples/s". */
void progress_update(progress_t *p, uint64_t done, const char *extra);
void progress_end(progress_t *p);

#endif
