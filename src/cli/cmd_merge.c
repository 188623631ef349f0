/* celadon merge: the parts of a render (celadon render --part K/N) summed
 * into its image, once they are checked to belong together and be complete. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/parts.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon merge PART.exr... -o OUT.{exr,hdr,tif,png,jpg}\n\n"
               "Sums the parts of a render (celadon render --part K/N, any order) into its\n"
               "image, the same as one process would have rendered up to float rounding.\n"
               "Refuses, naming the file or the missing shares, a set that is not all N\n"
               "parts of one render (same scene, files, options and seed), each once and\n"
               "complete (docs/distributed.md).\n\n"
               "  -o OUT    .exr (float32, the render's pixel format + the AOV channels), .hdr,\n"
               "            .tif (float32) or .png/.jpg (sRGB 8-bit), with the render's metadata\n");
}

/* The part that out names (the same file, under any name), or NULL. */
static const char *part_named_by(const char *out, const char *const *parts, int n)
{
    for (int i = 0; i < n; i++)
        if (cli_same_file(out, parts[i]))
            return parts[i];
    return NULL;
}

int cmd_merge(int argc, char **argv)
{
    const char *out = NULL;
    const char **parts = calloc((size_t)argc, sizeof *parts);
    if (!parts)
        return 1;
    int n = 0, rc = -1;
    char why[1200];
    for (int i = 1; i < argc && rc < 0; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            rc = 0;
        } else if (!strcmp(a, "-o")) {
            if (i + 1 == argc)
                rc = cli_usage_error("merge", "option %s needs a value", a);
            else
                out = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            rc = cli_usage_error("merge", "unknown option '%s'", a);
        } else {
            parts[n++] = a;
        }
    }
    if (rc < 0 && !out)
        rc = cli_usage_error("merge", "%s", "missing -o OUT");
    else if (rc < 0 && film_output_check(out, 0, why, sizeof why) != 0)
        rc = cli_usage_error("merge", "%s", why);
    else if (rc < 0 && n == 0)
        rc = cli_usage_error("merge", "%s", "no PART.exr given");
    else if (rc < 0 && part_named_by(out, parts, n)) {
        fprintf(stderr, "celadon: %s: is one of the parts being merged (%s): choose another output\n", out,
                part_named_by(out, parts, n));
        rc = 2;
    } else if (rc < 0 && cli_check_output(out, 0) != 0)
        rc = CLI_CANNOT_WRITE;
    if (rc < 0) {
        film_t film;
        char err[2048];
        int m = render_parts_merge(parts, n, NULL, &film, err, sizeof err);
        if (m == 0) {
            rc = film_write(&film, out, err, sizeof err) == 0 ? 0 : 1;
            film_free(&film);
        } else {
            rc = m == -2 ? 2 : 1;
        }
        if (rc != 0)
            fprintf(stderr, "celadon: %s\n", err);
        else
            fprintf(stderr, "merge: %d parts into %s\n", n, out);
    }
    free(parts);
    return rc;
}
