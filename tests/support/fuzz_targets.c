#include "fuzz_targets.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/mesh.h"
#include "celadon/profile.h"
#include "celadon/reconstruct.h"
#include "celadon/render.h"
#include "celadon/scene.h"
#include "celadon/sor.h"
#include "museum/catalogue.h"

static char scratch[PATH_MAX];

static void remove_scratch(void)
{
    char cmd[PATH_MAX + 16];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch);
    if (system(cmd) != 0)
        fprintf(stderr, "fuzz: cannot remove %s\n", scratch);
}

static void touch(const char *name)
{
    char path[PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/%s", scratch, name);
    FILE *f = fopen(path, "wb");
    if (f)
        fclose(f);
}

/* The process's scratch folder, made at the first call. */
static const char *scratch_dir(void)
{
    if (!scratch[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(scratch, sizeof scratch, "%s/celadon-fuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(scratch)) {
            perror("fuzz: mkdtemp");
            abort();
        }
        atexit(remove_scratch);
        touch("photo.png");
        touch("b.jpg");
    }
    return scratch;
}

/* Writes the input to scratch/name; its path in path. */
static void write_input(const char *name, const uint8_t *data, size_t size, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", scratch_dir(), name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) {
        perror("fuzz: cannot write the input");
        abort();
    }
}

/* Rays from a circle around the object toward points of its axis. */
static void trace_fan(const sor_t *s)
{
    vec3 lo, hi;
    sor_bounds(s, &lo, &hi);
    double size = fmax(hi.y - lo.y, hi.x - lo.x);
    for (int i = 0; i < 64; i++) {
        double phi = 0.7 * i, h = lo.y + (hi.y - lo.y) * ((i % 9) / 8.0);
        vec3 o = v3(3.0 * size * cos(phi), lo.y + (hi.y - lo.y) * ((i % 5) / 4.0) + 0.3 * size, 3.0 * size * sin(phi));
        ray3 r = {o, v3_norm(v3_sub(v3(0.0, h, 0.0), o))};
        sor_hit hit;
        sor_intersect(s, &r, 0.0, INFINITY, &hit);
        sor_occluded(s, &r, 0.0, INFINITY);
    }
}

int fuzz_profile(const uint8_t *data, size_t size)
{
    char path[PATH_MAX + 64], err[1024];
    write_input("profile.json", data, size, path, sizeof path);
    profile_t p;
    if (profile_read_json(path, &p, err, sizeof err) != 0)
        return 1;
    mesh_t m;
    if (mesh_revolve(&p.curve, p.domains, p.n_domains, 1.0, 16, MESH_CAP_BASE | MESH_CAP_MOUTH, &m) == 0)
        mesh_free(&m);
    sor_t *s = sor_create(&p.curve, 1.0, SOR_CAPS_ALL, err, sizeof err);
    if (s) {
        trace_fan(s);
        sor_destroy(s);
    }
    profile_free(&p);
    return s ? 0 : 1;
}

/* Builds and renders a scene from its text, anchored at anchor (the file
 * its relative names are found from): 0 when both were accepted. */
static int build_and_render(const char *text, size_t len, const char *anchor)
{
    char err[2048];
    scene_desc *d = scene_desc_create_from_text(text, len, anchor, NULL, 0, scene_plugin_find, err, sizeof err);
    if (!d)
        return 1;
    scene_options o = scene_options_default();
    o.width = 8, o.height = 6, o.spp = 1;
    scene_t *s = scene_create(d, &o, err, sizeof err);
    scene_desc_destroy(d);
    if (!s)
        return 1;
    render_options ro = {.threads = 1};
    film_t film;
    render_stats st;
    int rc = render_scene(s, &ro, &film, &st, err, sizeof err);
    if (rc == 0)
        film_free(&film);
    scene_destroy(s);
    return rc == 0 ? 0 : 1;
}

int fuzz_scene(const uint8_t *data, size_t size)
{
    static char anchor[PATH_MAX + 32];
    if (!anchor[0]) {
        char dir[PATH_MAX];
        if (!realpath("scenes/showcase", dir)) {
            fprintf(stderr, "fuzz: run from the repository's top folder (scenes/showcase/ is missing)\n");
            abort();
        }
        snprintf(anchor, sizeof anchor, "%s/fuzzed.xml", dir);
    }
    return build_and_render((const char *)data, size, anchor);
}

int fuzz_serialized(const uint8_t *data, size_t size)
{
    char path[PATH_MAX + 64], anchor[PATH_MAX + 64], xml[2 * PATH_MAX + 512];
    write_input("mesh.serialized", data, size, path, sizeof path);
    snprintf(anchor, sizeof anchor, "%s/fuzzed.xml", scratch_dir());
    int rc = 1;
    for (int index = 0; index < 2; index++) {
        /* a camera that sees the fan of support/serialized_file.h's meshes */
        int n = snprintf(xml, sizeof xml,
                         "<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
                         "<lookat origin=\"2.5, 14, 60\" target=\"2.5, 14, 0\" up=\"0, 1, 0\"/></transform></sensor>"
                         "<shape type=\"serialized\"><string name=\"filename\" value=\"%s\"/>"
                         "<integer name=\"shape_index\" value=\"%d\"/><emitter type=\"area\"/></shape></scene>",
                         path, index);
        if (build_and_render(xml, (size_t)n, anchor) == 0)
            rc = 0;
    }
    return rc;
}

int fuzz_image(const uint8_t *data, size_t size)
{
    char path[PATH_MAX + 64], err[1024];
    write_input("photo", data, size, path, sizeof path);
    reconstruct_options opt = reconstruct_options_default();
    reconstruction r;
    int rc = reconstruct_photo(path, &opt, &r, err, sizeof err);
    reconstruction_free(&r);
    return rc == 0 ? 0 : 1;
}

int fuzz_catalogue(const uint8_t *data, size_t size)
{
    char path[PATH_MAX + 64], err[1024];
    snprintf(path, sizeof path, "%s/catalogue.csv", scratch_dir());
    catalogue_t cat;
    if (catalogue_parse(path, (const char *)data, size, &cat, err, sizeof err) != 0)
        return 1;
    snprintf(path, sizeof path, "%s/photo.png", scratch_dir());
    catalogue_find(&cat, path);
    catalogue_free(&cat);
    return 0;
}

const fuzz_target fuzz_target_table[] = {
    {"profile", fuzz_profile},
    {"scene", fuzz_scene},
    {"image", fuzz_image},
    {"serialized", fuzz_serialized},
    {"catalogue", fuzz_catalogue},
    {NULL, NULL},
};
