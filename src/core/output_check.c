#include "core/output_check.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static atomic_uint probe_counter;

int output_check(const char *path, int is_folder, char *why, size_t whylen)
{
    char dir[PATH_MAX];
    if (snprintf(dir, sizeof dir, "%s", path) >= (int)sizeof dir) {
        snprintf(why, whylen, "%s", strerror(ENAMETOOLONG));
        return -1;
    }
    /* The folder the temporaries go into: the output's own when it is a
     * folder that exists, else the nearest existing folder above it. */
    struct stat st;
    int exists = is_folder && stat(dir, &st) == 0;
    if (exists && !S_ISDIR(st.st_mode)) {
        snprintf(why, whylen, "%s", strerror(ENOTDIR));
        return -1;
    }
    while (!exists) {
        char *slash = strrchr(dir, '/');
        if (!slash)
            strcpy(dir, ".");
        else if (slash == dir)
            dir[1] = '\0';
        else
            *slash = '\0';
        exists = stat(dir, &st) == 0;
        if (!exists && (!slash || slash == dir))
            break;
        if (exists && !S_ISDIR(st.st_mode)) {
            snprintf(why, whylen, "%s", strerror(ENOTDIR));
            return -1;
        }
        if (!is_folder)
            break; /* a file's folder must exist: nothing makes it */
    }
    if (!exists) {
        snprintf(why, whylen, "%s", strerror(ENOENT));
        return -1;
    }
    char probe[PATH_MAX + 64];
    snprintf(probe, sizeof probe, "%s/.celadon-probe-%ld-%u", dir, (long)getpid(), atomic_fetch_add(&probe_counter, 1u));
    int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        snprintf(why, whylen, "%s", strerror(errno));
        return -1;
    }
    close(fd);
    unlink(probe);
    return 0;
}
