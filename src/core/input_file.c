#include "core/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* 1 GiB, 3.5 MiB, 812 bytes: a size for messages. */
static void size_text(long long n, char *buf, size_t len)
{
    if (n >= 1ll << 30)
        snprintf(buf, len, "%.1f GiB", (double)n / (1ll << 30));
    else if (n >= 1ll << 20)
        snprintf(buf, len, "%.1f MiB", (double)n / (1ll << 20));
    else
        snprintf(buf, len, "%lld bytes", n);
}

/* The checks on an open descriptor: a regular file within the limit. */
static int check_fd(int fd, long long max_bytes, long long *size, char *why, size_t whylen)
{
    struct stat st;
    if (fstat(fd, &st) != 0) {
        snprintf(why, whylen, "cannot read: %s", strerror(errno));
        return -1;
    }
    if (S_ISDIR(st.st_mode)) {
        snprintf(why, whylen, "is a folder, not a file");
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, whylen, "not a regular file (a device, FIFO or socket)");
        return -1;
    }
    if ((long long)st.st_size > max_bytes) {
        char have[32], limit[32];
        size_text((long long)st.st_size, have, sizeof have);
        size_text(max_bytes, limit, sizeof limit);
        snprintf(why, whylen, "too large (%s; at most %s)", have, limit);
        return -1;
    }
    if (size)
        *size = (long long)st.st_size;
    return 0;
}

/* O_NONBLOCK: opening a FIFO must not wait for a writer. */
static int open_checked(const char *path, long long max_bytes, long long *size, char *why, size_t whylen)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, whylen, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (check_fd(fd, max_bytes, size, why, whylen) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

int input_check(const char *path, long long max_bytes, long long *size, char *why, size_t whylen)
{
    int fd = open_checked(path, max_bytes, size, why, whylen);
    if (fd < 0)
        return -1;
    close(fd);
    return 0;
}

FILE *input_open(const char *path, long long max_bytes, long long *size, char *why, size_t whylen)
{
    int fd = open_checked(path, max_bytes, size, why, whylen);
    if (fd < 0)
        return NULL;
    int flags = fcntl(fd, F_GETFL);
    FILE *f = flags >= 0 && fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) == 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        snprintf(why, whylen, "cannot read: %s", strerror(errno));
        close(fd);
    }
    return f;
}

int input_read_all(const char *path, long long max_bytes, char **buf, size_t *len, char *why, size_t whylen)
{
    long long size;
    FILE *f = input_open(path, max_bytes, &size, why, whylen);
    if (!f)
        return -1;
    char *b = malloc((size_t)size + 1);
    size_t n = b ? fread(b, 1, (size_t)size, f) : 0;
    int bad = !b ? ENOMEM : ferror(f) ? EIO : 0;
    fclose(f);
    if (bad || n != (size_t)size) {
        snprintf(why, whylen, "cannot read: %s", bad ? strerror(bad) : "the file changed while it was read");
        free(b);
        return -1;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return 0;
}
