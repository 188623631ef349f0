#include "core/json_file.h"

#include <errno.h>
#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "core/atomic_file.h"

int json_write_file_atomic(const char *path, const json_t *root, size_t flags, char *err, size_t errlen)
{
    atomic_file af;
    errno = 0;
    int rc = -1;
    if (atomic_file_open(&af, path) == 0) {
        if (json_dumpf(root, af.fp, flags) == 0 && fputc('\n', af.fp) != EOF)
            rc = atomic_file_commit(&af);
        else
            atomic_file_abort(&af);
    }
    if (rc != 0)
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
    return rc;
}
