/* celadon reconstruct: photographs of vessels to profiles, textures, meshes
 * and diagnostic overlays. Photos of one call are processed in parallel (one
 * per thread, each single-threaded); every photo's outputs are written into a
 * temporary folder and moved into place only when all of them are complete. */
#include <errno.h>
#include <getopt.h>
#include <jansson.h>
#include <limits.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/reconstruct.h"
#include "cli/cli_args.h"
#include "cli/commands.h"
#include "core/core.h"
#include "prior/prior.h"

typedef struct {
    const char *out_dir;
    reconstruct_options pipeline;
    int json;
} options;

typedef struct {
    const char *photo;
    char out[PATH_MAX];
    int exit_code; /* 0 ok, 1 internal failure, 2 bad input */
    char error[1024];
    int width, height;
    double tilt_deg;
    const char *side;
    int threshold_used, dropped_objects, holes_filled, excluded;
    int used_prior;
    int contour_points, polyline_points, control_points, domains;
    reconstruct_mesh_stats mesh, lods[RECONSTRUCT_MAX_LODS];
    double err_curve_to_polyline, err_polyline_to_curve;
    reconstruct_quality quality;
    const char *model;      /* "perspective" or "orthographic" */
    const char *method;     /* how the focal length was found; "none" without a camera */
    double elevation_deg, focal_px;
    char camera_note[256];  /* why orthographic, or empty */
    reconstruct_timings ms;
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
            "  --segmenter classic|learned|auto  the mask by the classical segmentation alone,\n"
            "                       with the learned object prior (a network, `make deps-model`),\n"
            "                       or the prior only where the classical result is refused\n"
            "                       (default auto)\n"
            "  --segments N         angular segments of model.obj/.ply (default 360)\n"
            "  --lod N,N,...        also write model_N.obj and model_N.ply for each N\n"
            "  --mouth-cap          close the mouth with a disc (the base is always closed)\n"
            "  --smoothing PX       largest distance of a profile point from the fitted\n"
            "                       B-spline, pixels (default 1)\n"
            "  --fov DEG            the camera's horizontal field of view over the photo's width\n"
            "                       (default: the EXIF focal length, else found from the imaged\n"
            "                       base and rim ellipses)\n"
            "  --force              write the outputs even when the result fails the quality gate\n"
            "                       (a warning line; profile.json records \"quality\": {\"passed\": false})\n"
            "  --json               print the report as JSON on stdout (an array for several photos)\n"
            "  -h, --help           this text\n\n"
            "exit status: 0 all photos done, 2 bad input or usage (the other photos are still\n"
            "done), 1 internal failure\n");
}

/* ------------------------------------------------------------------ options */

