/* celadon reconstruct: photographs of vessels to profiles, textures, meshes
 * and diagnostic overlays. Photos of one call are processed in parallel (one
 * per thread, each single-threaded); every photo's outputs are written into a
 * temporary folder and moved into place only when all of them are complete. */
#include <dirent.h>
#include <errno.h>
#include <getopt.h>
#include <jansson.h>
#include <limits.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/curve_distance.h"
#include "celadon/curve_domains.h"
#include "celadon/curve_fit.h"
#include "celadon/image.h"
#include "celadon/mesh.h"
#include "celadon/overlay.h"
#include "celadon/profile.h"
#include "celadon/progress.h"
#include "celadon/recon.h"
#include "celadon/recon_texture.h"
#include "cli/cli_args.h"
#include "cli/commands.h"

enum { MIN_SIDE_PX = 32, MAX_LODS = 8 };
#define MAX_MEGAPIXELS 100.0
/* The curvature-adaptive domains (rings of the mesh): each within 0.25 px of
 * its chord, and its tangent angle within 0.25 deg of linear in arc length
 * (more domains where the curvature changes; bounds the interpolated shading
 * normal's error between rings). */
#define DOMAIN_TOL_PX 0.25
#define DOMAIN_TOL_NORMAL_DEG 0.25

typedef struct {
    const char *out_dir;
    recon_options recon;
    int segments;
    int lods[MAX_LODS], n_lods;
    int mouth_cap;
    int json;
    double smoothing_px;
} options;

typedef struct {
    int segments, vertices, faces;
} mesh_stats;

/* Everything one photo's run reports (the paper's Table 1 and more). */
typedef struct {
    const char *photo;
    char out[PATH_MAX];
    int exit_code; /* 0 ok, 1 internal failure, 2 bad input */
    char error[1024];
    int width, height;
    double tilt_deg;
    const char *side;
    int threshold_used, dropped_objects, holes_filled;
    int contour_points, approx_points, polyline_points, control_points, domains;
    mesh_stats mesh, lods[MAX_LODS];
    double err_curve_to_polyline, err_polyline_to_curve;
    double ms_decode, ms_image, ms_bspline, ms_domains, ms_hausdorff, ms_texture, ms_mesh, ms_overlay, ms_write,
        ms_total;
} report;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: celadon reconstruct PHOTO... -o DIR [options]\n\n"
            "Reconstructs each photographed vessel as a surface of revolution. With one\n"
            "photo the outputs go straight into DIR; with several, into DIR/STEM/ (STEM = the\n"
            "file name without extension, made unique with -2, -3, ...). Outputs: profile.json,\n"
            "texture.png, model.obj + model.mtl, model.ply, overlay.png.\n\n"
            "options:\n"
            "  -o, --output DIR     output folder (created if missing)\n"
            "  --threshold N        gray threshold 0..255 for the mask (default: automatic;\n"
            "                       photos with alpha use the alpha channel)\n"
            "  --side left|right|auto  silhouette side the profile is taken from (default auto)\n"
            "  --segments N         angular segments of model.obj/.ply (default 360)\n"
            "  --lod N,N,...        also write model_N.obj and model_N.ply for each N\n"
            "  --mouth-cap          close the mouth with a disc (the base is always closed)\n"
            "  --smoothing PX       largest distance of a profile point from the fitted\n"
            "                       B-spline, pixels (default 1)\n"
            "  --json               print the report as JSON on stdout (an array for several photos)\n"
            "  -h, --help           this text\n\n"
            "exit status: 0 all photos done, 2 bad input or usage (the other photos are still\n"
            "done), 1 internal failure\n");
}

/* ------------------------------------------------------------------ options */

static int parse_int(const char *s, long lo, long hi, int *out)
{
    long long v;
    if (cli_parse_int(s, lo, hi, &v) != 0)
        return -1;
    *out = (int)v;
    return 0;
}

