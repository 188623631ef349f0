/* distribute.h with MPI (Open MPI): rank 0 hands out the units of the plan
 * (distribute_plan.h) to whichever rank asks, the films are summed on rank 0.
 *
 * Every rank renders in a thread of its own (render_samples, with its OpenMP
 * team), while its main thread does all the MPI calls
 * (MPI_THREAD_FUNNELED): on rank 0 it hands out units (to its own render
 * thread too), gathers the others' sample counts for the progress bar and
 * spreads a stop request; on the others it asks rank 0 for a unit whenever
 * its render thread is idle and reports progress. Waiting main threads poll
 * with 1 ms sleeps instead of MPI's blocking calls, which spin a core that
 * the render threads need.
 *
 * Messages (two uint64: kind, value), up to rank 0 on TAG_UP: ASK (value:
 * the samples this rank took so far), ASK_STOPPED (the same, from a rank that
 * was told to stop by a signal: it wants no more), PROGRESS; down to a rank
 * on TAG_DOWN: UNIT (value: the unit), STOP (finish the samples in flight),
 * NONE (no more units: go on to the sum). Rank 0 answers every ASK with one
 * UNIT or NONE, sends STOP at most once, never after NONE, and everything
 * down goes on one tag, so a rank sees them in the order sent. */
#include <errno.h>
#include <mpi.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "celadon/distribute.h"
#include "render/distribute_plan.h"
#include "render/render_loop.h"

enum { TAG_UP = 7101, TAG_DOWN = 7102 };
enum { MSG_ASK, MSG_ASK_STOPPED, MSG_PROGRESS, MSG_UNIT, MSG_STOP, MSG_NONE };

#define POLL_SECONDS 1e-3 /* a waiting main thread's sleep between polls (rank 0's all along) */
/* Another rank's main thread has nothing to answer: while its render thread
 * is busy (which wakes it when the unit is done) it only looks for a stop
 * now and then; once it has asked for a unit it looks often for the reply,
 * which its idle render thread waits for. Polling every millisecond all
 * along cost each rank 2% of a core (0.19 s of 8.5 s). */
#define WORKER_BUSY_SECONDS 10e-3
#define WORKER_REPLY_SECONDS 0.1e-3
#define PROGRESS_SECONDS 0.5  /* how often a rank reports its sample count */
enum { REDUCE_CHUNK = 1 << 24 }; /* doubles per MPI_Reduce call (128 MB) */

static int joined; /* MPI_Init_thread done here */

static void sleep_seconds(double s)
{
    struct timespec ts = {0, (long)(s * 1e9)};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR)
        ;
}

/* Completes a request without spinning: every rank waits here for the
 * slowest one (to build its scene, to finish its last unit). */
static void wait_politely(MPI_Request *rq)
{
    int done = 0;
    for (MPI_Test(rq, &done, MPI_STATUS_IGNORE); !done; MPI_Test(rq, &done, MPI_STATUS_IGNORE))
        sleep_seconds(POLL_SECONDS);
}

int distribute_begin(distribute_job *job, char *err, size_t errlen)
{
    *job = (distribute_job){0, 1};
    if (distribute_launched_size() == 0)
        return 0;
    distribute_prefer_shared_memory();
    int provided;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        snprintf(err, errlen, "MPI_Init_thread failed");
        return -1;
    }
    joined = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &job->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &job->size);
    if (provided < MPI_THREAD_FUNNELED) {
        snprintf(err, errlen, "this MPI library cannot be called from a threaded program (MPI_THREAD_FUNNELED)");
        return -1;
    }
    return 0;
}

void distribute_end(void)
{
    if (joined)
        MPI_Finalize();
    joined = 0;
}

static int job_size(void)
{
    int size = 1;
    if (joined)
        MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

int distribute_first_failure(int ok)
{
    if (!joined)
        return ok ? -1 : 0;
    int rank, size, first;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    int mine = ok ? size : rank;
    MPI_Request rq;
    MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &rq);
    wait_politely(&rq);
    return first == size ? -1 : first;
}

/* ---------------------------------------------------------- render thread */

/* A rank's render thread: it renders the units its main thread gives it. */
typedef struct {
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t changed; /* a unit given, a unit finished, quit */
    int unit;               /* the unit to render next, or -1 */
    int busy;               /* a unit given and not finished */
    int quit;
    int units_done;
    const scene_t *scene;
    const distribute_plan *plan;
    film_t *film;
    unsigned aovs;
    int threads;
    render_tally tally;
} render_thread;

