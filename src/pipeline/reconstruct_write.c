/* reconstruct_write: a reconstruction's files, published all together.
 * See include/celadon/reconstruct.h. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/mesh.h"
#include "celadon/overlay.h"
#include "core/core.h"
#include "celadon/reconstruct.h"

enum { MAX_FILES = 5 + 2 * (1 + RECONSTRUCT_MAX_LODS) };
/* Imaged cross-sections the overlay draws over a perspective photo. */
enum { OVERLAY_CROSS_SECTIONS = 5 };

/* The names of the files written so far into the temporary folder. */
typedef struct {
    char names[MAX_FILES][32];
    const char *list[MAX_FILES];
    int n;
} file_list;

static void add_file(file_list *f, const char *name)
{
    for (int i = 0; i < f->n; i++) /* a LOD equal to an earlier one writes the same names once */
        if (!strcmp(f->list[i], name))
            return;
    snprintf(f->names[f->n], sizeof f->names[f->n], "%s", name);
    f->list[f->n] = f->names[f->n];
    f->n++;
}

static double ms_since(double t0) { return 1e3 * (now_seconds() - t0); }

/* model.* at opt->segments, then model_N.* for each LOD, revolved from the
 * profile's shape (profile_shape: the meridian when there is a camera). */
static int write_meshes(reconstruction *r, const char *source, const reconstruct_options *opt, const char *tmp,
                        file_list *files, char *err, size_t errlen)
{
    unsigned caps = MESH_CAP_BASE | (opt->mouth_cap ? MESH_CAP_MOUTH : 0u);
    char path[PATH_MAX + 64], why[400];
    profile_t prof;
    reconstruction_profile(r, source, &prof);
    const double *domains;
    int n_domains;
    const bspline_t *shape = profile_shape(&prof, &domains, &n_domains);
    for (int k = -1; k < opt->n_lods; k++) {
        int segments = k < 0 ? opt->segments : opt->lods[k];
        mesh_t m;
        double t0 = now_seconds();
        if (mesh_revolve(shape, domains, n_domains, 1.0, segments, caps, &m) != 0) {
            snprintf(err, errlen, "cannot build the mesh (out of memory?)");
            return 1;
        }
        if (k < 0)
            r->ms.mesh = ms_since(t0);
        *(k < 0 ? &r->mesh : &r->lods[k]) = (reconstruct_mesh_stats){segments, m.n_verts, m.n_tris};
        char stem[24], name[32];
        snprintf(stem, sizeof stem, k < 0 ? "model" : "model_%d", segments);
        t0 = now_seconds();
        int rc = 0;
        for (int f = 0; f < 2 && rc == 0; f++) {
            snprintf(name, sizeof name, "%s.%s", stem, f ? "ply" : "obj");
            snprintf(path, sizeof path, "%s/%s", tmp, name);
            rc = f ? mesh_write_ply(path, &m, why, sizeof why) : mesh_write_obj(path, &m, "model.mtl", why, sizeof why);
            if (rc == 0)
                add_file(files, name);
        }
        r->ms.write += ms_since(t0);
        mesh_free(&m);
        if (rc != 0) {
            snprintf(err, errlen, "cannot write the mesh: %s", why);
            return 1;
        }
    }
    return 0;
}

/* tmp/name from 8-bit pixels, listed in files; 0, or 1 with err. */
static int write_png(const char *tmp, const char *name, int width, int height, int channels, const uint8_t *pixels,
                     file_list *files, char *err, size_t errlen)
{
    char path[PATH_MAX + 64], why[400];
    snprintf(path, sizeof path, "%s/%s", tmp, name);
    if (image_write_u8(path, width, height, channels, pixels, why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", name, why);
        return 1;
    }
    add_file(files, name);
    return 0;
}

/* Every output into the empty folder tmp. */
static int write_all(reconstruction *r, const char *source, const char *tmp, const reconstruct_options *opt,
                     file_list *files, char *err, size_t errlen)
{
    char path[PATH_MAX + 64], why[400];
    double t0 = now_seconds();
    if (write_png(tmp, "texture.png", r->texture.width, r->texture.height, 3, r->texture.rgb, files, err, errlen))
        return 1;
    if (r->texture.seen) { /* taken by the camera: which texels it saw (255) and which it did not (0) */
        size_t n = (size_t)r->texture.width * r->texture.height;
        uint8_t *mask = malloc(n ? n : 1);
        if (!mask) {
            snprintf(err, errlen, "cannot write texture_seen.png: out of memory");
            return 1;
        }
        for (size_t i = 0; i < n; i++)
            mask[i] = r->texture.seen[i] ? 255 : 0;
        int rc = write_png(tmp, "texture_seen.png", r->texture.width, r->texture.height, 1, mask, files, err, errlen);
        free(mask);
        if (rc != 0)
            return 1;
    }
    snprintf(path, sizeof path, "%s/model.mtl", tmp);
    if (mesh_write_mtl(path, "texture.png", why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot write model.mtl: %s", why);
        return 1;
    }
    add_file(files, "model.mtl");
    r->ms.write += ms_since(t0);
    if (write_meshes(r, source, opt, tmp, files, err, errlen) != 0)
        return 1;

    t0 = now_seconds();
    uint8_t *overlay = overlay_render(&r->photo, &r->extract, &r->curve);
    if (overlay && reconstruction_is_perspective(r) &&
        overlay_draw_camera(overlay, r->photo.width, r->photo.height, &r->camera, &r->meridian,
                            OVERLAY_CROSS_SECTIONS) != 0) {
        free(overlay);
        overlay = NULL;
    }
    if (!overlay) {
        snprintf(err, errlen, "out of memory drawing the overlay");
        return 1;
    }
    r->ms.overlay = ms_since(t0);
    t0 = now_seconds();
    int rc = write_png(tmp, "overlay.png", r->photo.width, r->photo.height, 3, overlay, files, err, errlen);
    free(overlay);
    if (rc != 0)
        return 1;
    profile_t prof;
    reconstruction_profile(r, source, &prof);
    snprintf(path, sizeof path, "%s/profile.json", tmp);
    if (profile_write_json(path, &prof, why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot write profile.json: %s", why);
        return 1;
    }
    add_file(files, "profile.json");
    r->ms.write += ms_since(t0);
    return 0;
}

int reconstruct_write(reconstruction *r, const char *source, const char *dir, const reconstruct_options *opt,
                      char *err, size_t errlen)
{
    double t_start = now_seconds();
    char tmp[PATH_MAX];
    if (folder_make_temp(dir, tmp, sizeof tmp) != 0) {
        snprintf(err, errlen, "cannot create a folder for %.512s: %s", dir, strerror(errno));
        return 1;
    }
    file_list files = {.n = 0};
    int rc = write_all(r, source, tmp, opt, &files, err, errlen);
    if (rc == 0 && folder_publish(tmp, dir, files.list, files.n) != 0) {
        snprintf(err, errlen, "cannot move the outputs into %.512s: %s", dir, strerror(errno));
        rc = 1;
    }
    if (rc != 0)
        folder_remove(tmp);
    r->ms.total += ms_since(t_start);
    return rc;
}
