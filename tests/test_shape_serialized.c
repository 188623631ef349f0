/* The `serialized` shape: files this test writes itself with zlib, in the
 * layout Mitsuba documents (versions 3 and 4, one or more meshes and the
 * end-of-file dictionary), read back exactly; damaged files refused in one
 * line. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "shapes/shapes.h"
#include "support/plugin_xml.h"

typedef struct {
    unsigned char *b;
    size_t n, cap;
} bytes;

static void put_bytes(bytes *o, const void *p, size_t n)
{
    if (o->n + n > o->cap) {
        o->cap = 2 * (o->n + n);
        o->b = realloc(o->b, o->cap);
        cr_assert_not_null(o->b);
    }
    memcpy(o->b + o->n, p, n);
    o->n += n;
}

static void put_le(bytes *o, uint64_t v, int size)
{
    unsigned char b[8];
    for (int i = 0; i < size; i++)
        b[i] = (unsigned char)(v >> (8 * i));
    put_bytes(o, b, (size_t)size);
}

static void put_real(bytes *o, double v, int dbl)
{
    if (dbl) {
        uint64_t u;
        memcpy(&u, &v, 8);
        put_le(o, u, 8);
    } else {
        float f = (float)v;
        uint32_t u;
        memcpy(&u, &f, 4);
        put_le(o, u, 4);
    }
}

/* A mesh: nv vertices at (i, 2i + k, -i/4) (k the mesh's number) with normals
 * (0, 0, 1) and uvs (i/8, 1 - i/8), fanned triangles (0, i, i+1). */
enum { NV = 6 };

static void put_mesh(bytes *file, int version, int k, int dbl, unsigned flags)
{
    bytes raw = {0};
    put_le(&raw, flags | (dbl ? 0x2000u : 0x1000u), 4);
    if (version == 4)
        put_bytes(&raw, "mesh", 5);
    put_le(&raw, NV, 8);
    put_le(&raw, NV - 2, 8);
    for (int i = 0; i < NV; i++) {
        put_real(&raw, i, dbl);
        put_real(&raw, 2 * i + k, dbl);
        put_real(&raw, -i / 4.0, dbl);
    }
    for (int i = 0; (flags & 1) && i < NV; i++)
        for (int c = 0; c < 3; c++)
            put_real(&raw, c == 2, dbl);
    for (int i = 0; (flags & 2) && i < NV; i++) {
        put_real(&raw, i / 8.0, dbl);
        put_real(&raw, 1 - i / 8.0, dbl);
    }
    for (int i = 0; (flags & 8) && i < NV; i++)
        for (int c = 0; c < 3; c++)
            put_real(&raw, 0.5, dbl);
    for (int t = 0; t < NV - 2; t++) {
        put_le(&raw, 0, 4);
        put_le(&raw, (uint64_t)t + 1, 4);
        put_le(&raw, (uint64_t)t + 2, 4);
    }
    uLongf zn = compressBound(raw.n);
    unsigned char *z = malloc(zn);
    cr_assert_eq(compress2(z, &zn, raw.b, raw.n, 9), Z_OK);
    put_le(file, 0x041C, 2);
    put_le(file, (uint64_t)version, 2);
    put_bytes(file, z, zn);
    free(z);
    free(raw.b);
}

/* A file of nmeshes meshes with its dictionary, written to path. */
static void write_file(const char *path, int version, int nmeshes, int dbl, unsigned flags)
{
    bytes f = {0};
    uint64_t off[4];
    for (int k = 0; k < nmeshes; k++) {
        off[k] = f.n;
        put_mesh(&f, version, k, dbl, flags);
    }
    for (int k = 0; k < nmeshes; k++)
        put_le(&f, off[k], version == 4 ? 8 : 4);
    put_le(&f, (uint64_t)nmeshes, 4);
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(f.b, 1, f.n, fp), f.n);
    fclose(fp);
    free(f.b);
}

/* Builds <shape type="serialized"> of path with extra parameters: 0, or -1
 * with the message in err. */
