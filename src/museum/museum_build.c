/* museum_build: photos -> reconstructions (the library pipeline, in
 * parallel) -> layout -> museum.glb, museum.xml, the page, preview.png,
 * museum.json, published together. See include/celadon/museum.h. */
#include "core/core.h"
#include "celadon/museum.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/reconstruct.h"
#include "museum/catalogue.h"
#include "museum/exhibit.h"
#include "museum/jpeg_memory.h"
#include "museum/label.h"
#include "museum/layout.h"
#include "museum/museum_folder.h"
#include "museum/museum_gltf.h"
#include "museum/museum_light.h"
#include "museum/museum_preview.h"
#include "museum/museum_scene.h"
#include "museum/slug.h"

enum { LABEL_WIDTH_PX = 768, MUSEUM_TEXTURE_JPEG_QUALITY = 85 };
#define SIGN_PX_PER_M 1000.0 /* the title sign's image: 55 px capitals */
#define VISITOR_RADIUS 0.25 /* m: how close a visitor's eye gets to a case wall */

museum_options museum_options_default(void)
{
    return (museum_options){.preview_width = 640, .preview_height = 360, .preview_spp = 16,
                            .bake_spp = MUSEUM_DEFAULT_BAKE_SPP};
}

/* The files written into the temporary folder, for the manifest. */
typedef struct {
    json_t *files;
    char tmp[PATH_MAX];
} build_ctx;

static double ms_since(double t0) { return 1e3 * (now_seconds() - t0); }

static void file_stem(const char *path, char *stem, size_t len)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    int n = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(stem, len, "%.*s", n, base);
}

static char *dup_or_null(const char *s) { return s ? strdup(s) : NULL; }

/* Titles, sizes and slugs from the catalogue (or the defaults). */
static int describe(const char *const *photos, int n, const catalogue_t *cat, museum_exhibit *ex,
                    const char **slugs)
{
    for (int i = 0; i < n; i++) {
        const catalogue_entry *c = catalogue_find(cat, photos[i]);
        char stem[256];
        file_stem(photos[i], stem, sizeof stem);
        ex[i].photo = photos[i];
        ex[i].title = strdup(c && c->title ? c->title : stem[0] ? stem : "Vessel");
        ex[i].date = dup_or_null(c ? c->date : NULL);
        ex[i].description = dup_or_null(c ? c->description : NULL);
        ex[i].height_cm_given = c ? c->height_cm : 0.0;
        ex[i].diameter_cm_given = c ? c->diameter_cm : 0.0;
        if (!ex[i].title)
            return -1;
        slugs[i] = ex[i].slug;
        slug_make(ex[i].title, slugs, i, ex[i].slug, sizeof ex[i].slug);
    }
    return 0;
}

static uint8_t *read_bytes(const char *path, size_t *len)
{
    char *buf, why[256];
    return input_read_all(path, INPUT_MAX_DATA_BYTES, &buf, len, why, sizeof why) == 0 ? (uint8_t *)buf : NULL;
}

static int write_bytes(const char *path, const uint8_t *data, size_t len)
{
    atomic_file af;
    if (atomic_file_open(&af, path) != 0)
        return -1;
    if (fwrite(data, 1, len, af.fp) != len) {
        atomic_file_abort(&af);
        return -1;
    }
    return atomic_file_commit(&af);
}

/* One photo: the pipeline, its profile.json and texture.png in
 * vessels/SLUG/, the levels of detail. */
