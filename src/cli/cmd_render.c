/* celadon render: a Mitsuba 3 scene rendered with the path tracer to EXR
 * (float32, optional AOV channels) or PNG/JPEG (sRGB, 8-bit). */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "celadon/render.h"
#include "celadon/scene.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

enum { MAX_DEFINES = 64 };

static void usage(FILE *f)
{
    fprintf(f, "usage: celadon render SCENE.xml -o OUT.{exr,png,jpg} [--spp N] [--res WxH]\n"
               "                      [--geometry analytic|mesh:N] [--threads N] [--seed S]\n"
               "                      [--sampler NAME] [-D name=value]... [--aov depth,normal,albedo]\n\n"
               "Renders a Mitsuba 3 scene (docs/scene-format.md) with the `path` integrator.\n"
               "SORs are intersected exactly unless --geometry mesh:N revolves them into N\n"
               "angular segments traced by Embree (same sampler seeds otherwise).\n\n"
               "  -o OUT          .exr (float32 RGB + AOV channels) or .png/.jpg (sRGB 8-bit)\n"
               "  --spp N         samples per pixel (default: the scene's sampler)\n"
               "  --res WxH       film size (default: the scene's film)\n"
               "  --geometry G    analytic (default) or mesh:N, N >= 3\n"
               "  --threads N     OpenMP threads (default: all cores)\n"
               "  --seed S        sampler seed (default: the scene's)\n"
               "  --sampler NAME  sampler plugin instead of the scene's, with its sample count and seed:\n"
               "                  independent, stratified, multijitter, orthogonal, ldsampler, zsobol\n"
               "  -D name=value   sets a scene <default> parameter\n"
               "  --aov LIST      extra EXR channels: depth, normal, albedo\n"
               "Ctrl-C stops the render and writes the image it has so far.\n");
}

static int output_kind_ok(const char *path, int *is_exr)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash))
        return 0;
    *is_exr = !strcasecmp(dot, ".exr");
    return *is_exr || !strcasecmp(dot, ".png") || !strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".jpeg");
}

static void on_sigint(int sig)
{
    (void)sig;
    render_request_stop();
}

int cmd_render(int argc, char **argv)
{
    const char *scene_path = NULL, *out = NULL;
    scene_options bo = scene_options_default();
    render_options ro = {0, 0, 1};
    scene_define defs[MAX_DEFINES];
    int ndefs = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        long long v;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        }
        if (a[0] != '-' || !a[1]) {
            if (scene_path)
                return cli_usage_error("render", "unexpected argument '%s'", a);
            scene_path = a;
            continue;
        }
        if (!val)
            return cli_usage_error("render", "option %s needs a value", a);
        i++;
        if (!strcmp(a, "-o")) {
            out = val;
        } else if (!strcmp(a, "--spp")) {
            if (cli_parse_int(val, 1, 1 << 24, &v) != 0)
                return cli_usage_error("render", "--spp wants an integer from 1 to 16777216, not '%s'", val);
            bo.spp = (int)v;
        } else if (!strcmp(a, "--res")) {
            int w, h, n = 0;
            if (sscanf(val, "%dx%d%n", &w, &h, &n) != 2 || val[n] || w < 1 || h < 1 || w > 65536 || h > 65536)
                return cli_usage_error("render", "--res wants WxH with sizes from 1 to 65536, not '%s'", val);
            bo.width = w, bo.height = h;
        } else if (!strcmp(a, "--geometry")) {
            if (!strcmp(val, "analytic"))
                bo.mesh_segments = 0;
            else if (!strncmp(val, "mesh:", 5) && cli_parse_int(val + 5, 3, 1000000, &v) == 0)
                bo.mesh_segments = (int)v;
            else
                return cli_usage_error("render", "--geometry wants analytic or mesh:N with N from 3 to 1000000, not '%s'", val);
        } else if (!strcmp(a, "--threads")) {
            if (cli_parse_int(val, 1, 1024, &v) != 0)
                return cli_usage_error("render", "--threads wants an integer from 1 to 1024, not '%s'", val);
            ro.threads = (int)v;
        } else if (!strcmp(a, "--seed")) {
            if (cli_parse_int(val, 0, (long long)(~0ull >> 1), &v) != 0)
                return cli_usage_error("render", "--seed wants a non-negative integer, not '%s'", val);
            bo.seed = v;
        } else if (!strcmp(a, "--sampler")) {
            if (!scene_plugin_find(SCENE_SAMPLER, val))
                return cli_usage_error("render", "--sampler wants independent, stratified, multijitter, orthogonal, "
                                                 "ldsampler or zsobol, not '%s'", val);
            bo.sampler = val;
        } else if (!strcmp(a, "-D")) {
            const char *eq = strchr(val, '=');
            if (!eq || eq == val || ndefs == MAX_DEFINES)
                return cli_usage_error("render", "-D wants name=value, not '%s'", val);
            char *name = strndup(val, (size_t)(eq - val));
            if (!name)
                return 1;
            defs[ndefs++] = (scene_define){name, eq + 1};
        } else if (!strcmp(a, "--aov")) {
            if (render_aov_parse(val, &ro.aovs) != 0)
                return cli_usage_error("render", "--aov wants a list of depth, normal, albedo, not '%s'", val);
        } else {
            return cli_usage_error("render", "unknown option '%s'", a);
        }
    }
    int rc = 2, is_exr = 0;
    if (!scene_path)
        rc = cli_usage_error("render", "%s", "missing SCENE.xml");
    else if (!out)
        rc = cli_usage_error("render", "%s", "missing -o OUT");
    else if (!output_kind_ok(out, &is_exr))
        rc = cli_usage_error("render", "output '%s' must end in .exr, .png, .jpg or .jpeg", out);
    else if (ro.aovs && !is_exr)
        rc = cli_usage_error("render", "--aov needs an .exr output, not '%s'", out);
    else
        rc = -1;
    if (rc >= 0) {
        for (int i = 0; i < ndefs; i++)
            free((char *)defs[i].name);
        return rc;
    }

    /* From here Ctrl-C asks for the image so far (an empty one while loading). */
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old);
    char err[2048];
    scene_t *scene = scene_create_from_file(scene_path, defs, ndefs, &bo, err, sizeof err);
    for (int i = 0; i < ndefs; i++)
        free((char *)defs[i].name);
    if (!scene) {
        fprintf(stderr, "celadon: %s\n", err);
        return 2;
    }
    film_t film;
    render_stats st;
    rc = render_scene(scene, &ro, &film, &st, err, sizeof err) == 0 ? 0 : 1;
    sigaction(SIGINT, &old, NULL);
    scene_destroy(scene);
    if (rc != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return rc;
    }
    if (film_write(&film, out, err, sizeof err) != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        rc = 1;
    } else if (st.interrupted) {
        fprintf(stderr, "celadon: interrupted; wrote the partial image %s\n", out);
        rc = 130;
    }
    film_free(&film);
    return rc;
}
