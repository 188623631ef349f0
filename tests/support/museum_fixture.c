#include "museum_fixture.h"

#include <criterion/criterion.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/image.h"
#include "synth_vessel.h"

static const char *const titles[] = {"Vase with a flared mouth", "Wide bowl", "Bottle, \"narrow neck\"", "Jar"};
static const double heights_cm[] = {32.0, 14.0, 28.0, 22.0};

void museum_fixture_photos(const char *dir, int n, char paths[][512])
{
    char csv[512], err[256];
    snprintf(csv, sizeof csv, "%s/catalogue.csv", dir);
    FILE *f = fopen(csv, "w");
    cr_assert_not_null(f);
    fprintf(f, "file,title,height_cm,description\n");
    for (int k = 0; k < n; k++) {
        synth_params p = synth_defaults((synth_shape)(k % SYNTH_SHAPE_COUNT), 240, 320);
        p.textured = 1;
        p.subrows = 4;
        p.fg2[0] = 0.8f, p.fg2[1] = 0.75f, p.fg2[2] = 0.3f;
        image_t img;
        cr_assert_eq(synth_draw(&p, &img), 0);
        snprintf(paths[k], 512, "%s/vessel-%d.png", dir, k);
        cr_assert_eq(synth_write(paths[k], &img, 8, err, sizeof err), 0, "%s", err);
        image_free(&img);
        /* Titles are quoted as CSV wants: inner quotes doubled. */
        fprintf(f, "vessel-%d.png,\"", k);
        for (const char *c = titles[k % 4]; *c; c++)
            fprintf(f, *c == '"' ? "\"\"" : "%c", *c);
        fprintf(f, "\",%.1f,Drawn for the tests: a known profile.\n", heights_cm[k % 4]);
    }
    fclose(f);
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

void museum_fixture_remove_tree(const char *path)
{
    if (path[0])
        nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

cli_result museum_fixture_run(const char *dir, const char *const *args)
{
    /* One sample per texel of the baked light: the tests check the bake's
     * plumbing and mean, not its noise (tests/test_museum_bake.c checks its values). */
    const char *argv[64] = {"museum", "--bake-spp", "1"};
    int n = 3;
    for (; args[n - 3] && n < 63; n++)
        argv[n] = args[n - 3];
    argv[n] = NULL;
    return cli_run(dir, argv);
}

static uint32_t u32(const uint8_t *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

void glb_read(const char *path, glb_file *g)
{
    memset(g, 0, sizeof *g);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    g->file = malloc((size_t)n);
    cr_assert(g->file && fread(g->file, 1, (size_t)n, f) == (size_t)n);
    fclose(f);
    cr_assert_geq(n, 28, "too short for a GLB");
    cr_assert_eq(u32(g->file), 0x46546C67u, "magic glTF");
    cr_assert_eq(u32(g->file + 4), 2u, "version 2");
    cr_assert_eq(u32(g->file + 8), (uint32_t)n, "header length = file length");
    uint32_t json_len = u32(g->file + 12);
    cr_assert_eq(u32(g->file + 16), 0x4E4F534Au, "first chunk JSON");
    cr_assert_eq(json_len % 4, 0u);
    json_error_t je;
    g->doc = json_loadb((const char *)g->file + 20, json_len, 0, &je);
    cr_assert_not_null(g->doc, "JSON chunk: %s", je.text);
    size_t off = 20 + json_len;
    if (off < (size_t)n) {
        cr_assert_eq(u32(g->file + off + 4), 0x004E4942u, "second chunk BIN");
        g->bin_len = u32(g->file + off);
        g->bin = g->file + off + 8;
        cr_assert_eq(off + 8 + g->bin_len, (size_t)n, "BIN chunk ends the file");
    }
}

void glb_close(glb_file *g)
{
    json_decref(g->doc);
    free(g->file);
    memset(g, 0, sizeof *g);
}

const float *glb_floats(const glb_file *g, int accessor, int *count)
{
    json_t *a = json_array_get(json_object_get(g->doc, "accessors"), (size_t)accessor);
    cr_assert_not_null(a);
    cr_assert_eq(json_integer_value(json_object_get(a, "componentType")), 5126);
    json_t *v = json_array_get(json_object_get(g->doc, "bufferViews"),
                               (size_t)json_integer_value(json_object_get(a, "bufferView")));
    size_t off = (size_t)json_integer_value(json_object_get(v, "byteOffset"));
    size_t len = (size_t)json_integer_value(json_object_get(v, "byteLength"));
    cr_assert_leq(off + len, g->bin_len);
    cr_assert_eq(off % 4, 0u);
    *count = (int)json_integer_value(json_object_get(a, "count"));
    return (const float *)(const void *)(g->bin + off);
}

double *glb_positions(const glb_file *g, int accessor, int node, int *count, double *step)
{
    json_t *a = json_array_get(json_object_get(g->doc, "accessors"), (size_t)accessor);
    cr_assert_not_null(a);
    int type = (int)json_integer_value(json_object_get(a, "componentType"));
    if (type == 5126) {
        const float *f = glb_floats(g, accessor, count);
        double *p = malloc((size_t)*count * 3 * sizeof *p);
        for (int i = 0; i < 3 * *count; i++)
            p[i] = f[i];
        *step = 0;
        return p;
    }
    cr_assert_eq(type, 5122, "positions are floats or 16-bit integers");
    cr_assert(!json_is_true(json_object_get(a, "normalized")));
    json_t *v = json_array_get(json_object_get(g->doc, "bufferViews"),
                               (size_t)json_integer_value(json_object_get(a, "bufferView")));
    size_t off = (size_t)json_integer_value(json_object_get(v, "byteOffset"));
    size_t stride = (size_t)json_integer_value(json_object_get(v, "byteStride"));
    *count = (int)json_integer_value(json_object_get(a, "count"));
    cr_assert_geq(stride, 6u);
    cr_assert_leq(off + (size_t)*count * stride, g->bin_len);
    json_t *n = json_array_get(json_object_get(g->doc, "nodes"), (size_t)node);
    json_t *t = json_object_get(n, "translation"), *s = json_object_get(n, "scale");
    double scale = json_number_value(json_array_get(s, 0));
    cr_assert(scale > 0 && json_number_value(json_array_get(s, 1)) == scale &&
                  json_number_value(json_array_get(s, 2)) == scale,
              "a uniform dequantization scale");
    double *p = malloc((size_t)*count * 3 * sizeof *p);
    for (int i = 0; i < *count; i++)
        for (int k = 0; k < 3; k++) {
            int16_t q;
            memcpy(&q, g->bin + off + (size_t)i * stride + 2 * (size_t)k, 2);
            p[3 * i + k] = json_number_value(json_array_get(t, (size_t)k)) + scale * q;
        }
    *step = scale;
    return p;
}

/* The parent of node (the node whose children list it), or -1. */
static int parent_of(const glb_file *g, int node)
{
    json_t *nodes = json_object_get(g->doc, "nodes");
    for (size_t i = 0; i < json_array_size(nodes); i++) {
        json_t *ch = json_object_get(json_array_get(nodes, i), "children");
        for (size_t k = 0; k < json_array_size(ch); k++)
            if (json_integer_value(json_array_get(ch, k)) == node)
                return (int)i;
    }
    return -1;
}

static vec3 translation(json_t *node)
{
    json_t *t = json_object_get(node, "translation");
    return t ? v3(json_number_value(json_array_get(t, 0)), json_number_value(json_array_get(t, 1)),
                  json_number_value(json_array_get(t, 2)))
             : v3(0, 0, 0);
}

vec3 glb_node_world_translation(const glb_file *g, int node)
{
    json_t *nodes = json_object_get(g->doc, "nodes");
    vec3 p = v3(0, 0, 0);
    for (int k = node; k >= 0; k = parent_of(g, k))
        p = v3_add(p, translation(json_array_get(nodes, (size_t)k)));
    return p;
}

/* Rotates v by the unit quaternion q = (x, y, z, w). */
static vec3 rotate(const double q[4], vec3 v)
{
    vec3 u = v3(q[0], q[1], q[2]);
    vec3 t = v3_scale(v3_cross(u, v), 2.0);
    return v3_add(v3_add(v, v3_scale(t, q[3])), v3_cross(u, t));
}

int glb_project(const glb_file *g, vec3 p, int width, int height, double *px, double *py)
{
    json_t *nodes = json_object_get(g->doc, "nodes"), *n = NULL;
    size_t i;
    json_array_foreach(nodes, i, n)
        if (json_object_get(n, "camera"))
            break;
    cr_assert_not_null(n, "no camera node");
    json_t *cam = json_array_get(json_object_get(g->doc, "cameras"),
                                 (size_t)json_integer_value(json_object_get(n, "camera")));
    double yfov = json_number_value(json_object_get(json_object_get(cam, "perspective"), "yfov"));
    json_t *r = json_object_get(n, "rotation");
    double q[4] = {-json_number_value(json_array_get(r, 0)), -json_number_value(json_array_get(r, 1)),
                   -json_number_value(json_array_get(r, 2)), json_number_value(json_array_get(r, 3))};
    vec3 local = rotate(q, v3_sub(p, glb_node_world_translation(g, (int)i))); /* the inverse rotation */
    if (local.z >= 0)
        return -1;
    double t = tan(yfov / 2), aspect = (double)width / height;
    *px = (local.x / -local.z / (t * aspect) + 1) / 2 * width;
    *py = (1 - local.y / -local.z / t) / 2 * height;
    return 0;
}

int glb_exhibits(const glb_file *g, int *exhibit, int *vessel, int max)
{
    json_t *nodes = json_object_get(g->doc, "nodes"), *n;
    size_t i;
    int count = 0;
    json_array_foreach(nodes, i, n)
    {
        json_t *x = json_object_get(n, "extras");
        if (!json_object_get(x, "title"))
            continue;
        int k = (int)json_integer_value(json_object_get(x, "index"));
        cr_assert(k >= 0 && k < max);
        exhibit[k] = (int)i;
        vessel[k] = -1;
        json_t *ch = json_object_get(n, "children");
        for (size_t c = 0; c < json_array_size(ch); c++) {
            int child = (int)json_integer_value(json_array_get(ch, c));
            if (json_object_get(json_object_get(json_array_get(nodes, (size_t)child), "extras"), "lod"))
                vessel[k] = child;
        }
        count++;
    }
    return count;
}