static void make_exhibit(const museum_options *opt, const char *tmp, museum_exhibit *e, museum_photo_report *rep)
{
    reconstruction r;
    reconstruct_options ro = reconstruct_options_default();
    ro.force = opt->force;
    rep->status = reconstruct_photo(e->photo, &ro, &r, rep->error, sizeof rep->error);
    if (rep->status == 0 && !r.quality.passed) {
        e->below_gate = rep->below_gate = 1;
        snprintf(rep->error, sizeof rep->error, "below the quality gate (%s), included with --force", r.quality.failed);
    }
    char dir[PATH_MAX + 128], path[PATH_MAX + 160], why[400];
    snprintf(dir, sizeof dir, "vessels/%s", e->slug);
    profile_t prof;
    const double *domains;
    int n_domains;
    if (rep->status == 0)
        reconstruction_profile(&r, e->photo, &prof);
    /* The vessel's shape: the meridian when the camera gave one. */
    if (rep->status == 0 && (museum_folder_sub(tmp, dir) != 0 ||
                             bspline_copy(&e->curve, profile_shape(&prof, &domains, &n_domains)) != 0)) {
        rep->status = 1;
        snprintf(rep->error, sizeof rep->error, "cannot create %.200s: %s", dir, strerror(errno));
    }
    if (rep->status == 0) {
        snprintf(path, sizeof path, "%s/%s/profile.json", tmp, dir);
        int rc = profile_write_json(path, &prof, why, sizeof why);
        snprintf(path, sizeof path, "%s/%s/texture.png", tmp, dir);
        rc = rc ? rc : image_write_u8(path, r.texture.width, r.texture.height, 3, r.texture.rgb, why, sizeof why);
        if (rc == 0 && jpeg_encode_rgb(r.texture.rgb, r.texture.width, r.texture.height, MUSEUM_TEXTURE_JPEG_QUALITY,
                                       &e->texture_jpg, &e->texture_len) != 0)
            rc = -1, snprintf(why, sizeof why, "cannot encode its JPEG");
        if (rc != 0) {
            rep->status = 1;
            snprintf(rep->error, sizeof rep->error, "cannot write the vessel's files: %s", why);
        }
    }
    reconstruction_free(&r);
    snprintf(path, sizeof path, "%s/%s", tmp, dir);
    if (rep->status != 0) {
        museum_folder_remove(path); /* a refused photo leaves nothing */
        return;
    }
    /* The curve's own largest radius: every level's vertices lie on the
     * curve's revolution and its chords inside, so nothing of the vessel is
     * wider (the control polygon's bound was up to 2.2 times wider on
     * real-dev reconstructions, and widened the room with it). */
    double top = bspline_largest(&e->curve, 1), widest = bspline_largest(&e->curve, 0);
    double rim = bspline_eval(&e->curve, 1.0).y;
    e->height_m = vessel_size_height_m(e->height_cm_given, e->diameter_cm_given, top, widest, &e->size_source);
    e->rim_height_m = e->height_m * rim / top;
    e->radius_m = widest * e->height_m / top;
    layout_vessel lv = {e->height_m, e->radius_m};
    double nearest = e->radius_m + layout_clearance(&lv) + VISITOR_RADIUS;
    e->n_lods = lod_make(&e->curve, e->rim_height_m, opt->lods, opt->n_lods, nearest, e->lods);
    if (e->n_lods < 1) {
        e->n_lods = 0;
        rep->status = 1;
        snprintf(rep->error, sizeof rep->error, "cannot build the vessel's meshes");
        museum_folder_remove(path);
    }
}

static int add_file(build_ctx *b, const char *fmt, const char *arg)
{
    char name[PATH_MAX];
    snprintf(name, sizeof name, fmt, arg);
    return json_array_append_new(b->files, json_string(name));
}

static int write_labels(build_ctx *b, const layout_t *l, museum_exhibit *ex, int n, char *err, size_t errlen)
{
    if (museum_folder_sub(b->tmp, "labels") != 0) {
        snprintf(err, errlen, "cannot create the labels folder: %s", strerror(errno));
        return -1;
    }
    for (int i = 0; i < n; i++) {
        const layout_exhibit *le = &l->exhibits[i];
        char size[128];
        vessel_size_line(ex[i].height_cm_given, ex[i].diameter_cm_given, size, sizeof size);
        label_text t = {ex[i].title, ex[i].date, size, ex[i].below_gate ? MUSEUM_BELOW_GATE_NOTE : NULL,
                        ex[i].description};
        int h = (int)lround(LABEL_WIDTH_PX * le->label_height / le->label_width);
        char path[PATH_MAX + 160];
        snprintf(path, sizeof path, "%s/labels/%s.png", b->tmp, ex[i].slug);
        if (label_render_png(&t, LABEL_WIDTH_PX, h, &ex[i].label_png, &ex[i].label_len) != 0 ||
            write_bytes(path, ex[i].label_png, ex[i].label_len) != 0) {
            snprintf(err, errlen, "cannot draw or write the label of %s", ex[i].photo);
            return -1;
        }
        add_file(b, "labels/%s.png", ex[i].slug);
        if (le->sign_lines > 0) {
            int sw = (int)lround(SIGN_PX_PER_M * le->sign_width), sh = (int)lround(SIGN_PX_PER_M * le->sign_height);
            snprintf(path, sizeof path, "%s/labels/%s-sign.png", b->tmp, ex[i].slug);
            if (label_sign_png(ex[i].title, sw, sh, SIGN_PX_PER_M * LAYOUT_SIGN_CAP, &ex[i].sign_png,
                               &ex[i].sign_len) != 0 ||
                write_bytes(path, ex[i].sign_png, ex[i].sign_len) != 0) {
                snprintf(err, errlen, "cannot draw or write the title sign of %s", ex[i].photo);
                return -1;
            }
            add_file(b, "labels/%s-sign.png", ex[i].slug);
        }
        add_file(b, "vessels/%s/profile.json", ex[i].slug);
        add_file(b, "vessels/%s/texture.png", ex[i].slug);
    }
    return 0;
}

