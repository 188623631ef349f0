#include "core/folder.h"

#include "core/temp_files.h"

#include <dirent.h>
#include <errno.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static atomic_uint temp_counter;

int folder_make(const char *path, char made[][PATH_MAX], int max_made, int *n_made)
{
    char buf[PATH_MAX];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char saved = *p;
        *p = '\0';
        if (mkdir(buf, 0777) == 0) {
            if (*n_made < max_made)
                snprintf(made[(*n_made)++], PATH_MAX, "%s", buf);
        } else if (errno != EEXIST) {
            return -1;
        }
        *p = saved;
        if (!saved)
            break;
    }
    struct stat st;
    if (stat(path, &st) != 0)
        return -1;
    if (!S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return -1;
    }
    return 0;
}

int folder_make_temp(const char *final, char *tmp, size_t len)
{
    struct stat st;
    unsigned k = atomic_fetch_add(&temp_counter, 1u);
    int n;
    if (stat(final, &st) == 0 && S_ISDIR(st.st_mode)) {
        n = snprintf(tmp, len, "%s/.celadon-tmp-%ld-%u", final, (long)getpid(), k);
    } else {
        const char *slash = strrchr(final, '/');
        int dirlen = slash ? (int)(slash - final) + 1 : 0;
        n = snprintf(tmp, len, "%.*s.celadon-tmp-%ld-%u", dirlen, final, (long)getpid(), k);
    }
    if (n < 0 || (size_t)n >= len) {
        errno = ENAMETOOLONG;
        return -1;
    }
    temp_files_hold();
    temp_files_track(tmp); /* before it exists: no moment without it */
    int rc = mkdir(tmp, 0777);
    if (rc != 0)
        temp_files_forget(tmp);
    temp_files_release();
    return rc == 0 ? 0 : -1;
}

void folder_remove(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char path[PATH_MAX + 256];
        while ((e = readdir(d)))
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
                snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
                remove(path);
            }
        closedir(d);
    }
    rmdir(dir);
    temp_files_forget(dir);
}

/* Moves the files, each rename, or none: a signal waits for the end. */
static int publish_files(const char *tmp, const char *final, const char *const *files, int n)
{
    struct stat st;
    if (stat(final, &st) != 0)
        return rename(tmp, final);
    for (int i = 0; i < n; i++) {
        char from[PATH_MAX + 64], to[PATH_MAX + 64];
        snprintf(from, sizeof from, "%s/%s", tmp, files[i]);
        snprintf(to, sizeof to, "%s/%s", final, files[i]);
        if (rename(from, to) != 0) {
            int saved = errno;
            for (int k = 0; k < i; k++) {
                snprintf(to, sizeof to, "%s/%s", final, files[k]);
                remove(to);
            }
            errno = saved;
            return -1;
        }
    }
    rmdir(tmp);
    return 0;
}

int folder_publish(const char *tmp, const char *final, const char *const *files, int n)
{
    temp_files_hold();
    int rc = publish_files(tmp, final, files, n);
    if (rc == 0)
        temp_files_forget(tmp);
    temp_files_release();
    return rc;
}