/* Returns -1 to continue, otherwise the exit code. */
static int parse_options(int argc, char **argv, options *o)
{
    /* Options of the pipeline itself carry OPT_PIPELINE and are set by name
     * (reconstruct_option_set, which the Python package shares). */
    enum { OPT_PIPELINE = 256, OPT_JSON };
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'},
        {"threshold", required_argument, NULL, OPT_PIPELINE},
        {"side", required_argument, NULL, OPT_PIPELINE},
        {"segmenter", required_argument, NULL, OPT_PIPELINE},
        {"segments", required_argument, NULL, OPT_PIPELINE},
        {"lod", required_argument, NULL, OPT_PIPELINE},
        {"smoothing", required_argument, NULL, OPT_PIPELINE},
        {"fov", required_argument, NULL, OPT_PIPELINE},
        {"force", no_argument, NULL, OPT_PIPELINE},
        {"mouth-cap", no_argument, NULL, OPT_PIPELINE},
        {"json", no_argument, NULL, OPT_JSON},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    *o = (options){.pipeline = reconstruct_options_default()};
    opterr = 0;
    optind = 1;
    int c, which;
    while ((c = getopt_long(argc, argv, ":o:h", longopts, &which)) != -1) {
        switch (c) {
        case 'o':
            o->out_dir = optarg;
            break;
        case OPT_PIPELINE: {
            char err[256];
            const struct option *opt = &longopts[which];
            if (reconstruct_option_set(&o->pipeline, opt->name, opt->has_arg ? optarg : "1", err, sizeof err) != 0)
                return cli_usage_error("reconstruct", "--%s", err);
            break;
        }
        case OPT_JSON:
            o->json = 1;
            break;
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

/* Which camera model the profile came from. */
static void camera_report(const reconstruction *r, report *rep)
{
    static const char *const methods[] = {"ellipses", "exif", "flag", "orthographic"};
    rep->model = reconstruction_is_perspective(r) ? "perspective" : "orthographic";
    rep->method = r->has_camera ? methods[r->camera.method] : "none";
    rep->elevation_deg = r->has_camera ? r->camera.elevation_deg : 0;
    rep->focal_px = r->has_camera ? r->camera.focal_px : 0;
    snprintf(rep->camera_note, sizeof rep->camera_note, "%s", r->has_camera ? r->camera.note : r->camera_note);
}

/* The library pipeline, then the outputs into rep->out; the run's figures
 * are kept in the report (the arrays are released). */
static void reconstruct_one(const options *o, report *rep)
{
    reconstruction r;
    int code = reconstruct_photo(rep->photo, &o->pipeline, &r, rep->error, sizeof rep->error);
    if (code == 0)
        code = reconstruct_write(&r, rep->photo, rep->out, &o->pipeline, rep->error, sizeof rep->error);
    rep->exit_code = code;
    if (code == 0) {
        const recon_result *x = &r.extract;
        rep->width = r.photo.width;
        rep->height = r.photo.height;
        rep->tilt_deg = x->tilt_deg;
        rep->side = x->side_used == RECON_SIDE_LEFT ? "left" : "right";
        rep->threshold_used = x->threshold_used;
        rep->dropped_objects = x->dropped_objects;
        rep->holes_filled = x->holes_filled;
        rep->excluded = x->n_excluded;
        rep->used_prior = r.used_prior;
        rep->quality = r.quality;
        rep->contour_points = x->n_contour;
        rep->polyline_points = x->n_polyline;
        rep->control_points = r.curve.n_ctrl;
        rep->domains = r.n_domains;
        rep->err_curve_to_polyline = r.err_curve_to_polyline;
        rep->err_polyline_to_curve = r.err_polyline_to_curve;
        camera_report(&r, rep);
        rep->mesh = r.mesh;
        memcpy(rep->lods, r.lods, sizeof rep->lods);
        rep->ms = r.ms;
    }
    reconstruction_free(&r);
}

static void print_summary(const report *r)
{
    fprintf(stderr,
            "%s -> %s/\n"
            "  axis tilt %.2f deg, profile from the %s side, %d part%s excluded, %d other object%s dropped\n"
            "  %d contour points -> %d control points, %d domains; Hausdorff curve->polyline %.2f px, "
            "polyline->curve %.2f px\n"
            "  mesh %d vertices, %d faces (%d segments)\n"
            "  %.1f ms: decode %.1f, image processing %.1f, B-spline %.1f, domains %.1f, errors %.1f, camera %.1f, "
            "texture %.1f, mesh %.1f, overlay %.1f, writing %.1f\n",
            r->photo, r->out, r->tilt_deg, r->side, r->excluded, r->excluded == 1 ? "" : "s", r->dropped_objects,
            r->dropped_objects == 1 ? "" : "s", r->contour_points, r->control_points, r->domains,
            r->err_curve_to_polyline, r->err_polyline_to_curve, r->mesh.vertices, r->mesh.faces, r->mesh.segments,
            r->ms.total, r->ms.decode, r->ms.image, r->ms.bspline, r->ms.domains, r->ms.hausdorff, r->ms.camera,
            r->ms.texture, r->ms.mesh, r->ms.overlay, r->ms.write);
    if (!strcmp(r->model, "perspective"))
        fprintf(stderr, "  camera: perspective, elevation %.2f deg, focal length %.0f px (from the %s); the profile "
                        "is the meridian\n",
                r->elevation_deg, r->focal_px,
                !strcmp(r->method, "flag") ? "--fov" : !strcmp(r->method, "exif") ? "EXIF" : "ellipses");
    else if (r->elevation_deg > 0)
        /* Parallel rays pitched by e (b/a = sin e): the meridian is solved
         * from the outline under that view, as for a perspective camera. */
        fprintf(stderr, "  camera: orthographic, seen from %.1f deg above (the ellipses' aspect); the profile is the "
                        "meridian under that view: %s\n",
                r->elevation_deg, r->camera_note);
    else
        fprintf(stderr, "  camera: orthographic, the profile is the image outline: %s\n", r->camera_note);
    if (!r->quality.passed)
        fprintf(stderr, "celadon: warning: %s: written with --force although the quality gate failed: %s\n", r->photo,
                r->quality.failed);
}

static json_t *mesh_json(const reconstruct_mesh_stats *m)
{
    return json_pack("{s:i, s:i, s:i}", "segments", m->segments, "vertices", m->vertices, "faces", m->faces);
}

/* The report of one photo: the paper's Table 1 columns (timings per stage,
 * contour points, control points, domains, vertices, faces, errors). */
static json_t *report_json(const options *o, const report *r)
{
    /* File names are any bytes; JSON text is UTF-8 (json_text). */
    char photo[4 * 4096], out[4 * 4096], error[4 * 2048];
    if (r->exit_code != 0)
        return json_pack("{s:s, s:b, s:i, s:s}", "photo", json_text(r->photo, photo, sizeof photo), "ok", 0,
                         "exit_code", r->exit_code, "error", json_text(r->error, error, sizeof error));
    json_t *lods = json_array();
    for (int k = 0; k < o->pipeline.n_lods; k++)
        json_array_append_new(lods, mesh_json(&r->lods[k]));
    json_t *timings = json_pack(
        "{s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f}", "decode", r->ms.decode, "object_prior",
        r->ms.prior, "image_processing", r->ms.image,
        "bspline", r->ms.bspline, "domains", r->ms.domains, "hausdorff", r->ms.hausdorff, "camera", r->ms.camera, "texture", r->ms.texture,
        "mesh", r->ms.mesh, "overlay", r->ms.overlay, "write", r->ms.write, "total", r->ms.total);
    json_t *errors = json_pack("{s:f, s:f}", "curve_to_polyline", r->err_curve_to_polyline, "polyline_to_curve",
                               r->err_polyline_to_curve);
    json_t *camera = json_pack("{s:s, s:s, s:f, s:f, s:s}", "model", r->model, "method", r->method,
                               "elevation_deg", r->elevation_deg, "focal_px", r->focal_px, "note", r->camera_note);
    json_t *quality = json_pack("{s:b, s:f, s:f, s:f, s:i, s:s}", "passed", r->quality.passed, "hausdorff_px",
                                r->quality.hausdorff_px, "lr_disagreement", r->quality.lr_disagreement,
                                "excluded_fraction", r->quality.excluded_fraction, "border_contact",
                                (int)r->quality.border_contact, "failed", r->quality.failed);
    return json_pack("{s:s, s:b, s:s, s:s, s:i, s:i, s:f, s:s, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, s:i, "
                     "s:o, s:o, s:o, s:o, s:o}",
                     "photo", json_text(r->photo, photo, sizeof photo), "ok", 1, "segmenter",
                     r->used_prior ? "learned" : "classic", "output",
                     json_text(r->out, out, sizeof out), "width", r->width, "height", r->height,
                     "tilt_deg", r->tilt_deg, "side", r->side, "threshold", r->threshold_used, "dropped_objects",
                     r->dropped_objects, "holes_filled", r->holes_filled, "excluded_parts", r->excluded,
                     "contour_points", r->contour_points, "polyline_points", r->polyline_points, "control_points",
                     r->control_points, "domains", r->domains, "segments", r->mesh.segments, "vertices",
                     r->mesh.vertices, "faces", r->mesh.faces, "error_px", errors, "quality", quality, "camera", camera,
                     "timings_ms", timings, "lods", lods);
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
    if (cli_check_output(o.out_dir, 1) != 0) {
        free(reps);
        return CLI_CANNOT_WRITE;
    }
    if (folder_make(o.out_dir, made, 16, &n_made) != 0) {
        fprintf(stderr, "celadon: %s: cannot create the output folder: %s\n", o.out_dir, strerror(errno));
        free(reps);
        return CLI_CANNOT_WRITE;
    }

    char model[4096];
    if (o.pipeline.segmenter != RECONSTRUCT_SEGMENTER_CLASSIC && !object_prior_available() &&
        object_prior_model_path(model, sizeof model) == 0)
        fprintf(stderr, "celadon: the learned object prior is off: no network at %s (`make deps-model` obtains it); "
                        "the classical segmentation decides alone\n", model);

    /* One photo per thread; nested regions inside the stages stay serial. */
    omp_set_max_active_levels(1);
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
    for (int i = 0; i < n; i++)
        reconstruct_one(&o, &reps[i]);

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
