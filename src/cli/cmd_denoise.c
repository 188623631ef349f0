/* celadon denoise: a render's EXR (with the denoising, half, specular and variance
 * AOVs) denoised into another EXR (denoise.h). */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "celadon/denoise.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon denoise IN.exr -o OUT.exr\n\n"
               "Denoises a render's colour by a first-order regression on its features\n"
               "(docs/rendering.md, \"Denoising\"). IN.exr must hold R, G, B and the channels of\n"
               "celadon render --aov denoising,half,specular,variance. OUT.exr has every channel\n"
               "of IN.exr, R, G, B denoised, and IN.exr's header plus celadon/denoised.\n");
}

static int is_exr(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strchr(dot, '/') && !strcasecmp(dot, ".exr");
}

int cmd_denoise(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o")) {
            if (i + 1 == argc)
                return cli_usage_error("denoise", "option %s needs a value", a);
            out = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_usage_error("denoise", "unknown option '%s'", a);
        } else if (in) {
            return cli_usage_error("denoise", "unexpected argument '%s'", a);
        } else {
            in = a;
        }
    }
    if (!in)
        return cli_usage_error("denoise", "%s", "missing IN.exr");
    if (!out)
        return cli_usage_error("denoise", "%s", "missing -o OUT.exr");
    if (!is_exr(out))
        return cli_usage_error("denoise", "the output must be an .exr, not '%s'", out);
    if (cli_same_file(in, out)) {
        fprintf(stderr, "celadon: %s: is the input: choose another output\n", out);
        return CLI_BAD_INPUT;
    }
    if (cli_check_output(out, 0) != 0)
        return CLI_CANNOT_WRITE;
    char err[2048];
    int rc = denoise_exr(in, out, err, sizeof err);
    if (rc != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return rc == -2 ? CLI_BAD_INPUT : CLI_CANNOT_WRITE;
    }
    return CLI_OK;
}
