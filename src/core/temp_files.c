#include "core/temp_files.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <string.h>
#include <unistd.h>

enum { SLOT_FREE, SLOT_FILLING, SLOT_LIVE };

static struct {
    atomic_int state;
    char path[4200];
} slots[TEMP_FILES_MAX];

static atomic_int holds;          /* moves into place under way */
static volatile sig_atomic_t held_signal; /* a signal that came during one */

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

/* Removes every tracked temporary, then ends the process by sig. */
static void clean_up_and_die(int sig)
{
    for (int i = 0; i < TEMP_FILES_MAX; i++)
        if (atomic_load(&slots[i].state) == SLOT_LIVE)
            remove_tree_at(AT_FDCWD, slots[i].path, 8);
    signal(sig, SIG_DFL);
    raise(sig);
}

static void on_signal(int sig)
{
    int saved = errno;
    if (atomic_load(&holds) > 0)
        held_signal = sig;
    else
        clean_up_and_die(sig); /* delivered when this handler returns */
    errno = saved;
}

void temp_files_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGHUP);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

void temp_files_hold(void) { atomic_fetch_add(&holds, 1); }

void temp_files_release(void)
{
    if (atomic_fetch_sub(&holds, 1) == 1 && held_signal)
        clean_up_and_die(held_signal);
}