/* index.html and museum.js from the web folder; 1 when they are not there. */
static int copy_page(build_ctx *b, const char *web_dir, char *err, size_t errlen)
{
    static const char *const names[] = {"index.html", "museum.js"};
    for (int k = 0; k < 2; k++) {
        char from[PATH_MAX + 32], to[PATH_MAX + 32];
        snprintf(from, sizeof from, "%s/%s", web_dir ? web_dir : "", names[k]);
        size_t len;
        uint8_t *data = web_dir ? read_bytes(from, &len) : NULL;
        if (!data)
            return 1;
        snprintf(to, sizeof to, "%s/%s", b->tmp, names[k]);
        int rc = write_bytes(to, data, len);
        free(data);
        if (rc != 0) {
            snprintf(err, errlen, "cannot write %s: %s", names[k], strerror(errno));
            return -1;
        }
        add_file(b, "%s", names[k]);
    }
    return 0;
}

static json_t *manifest(const build_ctx *b, const char *title, const museum_exhibit *ex, int n,
                        const museum_report *rep)
{
    json_t *vessels = json_array();
    for (int i = 0; i < n; i++) {
        json_t *lods = json_array();
        for (int k = 0; k < ex[i].n_lods; k++)
            json_array_append_new(lods, json_pack("{s:i, s:f, s:f, s:i}", "segments", ex[i].lods[k].segments,
                                                  "distance_m", ex[i].lods[k].distance, "error_m",
                                                  ex[i].lods[k].error, "triangles", ex[i].lods[k].mesh.n_tris));
        char title[4 * 512], photo[4 * 4096];
        json_array_append_new(vessels, json_pack("{s:s, s:s, s:s, s:f, s:s, s:f, s:b, s:o}", "title",
                                                 json_text(ex[i].title, title, sizeof title), "photo",
                                                 json_text(ex[i].photo, photo, sizeof photo), "folder", ex[i].slug,
                                                 "height_cm", 100.0 * ex[i].height_m, "size_from",
                                                 vessel_size_source_name(ex[i].size_source), "radius_cm",
                                                 100.0 * ex[i].radius_m, "quality_gate_passed", !ex[i].below_gate,
                                                 "lods", lods));
    }
    json_t *figures = json_pack("{s:I, s:I, s:I, s:i, s:I, s:[f,f,f]}", "triangles_full",
                                (json_int_t)rep->triangles_full, "triangles_entrance",
                                (json_int_t)rep->triangles_entrance, "triangles_coarsest",
                                (json_int_t)rep->triangles_coarsest, "draw_calls", rep->draw_calls, "glb_bytes",
                                (json_int_t)rep->glb_bytes, "room_m", rep->room[0], rep->room[1], rep->room[2]);
    return json_pack("{s:{s:i, s:s}, s:O, s:o, s:o}", "celadon_museum", "version", 1, "title", title, "files",
                     b->files, "vessels", vessels, "figures", figures);
}

/* The room's light from museum.xml's path tracer (museum_light.h): the
 * probes written as files, the lightmaps kept for museum.glb. The vessel-free
 * scene the probes see is a temporary file of the folder. */
