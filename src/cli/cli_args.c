#include "cli/cli_args.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/core.h"

static int quiet;

void cli_set_quiet(int q) { quiet = q; }

int cli_check_output(const char *path, int is_folder)
{
    char why[256];
    if (output_check(path, is_folder, why, sizeof why) == 0)
        return 0;
    if (!quiet)
        fprintf(stderr, "celadon: %s: cannot write there: %s\n", path, why);
    return CLI_CANNOT_WRITE;
}

int cli_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

int cli_usage_error(const char *cmd, const char *fmt, const char *arg)
{
    if (quiet)
        return 2;
    fprintf(stderr, "celadon %s: ", cmd);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (try celadon %s --help)\n", cmd);
    return 2;
}

int cli_parse_int(const char *s, long long lo, long long hi, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int cli_parse_int_list(const char *s, long long lo, long long hi, int *out, int max, int *n)
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    snprintf(buf, sizeof buf, "%s", s);
    *n = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        long long v;
        if (*n == max || cli_parse_int(tok, lo, hi, &v) != 0)
            return -1;
        out[(*n)++] = (int)v;
    }
    return *n > 0 ? 0 : -1;
}

_Static_assert(CLI_MAX_SEARCH_DIRS == 64, "the -a limit's usage error names it");

int cli_add_search_dirs(const char *cmd, const char *val, char **dirs, int *n)
{
    for (const char *p = val;; p++) {
        size_t len = strcspn(p, ";");
        if (len == 0)
            return cli_usage_error(cmd, "-a wants a folder (or folders separated by ';'), not '%s'", val);
        if (*n == CLI_MAX_SEARCH_DIRS)
            return cli_usage_error(cmd, "at most 64 -a folders, not more ('%s')", val);
        if (!(dirs[*n] = strndup(p, len)))
            return 1;
        ++*n;
        p += len;
        if (!*p)
            return 0;
    }
}