static int build(const char *path, const char *extra, shape_t *sh, char *err, size_t errlen)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char xml[1024];
    snprintf(xml, sizeof xml, "\n<shape type=\"serialized\"><string name=\"filename\" value=\"%s\"/>%s</shape>", path,
             extra);
    scene_obj *o;
    int rc = plugin_xml_objects(&fx, xml, SCENE_SHAPE, &o, 1, err, errlen) == 1 ? 0 : -1;
    shape_options opt = {0};
    if (rc == 0)
        rc = shape_create(o, NULL, &opt, sh, err, errlen);
    plugin_xml_close(&fx);
    return rc;
}

static char path[64];

static void make_file(void)
{
    snprintf(path, sizeof path, "/tmp/celadon-serialized-XXXXXX");
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    close(fd);
}
static void remove_file(void) { unlink(path); }

TestSuite(shape_serialized, .init = make_file, .fini = remove_file);

Test(shape_serialized, every_mesh_of_a_file_reads_back_exactly)
{
    const struct { int version, dbl; unsigned flags; } kinds[] = {{4, 0, 3}, {4, 1, 3}, {3, 0, 2 | 8}, {4, 0, 0}};
    for (size_t c = 0; c < sizeof kinds / sizeof kinds[0]; c++) {
        write_file(path, kinds[c].version, 3, kinds[c].dbl, kinds[c].flags);
        for (int k = 0; k < 3; k++) {
            char extra[128], err[512];
            snprintf(extra, sizeof extra, "<integer name=\"shape_index\" value=\"%d\"/>", k);
            shape_t sh;
            cr_assert_eq(build(path, extra, &sh, err, sizeof err), 0, "%s", err);
            cr_assert_eq(sh.mesh.n_verts, NV);
            cr_assert_eq(sh.mesh.n_tris, NV - 2);
            for (int i = 0; i < NV; i++) {
                cr_expect_eq(sh.mesh.pos[3 * i], (float)i);
                cr_expect_eq(sh.mesh.pos[3 * i + 1], (float)(2 * i + k), "mesh %d of version %d", k,
                             kinds[c].version);
                cr_expect_eq(sh.mesh.pos[3 * i + 2], (float)(-i / 4.0));
                if (kinds[c].flags & 1)
                    cr_expect_eq(sh.mesh.nrm[3 * i + 2], 1.0f);
                if (kinds[c].flags & 2) {
                    cr_expect_eq(sh.mesh.uv[2 * i], (float)(i / 8.0), "uvs as stored");
                    cr_expect_eq(sh.mesh.uv[2 * i + 1], (float)(1 - i / 8.0));
                } else {
                    cr_expect_null(sh.mesh.uv);
                }
            }
            for (int t = 0; t < NV - 2; t++)
                cr_expect(sh.mesh.tri[3 * t] == 0 && sh.mesh.tri[3 * t + 1] == (unsigned)t + 1 &&
                          sh.mesh.tri[3 * t + 2] == (unsigned)t + 2);
            shape_free(&sh);
        }
    }
}

Test(shape_serialized, damaged_files_are_refused_in_one_line)
{
    char err[512];
    shape_t sh;
    write_file(path, 4, 2, 0, 3);
    cr_assert_eq(build(path, "<integer name=\"shape_index\" value=\"2\"/>", &sh, err, sizeof err), -1);
    cr_expect(strstr(err, "snippet.xml:2: ") == err && strstr(err, "shape_index 2 is out of range (the file holds 2"),
              "%s", err);
    /* cut inside the first mesh's stream */
    FILE *fp = fopen(path, "r+b");
    cr_assert_eq(ftruncate(fileno(fp), 40), 0);
    fclose(fp);
    cr_assert_eq(build(path, "", &sh, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "truncated or corrupt"), "%s", err);
    fp = fopen(path, "wb");
    fputs("# not a mesh\n", fp);
    fclose(fp);
    cr_assert_eq(build(path, "", &sh, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "not a Mitsuba .serialized file"), "%s", err);
    cr_expect_null(strchr(err, '\n'));
}