static void *render_thread_main(void *arg)
{
    render_thread *w = arg;
    pthread_mutex_lock(&w->mu);
    for (;;) {
        while (w->unit < 0 && !w->quit)
            pthread_cond_wait(&w->changed, &w->mu);
        if (w->unit < 0)
            break;
        int u = w->unit, s0, s1, y0, y1;
        w->unit = -1;
        pthread_mutex_unlock(&w->mu);
        distribute_plan_unit(w->plan, u, &s0, &s1, &y0, &y1);
        render_samples(w->scene, w->threads, w->aovs, w->film, s0, s1, y0, y1, &w->tally);
        pthread_mutex_lock(&w->mu);
        w->busy = 0;
        w->units_done++;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->mu);
    return NULL;
}

static void render_thread_start(render_thread *w)
{
    pthread_mutex_init(&w->mu, NULL);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&w->changed, &ca);
    pthread_condattr_destroy(&ca);
    w->unit = -1;
    if (pthread_create(&w->thread, NULL, render_thread_main, w) != 0)
        abort();
}

static void render_thread_give(render_thread *w, int unit)
{
    pthread_mutex_lock(&w->mu);
    w->unit = unit;
    w->busy = 1;
    pthread_cond_broadcast(&w->changed);
    pthread_mutex_unlock(&w->mu);
}

static int render_thread_idle(render_thread *w)
{
    pthread_mutex_lock(&w->mu);
    int idle = !w->busy;
    pthread_mutex_unlock(&w->mu);
    return idle;
}

/* Sleeps busy_s while the thread renders a unit (or less: until it finishes
 * it), idle_s while it has none. */
static void render_thread_wait(render_thread *w, double busy_s, double idle_s)
{
    pthread_mutex_lock(&w->mu);
    if (w->busy) {
        struct timespec until;
        clock_gettime(CLOCK_MONOTONIC, &until);
        until.tv_nsec += (long)(busy_s * 1e9);
        until.tv_sec += until.tv_nsec / 1000000000L;
        until.tv_nsec %= 1000000000L;
        pthread_cond_timedwait(&w->changed, &w->mu, &until);
        pthread_mutex_unlock(&w->mu);
    } else {
        pthread_mutex_unlock(&w->mu);
        sleep_seconds(idle_s);
    }
}

/* Ends the thread once its unit is done. */
static void render_thread_join(render_thread *w)
{
    pthread_mutex_lock(&w->mu);
    w->quit = 1;
    pthread_cond_broadcast(&w->changed);
    pthread_mutex_unlock(&w->mu);
    pthread_join(w->thread, NULL);
    pthread_cond_destroy(&w->changed);
    pthread_mutex_destroy(&w->mu);
}

/* ---------------------------------------------------------- the ranks */

static void send_msg(int to, int tag, uint64_t kind, uint64_t value)
{
    uint64_t m[2] = {kind, value};
    MPI_Send(m, 2, MPI_UINT64_T, to, tag, MPI_COMM_WORLD);
}