static int bake_light(build_ctx *b, const museum_options *opt, const char *title, const layout_t *l,
                      const museum_exhibit *ex, int n, museum_light *light, museum_report *rep, char *err,
                      size_t errlen)
{
    double t0 = now_seconds();
    char scene[PATH_MAX + 32], room[PATH_MAX + 32], path[PATH_MAX + 160];
    snprintf(scene, sizeof scene, "%s/museum.xml", b->tmp);
    snprintf(room, sizeof room, "%s/bake-room.xml", b->tmp);
    int rc = museum_scene_write(room, title, l, ex, n, 0, 16, 16, 1, err, errlen);
    rc = rc ? rc : museum_light_bake(scene, room, l, ex, opt->bake_spp > 0 ? opt->bake_spp : 1, light, err, errlen);
    remove(room);
    if (rc != 0)
        return -1;
    snprintf(path, sizeof path, "%s/probe.hdr", b->tmp);
    rc = write_bytes(path, light->room_probe.bytes, light->room_probe.len);
    add_file(b, "%s", "probe.hdr");
    for (int i = 0; i < n && rc == 0; i++) {
        snprintf(path, sizeof path, "%s/vessels/%s/probe.hdr", b->tmp, ex[i].slug);
        rc = write_bytes(path, light->probe[i].bytes, light->probe[i].len);
        add_file(b, "vessels/%s/probe.hdr", ex[i].slug);
    }
    if (rc != 0) {
        snprintf(err, errlen, "cannot write the light probes: %s", strerror(errno));
        museum_light_free(light);
        return -1;
    }
    rep->ms_bake = ms_since(t0);
    return 0;
}

/* Everything after the reconstructions, into b->tmp. */
static int write_museum(build_ctx *b, const museum_options *opt, museum_exhibit *ex, int n, museum_report *rep,
                        char *err, size_t errlen)
{
    const char *title = opt->title ? opt->title : "Celadon museum";
    layout_vessel *lv = malloc((size_t)n * sizeof *lv);
    layout_t layout;
    if (!lv)
        return -1;
    for (int i = 0; i < n; i++)
        lv[i] = (layout_vessel){ex[i].height_m, ex[i].radius_m};
    int rc = layout_make(lv, n, &layout);
    free(lv);
    if (rc != 0) {
        snprintf(err, errlen, "cannot lay out the museum (out of memory?)");
        return -1;
    }
    rep->room[0] = layout.width, rep->room[1] = layout.depth, rep->room[2] = layout.height;
    char path[PATH_MAX + 32];
    rc = write_labels(b, &layout, ex, n, err, errlen);
    snprintf(path, sizeof path, "%s/museum.xml", b->tmp);
    rc = rc ? rc
            : museum_scene_write(path, title, &layout, ex, n, 1, opt->preview_width, opt->preview_height,
                                 opt->preview_spp > 0 ? opt->preview_spp : 16, err, errlen);
    museum_light light;
    rc = rc ? rc : bake_light(b, opt, title, &layout, ex, n, &light, rep, err, errlen);
    if (rc == 0) {
        char glb[PATH_MAX + 32];
        snprintf(glb, sizeof glb, "%s/museum.glb", b->tmp);
        rc = museum_gltf_write(glb, title, &layout, ex, n, &light, rep, err, errlen);
        museum_light_free(&light);
    }
    layout_free(&layout);
    if (rc != 0)
        return -1;
    add_file(b, "%s", "museum.glb");
    add_file(b, "%s", "museum.xml");
    int page = copy_page(b, opt->web_dir, err, errlen);
    if (page < 0)
        return -1;
    rep->web_missing = page;
    if (opt->preview_spp > 0) {
        double t0 = now_seconds();
        char png[PATH_MAX + 32];
        snprintf(png, sizeof png, "%s/preview.png", b->tmp);
        if (museum_preview_render(path, png, opt->progress, err, errlen) != 0)
            return -1;
        add_file(b, "%s", "preview.png");
        rep->ms_preview = ms_since(t0);
    }
    add_file(b, "%s", MUSEUM_MANIFEST);
    json_t *m = manifest(b, title, ex, n, rep);
    snprintf(path, sizeof path, "%s/%s", b->tmp, MUSEUM_MANIFEST);
    rc = m ? json_write_file_atomic(path, m, JSON_INDENT(2) | JSON_REAL_PRECISION(6), err, errlen) : -1;
    json_decref(m);
    return rc;
}

