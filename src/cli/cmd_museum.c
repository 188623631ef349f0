/* celadon museum: photographs of vessels -> a walkable museum (museum.glb +
 * the page, museum.xml + preview.png) in one folder, and a small server for
 * it on 127.0.0.1. The CLI parses, calls museum_build, prints. */
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/museum.h"
#include "celadon/render.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

#ifndef CELADON_WEB_DIR
#define CELADON_WEB_DIR "build/web"
#endif
#define DEFAULT_PORT 8000

static void usage(FILE *f)
{
    fprintf(f,
            "usage: celadon museum PHOTO... -o DIR [options]\n"
            "       celadon museum --catalogue FILE.csv -o DIR [options]\n"
            "       celadon museum --serve [PORT] -o DIR\n\n"
            "Reconstructs every photo and builds a museum in DIR: museum.glb (glTF 2.0 with\n"
            "levels of detail, glass cases, lights, labels), index.html + museum.js (walk it in\n"
            "a browser or a WebXR headset), museum.xml (the same museum for celadon render)\n"
            "and preview.png (its path-traced view from the entrance). docs/museum.md.\n\n"
            "options:\n"
            "  -o, --output DIR     the museum folder: new, empty, or an earlier museum\n"
            "  --catalogue FILE     CSV: file,title,date,height_cm,diameter_cm,description\n"
            "                       (only file needed); without photos on the command line,\n"
            "                       its rows are the photos\n"
            "  --title TEXT         the museum's name (default \"Celadon museum\")\n"
            "  --lod N,N,...        angular segments of the levels of detail (default: chosen\n"
            "                       per vessel by screen-space error)\n"
            "  --preview-res WxH    size of preview.png (default 640x360)\n"
            "  --preview-spp N      its samples per pixel (default 16; 0: no preview)\n"
            "  --bake-spp N         samples per texel of the room's light, baked by the path\n"
            "                       tracer into the page (default %d)\n"
            "  --force              include vessels that fail the quality gate (reconstruct\n"
            "                       --force); their labels say so\n"
            "  --serve [PORT]       then serve DIR on http://127.0.0.1:PORT/ (default %d;\n"
            "                       0: any free port) until Ctrl-C; without photos, serves an\n"
            "                       existing museum\n"
            "  -h, --help           this text\n\n"
            "Ctrl-C during the preview stops it early: the museum is written with the preview\n"
            "as far as it got.\n\n"
            "A vessel with neither a catalogue height nor diameter is %.0f cm tall (its label\n"
            "says \"Height not recorded\"). exit status: 0 every photo is in the museum, 2 bad\n"
            "input or usage (refused photos are left out, the rest still make the museum),\n"
            "1 internal failure\n",
            MUSEUM_DEFAULT_BAKE_SPP, DEFAULT_PORT, MUSEUM_DEFAULT_HEIGHT_CM);
}

typedef struct {
    museum_options museum;
    int serve, port;
} options;

static int parse_res(const char *s, int *w, int *h)
{
    char extra;
    return sscanf(s, "%dx%d%c", w, h, &extra) == 2 && *w >= 8 && *h >= 8 && *w <= 8192 && *h <= 8192 ? 0 : -1;
}

static int all_digits(const char *s)
{
    for (const char *p = s; *p; p++)
        if (*p < '0' || *p > '9')
            return 0;
    return *s != 0;
}

/* Returns -1 to continue, otherwise the exit code. */
static int parse_options(int argc, char **argv, options *o)
{
    enum { OPT_CATALOGUE = 256, OPT_TITLE, OPT_LOD, OPT_RES, OPT_SPP, OPT_BAKE_SPP, OPT_SERVE, OPT_FORCE };
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'},      {"catalogue", required_argument, NULL, OPT_CATALOGUE},
        {"title", required_argument, NULL, OPT_TITLE}, {"lod", required_argument, NULL, OPT_LOD},
        {"preview-res", required_argument, NULL, OPT_RES}, {"preview-spp", required_argument, NULL, OPT_SPP},
        {"bake-spp", required_argument, NULL, OPT_BAKE_SPP}, {"serve", optional_argument, NULL, OPT_SERVE}, {"force", no_argument, NULL, OPT_FORCE},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    *o = (options){.museum = museum_options_default(), .port = DEFAULT_PORT};
    opterr = 0;
    optind = 1;
    long long v;
    for (int c; (c = getopt_long(argc, argv, ":o:h", longopts, NULL)) != -1;) {
        switch (c) {
        case 'o': o->museum.out_dir = optarg; break;
        case OPT_CATALOGUE: o->museum.catalogue = optarg; break;
        case OPT_TITLE:
            if (!*optarg || strlen(optarg) > 200)
                return cli_usage_error("museum", "--title wants 1 to 200 characters, not '%s'", optarg);
            o->museum.title = optarg;
            break;
        case OPT_LOD:
            if (cli_parse_int_list(optarg, 3, 4096, o->museum.lods, MUSEUM_MAX_LODS, &o->museum.n_lods) != 0)
                return cli_usage_error("museum", "--lod wants up to 8 comma-separated integers 3..4096, not '%s'",
                                       optarg);
            break;
        case OPT_RES:
            if (parse_res(optarg, &o->museum.preview_width, &o->museum.preview_height) != 0)
                return cli_usage_error("museum", "--preview-res wants WxH, each 8..8192, not '%s'", optarg);
            break;
        case OPT_SPP:
            if (cli_parse_int(optarg, 0, 65536, &v) != 0)
                return cli_usage_error("museum", "--preview-spp wants an integer 0..65536, not '%s'", optarg);
            o->museum.preview_spp = (int)v;
            break;
        case OPT_BAKE_SPP:
            if (cli_parse_int(optarg, 1, 65536, &v) != 0)
                return cli_usage_error("museum", "--bake-spp wants an integer 1..65536, not '%s'", optarg);
            o->museum.bake_spp = (int)v;
            break;
        case OPT_SERVE: {
            /* --serve=PORT, or --serve PORT when the next word is a number. */
            const char *port = optarg ? optarg : optind < argc && all_digits(argv[optind]) ? argv[optind++] : NULL;
            o->serve = 1;
            if (port && cli_parse_int(port, 0, 65535, &v) != 0)
                return cli_usage_error("museum", "--serve wants a port 0..65535, not '%s'", port);
            o->port = port ? (int)v : DEFAULT_PORT;
            break;
        }
        case OPT_FORCE: o->museum.force = 1; break;
        case 'h': usage(stdout); return 0;
        case ':': return cli_usage_error("museum", "%s needs a value", argv[optind - 1]);
        default: return cli_usage_error("museum", "unknown option '%s'", argv[optind - 1]);
        }
    }
    if (!o->museum.out_dir || !*o->museum.out_dir)
        return cli_usage_error("museum", "%s", "no output folder (-o DIR)");
    if (optind >= argc && !o->museum.catalogue && !o->serve)
        return cli_usage_error("museum", "%s", "no photo given (PHOTO... or --catalogue FILE)");
    return -1;
}

