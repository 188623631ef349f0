/* Helpers of the renderer tests: a temporary folder holding a profile.json
 * of one of the test vessels and a scene file, and renders of it to memory. */
#ifndef CELADON_TEST_RENDER_UTIL_H
#define CELADON_TEST_RENDER_UTIL_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/profile.h"
#include "celadon/render.h"
#include "support/sor_profiles.h"

typedef struct {
    char dir[64];
} render_fixture;

static inline void render_fixture_open(render_fixture *f)
{
    snprintf(f->dir, sizeof f->dir, "/tmp/celadon-test-render-XXXXXX");
    cr_assert_not_null(mkdtemp(f->dir));
}

static inline void render_fixture_close(render_fixture *f)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", f->dir);
    cr_assert_eq(system(cmd), 0);
}

/* Writes dir/name as profile.json of test profile `which` ("plum", ...),
 * with nd uniform domain boundaries (the rings a revolved mesh keeps). */
static inline void render_write_profile_domains(const render_fixture *f, const char *name, const char *which, int nd)
{
    int idx = -1;
    for (int i = 0; i < sor_test_profile_count(); i++)
        if (!strcmp(sor_test_profile_name(i), which))
            idx = i;
    cr_assert_geq(idx, 0);
    profile_t p;
    memset(&p, 0, sizeof p);
    snprintf(p.source_path, sizeof p.source_path, "synthetic");
    p.axis_direction = v2(0, -1);
    snprintf(p.side, sizeof p.side, "right");
    sor_test_profile(idx, &p.curve);
    vec2 poly[2] = {bspline_eval(&p.curve, 0.0), bspline_eval(&p.curve, 1.0)};
    p.polyline = poly;
    p.n_polyline = 2;
    double *dom = malloc(sizeof *dom * (size_t)nd);
    cr_assert_not_null(dom);
    for (int i = 0; i < nd; i++)
        dom[i] = (double)i / (nd - 1);
    p.domains = dom;
    p.n_domains = nd;
    char path[256], err[256];
    snprintf(path, sizeof path, "%s/%s", f->dir, name);
    cr_assert_eq(profile_write_json(path, &p, err, sizeof err), 0, "%s", err);
    bspline_free(&p.curve);
    free(dom);
}

/* The same with 201 domain boundaries: a straight wall's rings are exact. */
static inline void render_write_profile(const render_fixture *f, const char *name, const char *which)
{
    render_write_profile_domains(f, name, which, 201);
}

/* Writes text to dir/name; returns the path in out. */
static inline void render_write_file(const render_fixture *f, const char *name, const char *text, char *out,
                                     size_t outlen)
{
    snprintf(out, outlen, "%s/%s", f->dir, name);
    FILE *fp = fopen(out, "w");
    cr_assert_not_null(fp);
    fputs(text, fp);
    fclose(fp);
}

/* Builds (asserting it builds) the scene of body (shapes, emitters) with a
 * 4x4 perspective sensor and the default integrator and sampler, written
 * to dir/scene.xml. */
static inline scene_t *render_scene_of(const render_fixture *f, const char *body)
{
    char xml[16384], path[256], err[512];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\">\n"
             "  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/>"
             "<integer name=\"height\" value=\"4\"/></film></sensor>\n"
             "  %s\n"
             "</scene>\n",
             body);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    return s;
}

/* Writes len bytes to dir/name; returns the path in out. */
static inline void render_write_bytes(const render_fixture *f, const char *name, const void *bytes, size_t len,
                                      char *out, size_t outlen)
{
    snprintf(out, outlen, "%s/%s", f->dir, name);
    FILE *fp = fopen(out, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(bytes, 1, len, fp), len);
    fclose(fp);
}

/* The whole file (malloc'd) and its size, or NULL. */
static inline char *render_read_file(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    rewind(fp);
    char *b = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (b && fread(b, 1, (size_t)n, fp) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(fp);
    if (b)
        b[n] = '\0', *len = (size_t)n;
    return b;
}

/* The usual fixture: a new folder with profile.json of test profile `which`
 * (render_write_profile) and scene.xml holding xml; its path in scene. */
static inline void render_fixture_with_scene(render_fixture *f, const char *which, const char *xml, char *scene,
                                             size_t scenelen)
{
    render_fixture_open(f);
    render_write_profile(f, "profile.json", which);
    render_write_file(f, "scene.xml", xml, scene, scenelen);
}

/* Loads and renders a scene file with the options bo to averaged float
 * pixels (nchannels per pixel, malloc'd). */
static inline float *render_to_pixels_with(const char *scene_path, const scene_options *bo, int threads,
                                           unsigned aovs, int *w, int *h, int *nch)
{
    char err[1024];
    scene_t *s = scene_create_from_file(scene_path, NULL, 0, bo, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    render_options ro = {.threads = threads, .aovs = aovs};
    film_t film;
    cr_assert_eq(render_scene(s, &ro, &film, NULL, err, sizeof err), 0, "%s", err);
    *w = film.width, *h = film.height, *nch = film.nchannels;
    float *px = malloc(sizeof *px * (size_t)film.width * film.height * film.nchannels);
    cr_assert_not_null(px);
    film_develop(&film, px);
    film_free(&film);
    scene_destroy(s);
    return px;
}

/* The RGB of a scene file rendered with seed on 2 threads, 3 floats a pixel
 * (malloc'd), its size in *w, *h. */
static inline float *render_to_rgb(const char *scene_path, long long seed, int *w, int *h)
{
    scene_options bo = scene_options_default();
    bo.seed = seed;
    int nch;
    float *px = render_to_pixels_with(scene_path, &bo, 2, 0, w, h, &nch);
    float *rgb = malloc(sizeof *rgb * 3 * (size_t)(*w * *h));
    cr_assert_not_null(rgb);
    for (int i = 0; i < *w * *h; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = px[i * nch + c];
    free(px);
    return rgb;
}

/* The same with the SORs meshed into mesh_segments (0: analytic) and seed. */
static inline float *render_to_pixels(const char *scene_path, int mesh_segments, long long seed, int threads,
                                      unsigned aovs, int *w, int *h, int *nch)
{
    scene_options bo = scene_options_default();
    bo.mesh_segments = mesh_segments;
    bo.seed = seed;
    return render_to_pixels_with(scene_path, &bo, threads, aovs, w, h, nch);
}

#endif