static int parse_lods(const char *s, options *o)
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    snprintf(buf, sizeof buf, "%s", s);
    o->n_lods = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (o->n_lods == MAX_LODS || parse_int(tok, 3, 100000, &o->lods[o->n_lods]) != 0)
            return -1;
        o->n_lods++;
    }
    return o->n_lods > 0 ? 0 : -1;
}

/* Returns -1 to continue, otherwise the exit code. */
static int parse_options(int argc, char **argv, options *o)
{
    enum { OPT_THRESHOLD = 256, OPT_SIDE, OPT_SEGMENTS, OPT_LOD, OPT_MOUTH_CAP, OPT_JSON, OPT_SMOOTHING };
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'},      {"threshold", required_argument, NULL, OPT_THRESHOLD},
        {"side", required_argument, NULL, OPT_SIDE},   {"segments", required_argument, NULL, OPT_SEGMENTS},
        {"lod", required_argument, NULL, OPT_LOD},     {"mouth-cap", no_argument, NULL, OPT_MOUTH_CAP},
        {"json", no_argument, NULL, OPT_JSON},         {"smoothing", required_argument, NULL, OPT_SMOOTHING},
        {"help", no_argument, NULL, 'h'},              {NULL, 0, NULL, 0},
    };
    *o = (options){.recon = {.threshold = -1, .side = RECON_SIDE_AUTO}, .segments = 360, .smoothing_px = 1.0};
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":o:h", longopts, NULL)) != -1) {
        switch (c) {
        case 'o':
            o->out_dir = optarg;
            break;
        case OPT_THRESHOLD:
            if (parse_int(optarg, 0, 255, &o->recon.threshold) != 0)
                return cli_usage_error("reconstruct", "--threshold wants an integer 0..255, not '%s'", optarg);
            break;
        case OPT_SIDE:
            if (!strcmp(optarg, "left"))
                o->recon.side = RECON_SIDE_LEFT;
            else if (!strcmp(optarg, "right"))
                o->recon.side = RECON_SIDE_RIGHT;
            else if (!strcmp(optarg, "auto"))
                o->recon.side = RECON_SIDE_AUTO;
            else
                return cli_usage_error("reconstruct", "--side wants left, right or auto, not '%s'", optarg);
            break;
        case OPT_SEGMENTS:
            if (parse_int(optarg, 3, 100000, &o->segments) != 0)
                return cli_usage_error("reconstruct", "--segments wants an integer 3..100000, not '%s'", optarg);
            break;
        case OPT_LOD:
            if (parse_lods(optarg, o) != 0)
                return cli_usage_error("reconstruct", "--lod wants up to 8 comma-separated integers 3..100000, not '%s'", optarg);
            break;
        case OPT_MOUTH_CAP:
            o->mouth_cap = 1;
            break;
        case OPT_JSON:
            o->json = 1;
            break;
        case OPT_SMOOTHING: {
            char *end;
            o->smoothing_px = strtod(optarg, &end);
            if (end == optarg || *end || !(o->smoothing_px >= 0.01 && o->smoothing_px <= 100.0))
                return cli_usage_error("reconstruct", "--smoothing wants pixels between 0.01 and 100, not '%s'", optarg);
            break;
        }
        case 'h':
            usage(stdout);
            return 0;
        case ':':
            return cli_usage_error("reconstruct", "%s needs a value", argv[optind - 1]);
        default:
            return cli_usage_error("reconstruct", "unknown option '%s'", argv[optind - 1]);
        }
    }
    if (!o->out_dir || !*o->out_dir)
        return cli_usage_error("reconstruct", "%s", "no output folder (-o DIR)");
    if (optind >= argc)
        return cli_usage_error("reconstruct", "%s", "no photo given");
    return -1;
}

/* ------------------------------------------------------------------ folders */

/* Creates path and its missing parents; *created counts the folders made
 * (innermost last in made[]) so a run that produced nothing can remove them. */
static int make_dirs(const char *path, char made[][PATH_MAX], int max_made, int *created)
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
            if (*created < max_made)
                snprintf(made[(*created)++], PATH_MAX, "%s", buf);
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