static void print_summary(const museum_options *o, const museum_report *r)
{
    fprintf(stderr,
            "celadon: museum of %d vessel%s in %s/ (room %.1f x %.1f x %.1f m)\n"
            "  museum.glb %.1f MB; triangles %lld at full detail, %lld seen from the entrance (LOD), %lld at the "
            "coarsest; %d draw calls\n"
            "  reconstruct %.2f s, write %.2f s (light baked in %.2f s), preview %.2f s; total %.2f s\n",
            r->n_vessels, r->n_vessels == 1 ? "" : "s", o->out_dir, r->room[0], r->room[1], r->room[2],
            r->glb_bytes / 1e6, r->triangles_full, r->triangles_entrance, r->triangles_coarsest, r->draw_calls,
            r->ms_reconstruct / 1e3, r->ms_write / 1e3, r->ms_bake / 1e3, r->ms_preview / 1e3, r->ms_total / 1e3);
    if (r->web_missing)
        fprintf(stderr, "celadon: warning: index.html and museum.js are not in %s (`make` builds them with npm, "
                        "which `make deps` installs): the folder has no page yet\n",
                o->web_dir);
}

/* Ctrl-C cuts the preview short: the museum is still written whole, with
 * the preview as far as it got. */
static void on_sigint(int sig)
{
    (void)sig;
    render_request_stop();
}

static int serve(const char *dir, int port)
{
    char manifest[4200], err[512];
    struct stat st;
    snprintf(manifest, sizeof manifest, "%s/museum.json", dir);
    if (stat(manifest, &st) != 0) {
        fprintf(stderr, "celadon: %s: not a museum (no museum.json); build one with celadon museum PHOTO... -o %s\n",
                dir, dir);
        return 2;
    }
    if (museum_serve(dir, port, err, sizeof err) != 0) {
        fprintf(stderr, "celadon: %s\n", err);
        return 1;
    }
    return 0;
}

int cmd_museum(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    int n = argc - optind;
    if (n == 0 && !o.museum.catalogue)
        return serve(o.museum.out_dir, o.port);
    if (cli_check_output(o.museum.out_dir, 1) != 0)
        return CLI_CANNOT_WRITE;
    const char *web = getenv("CELADON_WEB_DIR");
    o.museum.web_dir = web && *web ? web : CELADON_WEB_DIR;
    o.museum.progress = 1;
    void (*previous)(int) = signal(SIGINT, on_sigint);
    museum_report rep;
    char err[1024] = "";
    rc = museum_build((const char *const *)argv + optind, n, &o.museum, &rep, err, sizeof err);
    int built = rep.n_vessels, refused = 0;
    for (int i = 0; i < rep.n_photos; i++)
        if (rep.photos[i].status != 0) {
            fprintf(stderr, "celadon: %s: %s\n", rep.photos[i].photo, rep.photos[i].error);
            refused++;
        } else if (rep.photos[i].below_gate) {
            fprintf(stderr, "celadon: warning: %s: %s\n", rep.photos[i].photo, rep.photos[i].error);
        }
    if (built > 0 && rc != 1)
        print_summary(&o.museum, &rep);
    else if (!(built == 0 && refused == rep.n_photos && refused > 0)) /* those lines said it all */
        fprintf(stderr, "celadon: %s\n", err);
    museum_report_free(&rep);
    signal(SIGINT, previous);
    if (o.serve && rc != 1 && built > 0) {
        int src = serve(o.museum.out_dir, o.port);
        return src ? src : rc;
    }
    return rc;
}
