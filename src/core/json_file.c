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

/* The length of the valid UTF-8 sequence at s (RFC 3629: no overlong
 * forms, no surrogates, nothing above U+10FFFF), or 0. */
static int utf8_length(const unsigned char *s)
{
    unsigned c = s[0];
    if (c < 0x80)
        return 1;
    int n = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    /* The second byte's range narrows after E0, ED, F0 and F4. */
    unsigned lo = c == 0xe0 ? 0xa0 : c == 0xf0 ? 0x90 : 0x80, hi = c == 0xed ? 0x9f : c == 0xf4 ? 0x8f : 0xbf;
    if (n && !(s[1] >= lo && s[1] <= hi))
        return 0;
    for (int i = 2; i < n; i++)
        if ((s[i] & 0xc0) != 0x80)
            return 0;
    return n;
}

const char *json_text(const char *s, char *buf, size_t len)
{
    const unsigned char *p = (const unsigned char *)s;
    int valid = 1;
    for (size_t i = 0; p[i] && valid; i += (size_t)utf8_length(p + i))
        valid = utf8_length(p + i) > 0;
    if (valid)
        return s;
    size_t n = 0;
    for (size_t i = 0; p[i];) {
        int k = utf8_length(p + i);
        const char *piece = k ? (const char *)p + i : "\xef\xbf\xbd"; /* U+FFFD */
        size_t m = k ? (size_t)k : 3;
        if (n + m + 1 > len)
            break;
        memcpy(buf + n, piece, m);
        n += m;
        i += k ? (size_t)k : 1;
    }
    buf[n] = '\0';
    return buf;
}