/* The photos: those given, or the catalogue's. */
static const char **photo_list(const char *const *photos, int *n, const catalogue_t *cat)
{
    int count = *n > 0 ? *n : cat->n;
    const char **list = calloc((size_t)(count > 0 ? count : 1), sizeof *list);
    for (int i = 0; list && i < count; i++)
        list[i] = *n > 0 ? photos[i] : cat->entries[i].path;
    *n = count;
    return list;
}

/* Reconstructs every photo (one per thread) and keeps those that made it
 * at the front of ex; returns their number. */
static int reconstruct_all(const museum_options *opt, const char *tmp, museum_exhibit *ex, museum_report *rep)
{
    int n = rep->n_photos;
    omp_set_max_active_levels(1);
#pragma omp parallel for schedule(dynamic, 1) if (n > 1)
    for (int i = 0; i < n; i++)
        make_exhibit(opt, tmp, &ex[i], &rep->photos[i]);
    int kept = 0;
    for (int i = 0; i < n; i++) {
        if (rep->photos[i].status == 0)
            ex[kept++] = ex[i];
        else
            museum_exhibit_free(&ex[i]);
    }
    return kept;
}

static int build(const char *const *photos, int n, const museum_options *opt, const catalogue_t *cat,
                 museum_report *rep, char *err, size_t errlen)
{
    const char **list = photo_list(photos, &n, cat);
    museum_exhibit *ex = calloc((size_t)(n > 0 ? n : 1), sizeof *ex);
    rep->photos = calloc((size_t)(n > 0 ? n : 1), sizeof *rep->photos);
    const char **slugs = calloc((size_t)(n > 0 ? n : 1), sizeof *slugs);
    build_ctx b = {.files = json_array()};
    int rc = 1;
    if (!list || !ex || !slugs || !rep->photos || !b.files || describe(list, n, cat, ex, slugs) != 0) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    rep->n_photos = n;
    for (int i = 0; i < n; i++)
        snprintf(rep->photos[i].photo, sizeof rep->photos[i].photo, "%s", list[i]);
    if (n == 0) {
        snprintf(err, errlen, "%s: the catalogue lists no photo", opt->catalogue);
        rc = 2;
        goto done;
    }
    if (museum_folder_begin(opt->out_dir, b.tmp, sizeof b.tmp, err, errlen) != 0)
        goto done;
    double t0 = now_seconds();
    rep->n_vessels = reconstruct_all(opt, b.tmp, ex, rep);
    rep->ms_reconstruct = ms_since(t0);
    int worst = 0; /* internal failures (1) outrank bad input (2) */
    for (int i = 0; i < n; i++)
        worst = rep->photos[i].status == 1 || worst == 1 ? 1 : worst ? worst : rep->photos[i].status;
    if (rep->n_vessels == 0) {
        snprintf(err, errlen, "%s: no photo could be reconstructed, no museum written", opt->out_dir);
        rc = worst;
    } else {
        t0 = now_seconds();
        int ok = write_museum(&b, opt, ex, rep->n_vessels, rep, err, errlen) == 0 &&
                 museum_folder_publish(b.tmp, opt->out_dir, err, errlen) == 0;
        rep->ms_write = ms_since(t0) - rep->ms_preview;
        rc = ok ? worst : 1;
    }
    if (rep->n_vessels == 0 || rc == 1)
        museum_folder_remove(b.tmp);
done:
    for (int i = 0; i < rep->n_vessels; i++)
        museum_exhibit_free(&ex[i]);
    free(ex);
    free(slugs);
    free(list);
    json_decref(b.files);
    return rc;
}

int museum_build(const char *const *photos, int n, const museum_options *opt, museum_report *rep, char *err,
                 size_t errlen)
{
    double t0 = now_seconds();
    memset(rep, 0, sizeof *rep);
    catalogue_t cat = {0};
    if (opt->catalogue && catalogue_read(opt->catalogue, &cat, err, errlen) != 0)
        return 2;
    int rc = museum_folder_check(opt->out_dir, err, errlen) != 0 ? 2 : build(photos, n, opt, &cat, rep, err, errlen);
    catalogue_free(&cat);
    rep->ms_total = ms_since(t0);
    return rc;
}

void museum_report_free(museum_report *rep)
{
    free(rep->photos);
    memset(rep, 0, sizeof *rep);
}