/* Removes the files in a folder this run made, then the folder. */
static void remove_tree(const char *dir)
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
}

/* Moves the finished outputs from tmp to final: one rename when final does
 * not exist yet, else file by file (undone if one fails). */
static int publish(const char *tmp, const char *final, const char *const *files, int n_files)
{
    struct stat st;
    if (stat(final, &st) != 0)
        return rename(tmp, final);
    for (int i = 0; i < n_files; i++) {
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

/* The file name without folder and last extension ("photo" when that is empty). */
static void file_stem(const char *path, char *stem, size_t len)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    int n = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    if (n == 0)
        snprintf(stem, len, "photo");
    else
        snprintf(stem, len, "%.*s", n, base);
}

/* ------------------------------------------------------------------ one photo */

static double ms_since(double t0) { return 1e3 * (now_seconds() - t0); }

/* Copies the captured text to stderr, leaving out libpng's own lines. */
static void replay_captured(FILE *cap)
{
    char line[1024];
    rewind(cap);
    while (fgets(line, sizeof line, cap))
        if (strncmp(line, "libpng ", 7) != 0)
            fputs(line, stderr);
}

/* libpng (inside OpenImageIO) prints "libpng error: ..." on stderr for a
 * damaged PNG, on top of the error OpenImageIO returns; that would break the
 * one-line-per-bad-photo rule. So probing and decoding run with stderr
 * captured in a temporary file, replayed afterwards without libpng's lines.
 * Serialised: stderr is one per process. */
static int read_image_quietly(const char *path, image_t *img, int probe_only, int *w, int *h, char *err,
                              size_t errlen)
{
    int rc;
#pragma omp critical(celadon_stderr)
    {
        fflush(stderr);
        FILE *cap = tmpfile();
        int saved = cap ? dup(2) : -1;
        int captured = saved >= 0 && dup2(fileno(cap), 2) >= 0;
        int ch;
        rc = probe_only ? image_probe(path, w, h, &ch, err, errlen) : image_read(path, img, err, errlen);
        if (captured) {
            fflush(stderr);
            dup2(saved, 2);
            replay_captured(cap);
        }
        if (saved >= 0)
            close(saved);
        if (cap)
            fclose(cap);
    }
    return rc;
}

/* Problems with the file itself, before decoding: missing, a folder, empty,
 * not an image, too small or too large. */
static int check_file(const char *path, report *rep)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        snprintf(rep->error, sizeof rep->error, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (S_ISDIR(st.st_mode)) {
        snprintf(rep->error, sizeof rep->error, "is a folder, not a photo");
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(rep->error, sizeof rep->error, "not a regular file");
        return -1;
    }
    if (st.st_size == 0) {
        snprintf(rep->error, sizeof rep->error, "empty file");
        return -1;
    }
    if (access(path, R_OK) != 0) {
        snprintf(rep->error, sizeof rep->error, "cannot read: %s", strerror(errno));
        return -1;
    }
    int w, h;
    char err[400];
    if (read_image_quietly(path, NULL, 1, &w, &h, err, sizeof err) != 0) {
        snprintf(rep->error, sizeof rep->error, "not a readable image (%s)", err);
        return -1;
    }
    if (w < MIN_SIDE_PX || h < MIN_SIDE_PX) {
        snprintf(rep->error, sizeof rep->error, "image too small (%dx%d; at least %dx%d needed)", w, h, MIN_SIDE_PX,
                 MIN_SIDE_PX);
        return -1;
    }
    if ((double)w * h > MAX_MEGAPIXELS * 1e6) {
        snprintf(rep->error, sizeof rep->error, "image too large (%dx%d; at most %.0f megapixels)", w, h,
                 MAX_MEGAPIXELS);
        return -1;
    }
    return 0;
}

static int fail(report *rep, int code, const char *fmt, const char *what)
{
    rep->exit_code = code;
    snprintf(rep->error, sizeof rep->error, fmt, what);
    return -1;
}

/* The meshes: model.* at --segments, then model_N.* for each --lod. Adds the
 * written file names to files[]. */
static int write_meshes(const options *o, const bspline_t *curve, const double *u, int n_u, const char *tmp,
                        report *rep, const char **files, int *n_files, char names[][32])
{
    unsigned caps = MESH_CAP_BASE | (o->mouth_cap ? MESH_CAP_MOUTH : 0u);
    char path[PATH_MAX + 64], err[400];
    for (int k = -1; k < o->n_lods; k++) {
        int segments = k < 0 ? o->segments : o->lods[k];
        mesh_t m;
        double t0 = now_seconds();
        if (mesh_revolve(curve, u, n_u, 1.0, segments, caps, &m) != 0)
            return fail(rep, 1, "%s", "cannot build the mesh (out of memory?)");
        if (k < 0)
            rep->ms_mesh = ms_since(t0);
        mesh_stats *st = k < 0 ? &rep->mesh : &rep->lods[k];
        *st = (mesh_stats){segments, m.n_verts, m.n_tris};
        char stem[24];
        if (k < 0)
            snprintf(stem, sizeof stem, "model");
        else
            snprintf(stem, sizeof stem, "model_%d", segments);
        t0 = now_seconds();
        int rc = 0;
        for (int f = 0; f < 2 && rc == 0; f++) {
            char *name = names[*n_files];
            snprintf(name, 32, "%s.%s", stem, f ? "ply" : "obj");
            snprintf(path, sizeof path, "%s/%s", tmp, name);
            rc = f ? mesh_write_ply(path, &m, err, sizeof err) : mesh_write_obj(path, &m, "model.mtl", err, sizeof err);
            if (rc == 0) {
                /* A LOD equal to an earlier one writes the same names once. */
                int dup = 0;
                for (int i = 0; i < *n_files; i++)
                    dup |= !strcmp(files[i], name);
                if (!dup)
                    files[(*n_files)++] = name;
            }
        }
        rep->ms_write += ms_since(t0);
        mesh_free(&m);
        if (rc != 0)
            return fail(rep, 1, "cannot write the mesh: %s", err);
    }
    return 0;
}

static void fill_profile(profile_t *p, const char *photo, const recon_result *res, const bspline_t *curve,
                         double *domains, int n_domains, const report *rep)
{
    memset(p, 0, sizeof *p);
    snprintf(p->source_path, sizeof p->source_path, "%s", photo);
    p->source_width = rep->width;
    p->source_height = rep->height;
    p->axis_origin = res->axis_origin;
    p->axis_direction = res->axis_direction;
    p->tilt_deg = res->tilt_deg;
    memcpy(p->corners, res->corners, sizeof p->corners);
    snprintf(p->side, sizeof p->side, "%s", rep->side);
    p->n_polyline = res->n_polyline;
    p->polyline = res->polyline;
    p->curve = *curve;
    p->n_domains = n_domains;
    p->domains = domains;
    p->err_curve_to_polyline = rep->err_curve_to_polyline;
    p->err_polyline_to_curve = rep->err_polyline_to_curve;
    p->contour_points = rep->contour_points;
    p->ms_image_processing = rep->ms_image;
    p->ms_bspline = rep->ms_bspline + rep->ms_domains;
    p->ms_texture = rep->ms_texture;
    p->ms_mesh = rep->ms_mesh;
}

/* Runs the whole pipeline for one photo, writing into the empty folder tmp.
 * Returns 0, or -1 with rep->exit_code and rep->error set. */
static int run_pipeline(const options *o, const char *photo, const char *tmp, report *rep)
{
    double t_start = now_seconds();
    image_t img = {0};
    recon_result res = {0};
    bspline_t curve = {0};
    double *domains = NULL;
    int n_domains = 0;
    recon_texture_t tex = {0};
    uint8_t *overlay = NULL;
    char err[400], path[PATH_MAX + 64];
    const char *files[8 + 2 * MAX_LODS];
    char mesh_names[2 + 2 * MAX_LODS][32];
    int n_files = 0, status = -1;

    if (check_file(photo, rep) != 0) {
        rep->exit_code = 2;
        return -1;
    }
    double t0 = now_seconds();
    if (read_image_quietly(photo, &img, 0, NULL, NULL, err, sizeof err) != 0) {
        fail(rep, 2, "cannot decode the image (%s)", err);
        goto done;
    }
    rep->ms_decode = ms_since(t0);
    rep->width = img.width;
    rep->height = img.height;

    recon_status rs = recon_extract(&img, &o->recon, &res, err, sizeof err);
    if (rs != RECON_OK) {
        fail(rep, rs == RECON_ERR_INTERNAL ? 1 : 2, "%s", err);
        goto done;
    }
    rep->ms_image = res.ms_image_processing;
    rep->tilt_deg = res.tilt_deg;
    rep->side = res.side_used == RECON_SIDE_LEFT ? "left" : "right";
    rep->threshold_used = res.threshold_used;
    rep->dropped_objects = res.dropped_objects;
    rep->holes_filled = res.holes_filled;
    rep->contour_points = res.n_contour;
    rep->approx_points = res.n_approx;
    rep->polyline_points = res.n_polyline;

    t0 = now_seconds();
    bspline_fit_info info;
    if (bspline_fit_profile(res.polyline, res.n_polyline, o->smoothing_px, &curve, &info) != 0) {
        fail(rep, 2, "%s", "the profile is too short or degenerate to fit a curve");
        goto done;
    }
    rep->ms_bspline = ms_since(t0);
    rep->control_points = curve.n_ctrl;
    t0 = now_seconds();
    if (curve_domains_by_curvature_variation(&curve, DOMAIN_TOL_PX, DOMAIN_TOL_NORMAL_DEG, &domains, &n_domains) != 0) {
        fail(rep, 1, "%s", "cannot split the curve into domains");
        goto done;
    }
    rep->ms_domains = ms_since(t0);
    rep->domains = n_domains;
    t0 = now_seconds();
    curve_polyline_hausdorff(&curve, res.polyline, res.n_polyline, &rep->err_curve_to_polyline,
                             &rep->err_polyline_to_curve);
    rep->ms_hausdorff = ms_since(t0);

    t0 = now_seconds();
    if (recon_texture_from_photo(&img, &res, &tex, err, sizeof err) != 0) {
        fail(rep, 2, "%s", err);
        goto done;
    }
    rep->ms_texture = ms_since(t0);

    t0 = now_seconds();
    snprintf(path, sizeof path, "%s/texture.png", tmp);
    if (image_write_u8(path, tex.width, tex.height, 3, tex.rgb, err, sizeof err) != 0) {
        fail(rep, 1, "cannot write texture.png: %s", err);
        goto done;
    }
    files[n_files++] = "texture.png";
    snprintf(path, sizeof path, "%s/model.mtl", tmp);
    if (mesh_write_mtl(path, "texture.png", err, sizeof err) != 0) {
        fail(rep, 1, "cannot write model.mtl: %s", err);
        goto done;
    }
    files[n_files++] = "model.mtl";
    rep->ms_write = ms_since(t0);
    if (write_meshes(o, &curve, domains, n_domains, tmp, rep, files, &n_files, mesh_names) != 0)
        goto done;
    t0 = now_seconds();
    overlay = overlay_render(&img, &res, &curve);
    if (!overlay) {
        fail(rep, 1, "%s", "out of memory drawing the overlay");
        goto done;
    }
    rep->ms_overlay = ms_since(t0);
    t0 = now_seconds();
    snprintf(path, sizeof path, "%s/overlay.png", tmp);
    if (image_write_u8(path, img.width, img.height, 3, overlay, err, sizeof err) != 0) {
        fail(rep, 1, "cannot write overlay.png: %s", err);
        goto done;
    }
    files[n_files++] = "overlay.png";
    profile_t prof;
    fill_profile(&prof, photo, &res, &curve, domains, n_domains, rep);
    snprintf(path, sizeof path, "%s/profile.json", tmp);
    if (profile_write_json(path, &prof, err, sizeof err) != 0) {
        fail(rep, 1, "cannot write profile.json: %s", err);
        goto done;
    }
    files[n_files++] = "profile.json";
    rep->ms_write += ms_since(t0);
    if (publish(tmp, rep->out, files, n_files) != 0) {
        snprintf(rep->error, sizeof rep->error, "cannot move the outputs into %.512s: %s", rep->out, strerror(errno));
        rep->exit_code = 1;
        goto done;
    }
    rep->ms_total = ms_since(t_start);
    status = 0;
done:
    free(overlay);
    recon_texture_free(&tex);
    free(domains);
    bspline_free(&curve);
    recon_result_free(&res);
    image_free(&img);
    return status;
}

/* One photo: a fresh temporary folder inside DIR, the pipeline, and on
 * failure nothing left behind. */
static void reconstruct_photo(const options *o, int index, report *rep)
{
    char tmp[PATH_MAX];
    snprintf(tmp, sizeof tmp, "%s/.celadon-tmp-%ld-%d", o->out_dir, (long)getpid(), index);
    if (mkdir(tmp, 0777) != 0) {
        rep->exit_code = 1;
        snprintf(rep->error, sizeof rep->error, "cannot create a folder in %.512s: %s", o->out_dir, strerror(errno));
        return;
    }
    if (run_pipeline(o, rep->photo, tmp, rep) != 0)
        remove_tree(tmp);
}

static void print_summary(const report *r)
{
    fprintf(stderr,
            "%s -> %s/\n"
            "  axis tilt %.2f deg, profile from the %s side, threshold %d, %d other object%s dropped\n"
            "  %d contour points -> %d control points, %d domains; Hausdorff curve->polyline %.2f px, "
            "polyline->curve %.2f px\n"
            "  mesh %d vertices, %d faces (%d segments)\n"
            "  %.1f ms: decode %.1f, image processing %.1f, B-spline %.1f, domains %.1f, errors %.1f, texture %.1f, "
            "mesh %.1f, overlay %.1f, writing %.1f\n",
            r->photo, r->out, r->tilt_deg, r->side, r->threshold_used, r->dropped_objects,
            r->dropped_objects == 1 ? "" : "s", r->contour_points, r->control_points, r->domains,
            r->err_curve_to_polyline, r->err_polyline_to_curve, r->mesh.vertices, r->mesh.faces, r->mesh.segments,
            r->ms_total, r->ms_decode, r->ms_image, r->ms_bspline, r->ms_domains, r->ms_hausdorff, r->ms_texture,
            r->ms_mesh, r->ms_overlay, r->ms_write);
}

static json_t *mesh_json(const mesh_stats *m)
{
    return json_pack("{s:i, s:i, s:i}", "segments", m->segments, "vertices", m->vertices, "faces", m->faces);
}

/* The report of one photo: the paper's Table 1 columns (timings per stage,
 * contour points, control points, domains, vertices, faces, errors). */
static json_t *report_json(const options *o, const report *r)
{
    if (r->exit_code != 0)
        return json_pack("{s:s, s:b, s:i, s:s}", "photo", r->photo, "ok", 0, "exit_code", r->exit_code, "error",
                         r->error);
    json_t *lods = json_array();
    for (int k = 0; k < o->n_lods; k++)
        json_array_append_new(lods, mesh_json(&r->lods[k]));
    json_t *timings = json_pack(
        "{s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f}", "decode", r->ms_decode, "image_processing", r->ms_image,
        "bspline", r->ms_bspline, "domains", r->ms_domains, "hausdorff", r->ms_hausdorff, "texture", r->ms_texture,
        "mesh", r->ms_mesh, "overlay", r->ms_overlay, "write", r->ms_write, "total", r->ms_total);
    json_t *errors = json_pack("{s:f, s:f}", "curve_to_polyline", r->err_curve_to_polyline, "polyline_to_curve",
                               r->err_polyline_to_curve);
    return json_pack("{s:s, s:b, s:s, s:i, s:i, s:f, s:s, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, "
                     "s:o, s:o, s:o}",
                     "photo", r->photo, "ok", 1, "output", r->out, "width", r->width, "height", r->height,
                     "tilt_deg", r->tilt_deg, "side", r->side, "threshold", r->threshold_used, "dropped_objects",
                     r->dropped_objects, "holes_filled", r->holes_filled, "contour_points", r->contour_points, "approx_points", r->approx_points,
                     "polyline_points", r->polyline_points, "control_points", r->control_points, "domains",
                     r->domains, "segments", r->mesh.segments, "vertices", r->mesh.vertices, "faces", r->mesh.faces,
                     "error_px", errors, "timings_ms", timings, "lods", lods);
}

/* Output folders: DIR itself for one photo; DIR/STEM for several, with
 * repeated stems made unique by -2, -3, ... in the order given. */
static int assign_outputs(const options *o, report *reps, int n)
{
    for (int i = 0; i < n; i++) {
        if (n == 1) {
            snprintf(reps[i].out, sizeof reps[i].out, "%s", o->out_dir);
            continue;
        }
        char stem[256], name[300];
        file_stem(reps[i].photo, stem, sizeof stem);
        snprintf(name, sizeof name, "%s", stem);
        for (int k = 2;; k++) {
            int taken = 0;
            for (int j = 0; j < i && !taken; j++) {
                const char *other = strrchr(reps[j].out, '/');
                taken = !strcmp(other + 1, name);
            }
            if (!taken)
                break;
            snprintf(name, sizeof name, "%s-%d", stem, k);
        }
        if (snprintf(reps[i].out, sizeof reps[i].out, "%s/%s", o->out_dir, name) >= (int)sizeof reps[i].out)
            return -1;
    }
    return 0;
}

int cmd_reconstruct(int argc, char **argv)
{
    options o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    int n = argc - optind;
    report *reps = calloc((size_t)n, sizeof *reps);
    if (!reps) {
        fprintf(stderr, "celadon: out of memory\n");
        return 1;
    }
    for (int i = 0; i < n; i++)
        reps[i].photo = argv[optind + i];
    char made[16][PATH_MAX];
    int n_made = 0;
    if (strlen(o.out_dir) >= PATH_MAX - 300 || assign_outputs(&o, reps, n) != 0) {
        fprintf(stderr, "celadon: %s: output folder name too long\n", o.out_dir);
        free(reps);
        return 2;
    }
    if (make_dirs(o.out_dir, made, 16, &n_made) != 0) {
        fprintf(stderr, "celadon: %s: cannot create the output folder: %s\n", o.out_dir, strerror(errno));
        free(reps);
        return 2;
    }

    /* One photo per thread; nested regions inside the stages stay serial. */
    omp_set_max_active_levels(1);
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
    for (int i = 0; i < n; i++)
        reconstruct_photo(&o, i, &reps[i]);

    int worst = 0, n_ok = 0;
    json_t *all = o.json ? json_array() : NULL;
    for (int i = 0; i < n; i++) {
        const report *r = &reps[i];
        if (r->exit_code == 0) {
            n_ok++;
            print_summary(r);
        } else {
            fprintf(stderr, "celadon: %s: %s\n", r->photo, r->error);
            /* Internal failures (1) outrank bad input (2) in the exit status. */
            if (worst != 1)
                worst = r->exit_code;
        }
        if (all)
            json_array_append_new(all, report_json(&o, r));
    }
    if (all) {
        json_t *out = n == 1 ? json_incref(json_array_get(all, 0)) : json_incref(all);
        json_dumpf(out, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(6));
        fputc('\n', stdout);
        json_decref(out);
        json_decref(all);
    }
    if (n_ok == 0)
        for (int k = n_made - 1; k >= 0; k--)
            rmdir(made[k]);
    else
        fprintf(stderr, "celadon: %d of %d photo%s reconstructed into %s/\n", n_ok, n, n == 1 ? "" : "s", o.out_dir);
    free(reps);
    return worst;
}