/* The next message on tag from `from` (MPI_ANY_SOURCE), if one is there. */
static int poll_msg(int from, int tag, uint64_t m[2], int *source)
{
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(from, tag, MPI_COMM_WORLD, &flag, &st);
    if (!flag)
        return 0;
    MPI_Recv(m, 2, MPI_UINT64_T, st.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    *source = st.MPI_SOURCE;
    return 1;
}

/* Rank 0's bookkeeping. */
typedef struct {
    int size, next_unit, stopping;
    int pending;          /* other ranks not yet told NONE */
    int *told_none, *told_stop, *units;
    uint64_t *taken;      /* each other rank's last reported sample count */
    progress_t bar;
} coordinator;

static void coordinator_stop(coordinator *c)
{
    if (c->stopping)
        return;
    c->stopping = 1;
    render_request_stop_now();
    for (int r = 1; r < c->size; r++)
        if (!c->told_none[r] && !c->told_stop[r]) {
            send_msg(r, TAG_DOWN, MSG_STOP, 0);
            c->told_stop[r] = 1;
        }
}

static int coordinator_take(coordinator *c, const distribute_plan *plan)
{
    return c->stopping || c->next_unit >= plan->units ? -1 : c->next_unit++;
}

/* Rank 0's main thread: hands out units until none is left (or a stop) and
 * every rank has been told so, and its render thread is idle. */
static void coordinate(coordinator *c, render_thread *w, const distribute_plan *plan, const render_options *opt)
{
    int local_done = 0;
    for (;;) {
        if (render_stop_requested())
            coordinator_stop(c);
        if (!local_done && render_thread_idle(w)) {
            int u = coordinator_take(c, plan);
            if (u < 0)
                local_done = 1;
            else
                render_thread_give(w, u), c->units[0]++;
        }
        uint64_t m[2];
        int from;
        while (poll_msg(MPI_ANY_SOURCE, TAG_UP, m, &from)) {
            c->taken[from] = m[1];
            if (m[0] == MSG_PROGRESS)
                continue;
            if (m[0] == MSG_ASK_STOPPED)
                coordinator_stop(c);
            int u = coordinator_take(c, plan);
            if (u >= 0) {
                send_msg(from, TAG_DOWN, MSG_UNIT, (uint64_t)u);
                c->units[from]++;
            } else {
                send_msg(from, TAG_DOWN, MSG_NONE, 0);
                c->told_none[from] = 1;
                c->pending--;
            }
        }
        if (opt->progress) {
            uint64_t all = atomic_load(&w->tally.taken);
            for (int r = 1; r < c->size; r++)
                all += c->taken[r];
            char extra[64];
            double el = now_seconds() - w->tally.t_start;
            snprintf(extra, sizeof extra, "%.2f Msamples/s", el > 0 ? 1e-6 * (double)all / el : 0.0);
            progress_update(&c->bar, all, extra);
        }
        if (local_done && c->pending == 0 && render_thread_idle(w))
            return;
        render_thread_wait(w, POLL_SECONDS, POLL_SECONDS);
    }
}

/* Another rank's main thread: asks for units until told NONE. */
static void work(render_thread *w)
{
    int asked = 0;
    uint64_t reported = 0;
    double last_report = now_seconds();
    for (;;) {
        uint64_t taken = atomic_load(&w->tally.taken);
        if (!asked && render_thread_idle(w)) {
            send_msg(0, TAG_UP, render_stop_requested() ? MSG_ASK_STOPPED : MSG_ASK, taken);
            asked = 1, reported = taken;
        }
        uint64_t m[2];
        int from;
        while (poll_msg(0, TAG_DOWN, m, &from)) {
            if (m[0] == MSG_NONE)
                return;
            if (m[0] == MSG_STOP)
                render_request_stop_now();
            else
                render_thread_give(w, (int)m[1]), asked = 0;
        }
        if (taken != reported && now_seconds() - last_report > PROGRESS_SECONDS) {
            send_msg(0, TAG_UP, MSG_PROGRESS, taken);
            reported = taken, last_report = now_seconds();
        }
        render_thread_wait(w, WORKER_BUSY_SECONDS, WORKER_REPLY_SECONDS);
    }
}

/* Sums every rank's array into rank 0's. */
static void reduce_to_root(double *a, size_t n, int rank)
{
    for (size_t off = 0; off < n; off += REDUCE_CHUNK) {
        int count = (int)(n - off < REDUCE_CHUNK ? n - off : REDUCE_CHUNK);
        MPI_Reduce(rank == 0 ? MPI_IN_PLACE : a + off, a + off, count, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    }
}

static void print_balance(const coordinator *c, const double *ready_cpu, double reduce_seconds)
{
    fprintf(stderr, "distribute: units per rank:");
    for (int r = 0; r < c->size; r++)
        fprintf(stderr, " %d", c->units[r]);
    fprintf(stderr, "; CPU s before rendering per rank:");
    for (int r = 0; r < c->size; r++)
        fprintf(stderr, " %.2f", ready_cpu[r]);
    fprintf(stderr, "; films summed in %.3f s\n", reduce_seconds);
}

static double process_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The process's CPU time at the end of its last distributed render. */
static double cpu_after_last_render;

int distribute_render(const scene_t *s, const render_options *opt, film_t *film, render_stats *stats, char *err,
                      size_t errlen)
{
    int size = job_size();
    if (size == 1)
        return render_scene(s, opt, film, stats, err, errlen);
    /* A rank's fixed cost: its start, MPI_Init and scene build (the first
     * render), or the next frame's build. */
    double ready_cpu = process_cpu_seconds() - cpu_after_last_render;
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int s0, s1, width, height;
    render_sample_range(s, opt, &s0, &s1);
    scene_film_size(s, &width, &height);
    err[0] = '\0';
    int ok = s0 >= 0 && s1 <= scene_spp(s) && s0 < s1;
    if (!ok)
        snprintf(err, errlen, "samples %d to %d are not a range of the scene's %d", s0, s1, scene_spp(s));
    else
        ok = render_film_init(s, opt->aovs, film, err, errlen) == 0;
    if (distribute_first_failure(ok) >= 0) {
        if (ok)
            film_free(film);
        return -1;
    }
    distribute_plan plan = distribute_plan_make(s0, s1, width, height, size);
    render_thread w = {.scene = s, .plan = &plan, .film = film, .aovs = opt->aovs,
                       .threads = render_thread_count(opt)};
    w.tally.t_start = now_seconds();
    render_thread_start(&w);
    coordinator c = {.size = size, .pending = size - 1};
    if (rank == 0) {
        c.told_none = calloc((size_t)size, sizeof(int));
        c.told_stop = calloc((size_t)size, sizeof(int));
        c.units = calloc((size_t)size, sizeof(int));
        c.taken = calloc((size_t)size, sizeof(uint64_t));
        if (!c.told_none || !c.told_stop || !c.units || !c.taken)
            abort();
        if (opt->progress) {
            fprintf(stderr, "distribute: %d ranks share %d unit%s of %d spp x %d rows\n", size, plan.units,
                    plan.units > 1 ? "s" : "", plan.pass_spp, plan.band_rows);
            progress_begin_lines(&c.bar, "render", render_sample_count(s, s0, s1));
        }
        coordinate(&c, &w, &plan, opt);
    } else {
        work(&w);
    }
    render_thread_join(&w);
    /* Everyone waits for the last unit here without spinning, then sums. */
    MPI_Request rq;
    MPI_Ibarrier(MPI_COMM_WORLD, &rq);
    wait_politely(&rq);
    double t_reduce = now_seconds();
    uint64_t taken = atomic_load(&w.tally.taken), all = 0;
    MPI_Reduce(&taken, &all, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    size_t npix = (size_t)width * (size_t)height;
    reduce_to_root(film->sum, npix * (size_t)film->nchannels, rank);
    reduce_to_root(film->weight, npix, rank);
    reduce_to_root(film->samples, npix * 3, rank);
    reduce_to_root(film->ids, npix * 2, rank); /* one rank took each pixel's sample 0 */
    double t_end = now_seconds();
    double *ready = rank == 0 ? calloc((size_t)size, sizeof(double)) : NULL;
    if (rank == 0 && !ready)
        abort();
    MPI_Gather(&ready_cpu, 1, MPI_DOUBLE, ready, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    /* Interrupted: fewer samples than asked for. Every rank learns it from
     * rank 0, so that they all stop or go on (--frames) together. */
    render_stats st = {t_end - w.tally.t_start, rank == 0 ? all : taken, all < render_sample_count(s, s0, s1),
                       w.tally.busy_cpu_seconds, w.tally.idle_cpu_seconds};
    MPI_Bcast(&st.interrupted, 1, MPI_INT, 0, MPI_COMM_WORLD);
    film->meta.seconds = st.seconds, film->meta.interrupted = st.interrupted;
    /* Passes' worth of samples: units of a pass may be taken out of order. */
    film->meta.passes = (int)(all / render_sample_count(s, s0, s0 + plan.pass_spp));
    film->meta.threads = w.threads, film->meta.ranks = size;
    if (rank == 0) {
        if (opt->progress) {
            if (!st.interrupted)
                progress_end(&c.bar);
            char who[64];
            snprintf(who, sizeof who, "%d ranks (rank 0: %d thread%s)", size, w.threads, w.threads > 1 ? "s" : "");
            render_print_summary(s, opt, &st, who);
            print_balance(&c, ready, t_end - t_reduce);
        }
        free(c.told_none), free(c.told_stop), free(c.units), free(c.taken), free(ready);
    } else {
        film_free(film);
    }
    if (stats)
        *stats = st;
    render_stop_clear();
    cpu_after_last_render = process_cpu_seconds();
    return 0;
}
