#include "core/temp_files.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { SLOT_FREE, SLOT_FILLING, SLOT_LIVE };

static struct {
    atomic_int state;
    char path[4200];
} slots[TEMP_FILES_MAX];

static atomic_int changes; /* holds under way, over every thread */
static atomic_int dying;   /* a handler is removing the temporaries */
static _Thread_local int depth;          /* this thread's nested holds */
static _Thread_local sigset_t mask_before; /* its signal mask outside them */

/* CELADON_TEST_SIGNAL_AT=N:SIG (docs/faults.md): the Nth hold of the
 * process sends the process SIG once it has begun, so that tests can
 * interrupt at every change to the file system in turn; the thread that
 * sent it does not go on past that hold until a handler has begun. */
static long signal_at;
static int signal_at_sig;
static atomic_long holds_begun;
static _Thread_local int sent_signal_at; /* this thread's hold sent it */

void temp_files_track(const char *path)
{
    if (strlen(path) >= sizeof slots[0].path)
        return;
    for (int i = 0; i < TEMP_FILES_MAX; i++) {
        int expected = SLOT_FREE;
        if (atomic_compare_exchange_strong(&slots[i].state, &expected, SLOT_FILLING)) {
            strcpy(slots[i].path, path);
            atomic_store(&slots[i].state, SLOT_LIVE);
            return;
        }
    }
}

void temp_files_forget(const char *path)
{
    for (int i = 0; i < TEMP_FILES_MAX; i++)
        if (atomic_load(&slots[i].state) == SLOT_LIVE && strcmp(slots[i].path, path) == 0) {
            atomic_store(&slots[i].state, SLOT_FREE);
            return;
        }
}

/* Removes name (relative to dirfd) and, when it is a folder, what it holds,
 * down to depth levels; only async-signal-safe calls (getdents64, not
 * readdir). Entries removed while listing may shift the listing, so a
 * folder is listed again until a pass removes nothing. Returns 0 when name
 * is gone. */
static int remove_tree_at(int dirfd, const char *name, int depth)
{
    if (unlinkat(dirfd, name, 0) == 0 || errno == ENOENT)
        return 0;
    if ((errno != EISDIR && errno != EPERM) || depth == 0)
        return -1;
    int fd = openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return -1;
    for (int removed = 1; removed;) {
        removed = 0;
        char buf[4096];
        long n;
        lseek(fd, 0, SEEK_SET);
        while ((n = (long)getdents64(fd, buf, sizeof buf)) > 0)
            for (long off = 0; off < n;) {
                struct dirent64 *e = (struct dirent64 *)(void *)(buf + off);
                off += e->d_reclen;
                if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && remove_tree_at(fd, e->d_name, depth - 1) == 0)
                    removed = 1;
            }
    }
    close(fd);
    return unlinkat(dirfd, name, AT_REMOVEDIR);
}

/* Waits for the holds under way (at most 2 s: a thread that never ends
 * its hold must not keep the process alive), then removes every tracked
 * temporary and ends the process by sig. No new hold begins meanwhile. */
static void clean_up_and_die(int sig)
{
    atomic_store(&dying, 1);
    for (int ms = 0; atomic_load(&changes) > 0 && ms < 2000; ms++)
        nanosleep(&(struct timespec){0, 1000000}, NULL);
    for (int i = 0; i < TEMP_FILES_MAX; i++)
        if (atomic_load(&slots[i].state) == SLOT_LIVE)
            remove_tree_at(AT_FDCWD, slots[i].path, 8);
    signal(sig, SIG_DFL);
    raise(sig); /* delivered when the handler returns */
}

static void on_signal(int sig)
{
    int saved = errno;
    clean_up_and_die(sig);
    errno = saved;
}

static void fill_ending_signals(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGINT);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGHUP);
}

void temp_files_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    fill_ending_signals(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    const char *at = getenv("CELADON_TEST_SIGNAL_AT");
    if (at) {
        char *end;
        signal_at = strtol(at, &end, 10);
        signal_at_sig = *end == ':' ? (int)strtol(end + 1, &end, 10) : 0;
        if (*end || signal_at_sig <= 0)
            signal_at = 0;
    }
}

/* The three signals are blocked in this thread during its holds, so a
 * handler never runs inside one: it runs in another thread and waits for
 * the hold to end, or here once the hold ends and the signal is unblocked.
 * The count goes up before dying is read and the handler sets dying before
 * it reads the count, so one of the two always sees the other. */
void temp_files_hold(void)
{
    if (depth++ > 0)
        return;
    sigset_t block;
    fill_ending_signals(&block);
    pthread_sigmask(SIG_BLOCK, &block, &mask_before);
    atomic_fetch_add(&changes, 1);
    if (atomic_load(&dying)) { /* the process is ending: no more changes */
        atomic_fetch_sub(&changes, 1);
        for (;;)
            pause();
    }
    if (signal_at > 0 && atomic_fetch_add(&holds_begun, 1) + 1 == signal_at) {
        sent_signal_at = 1;
        kill(getpid(), signal_at_sig);
    }
}

/* Once a handler has begun (in another thread, waiting for the holds), the
 * thread that ends a hold goes no further: were it to reach exit() first,
 * the process would end with status 0 in the middle of the clean-up. Here
 * the signals are unblocked again, so a signal pending for this thread runs
 * its handler before the check. */
void temp_files_release(void)
{
    if (--depth > 0)
        return;
    atomic_fetch_sub(&changes, 1);
    pthread_sigmask(SIG_SETMASK, &mask_before, NULL);
    for (int ms = 0; sent_signal_at && !atomic_load(&dying) && ms < 2000; ms++)
        nanosleep(&(struct timespec){0, 1000000}, NULL); /* the other thread's handler is on its way */
    if (atomic_load(&dying))
        for (;;)
            pause();
}
