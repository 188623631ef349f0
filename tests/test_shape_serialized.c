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
#include "support/serialized_file.h"

/* A file of nmeshes meshes (support/serialized_file.h) written to path. */
static void write_file(const char *path, int version, int nmeshes, int dbl, unsigned flags, int level)
{
    cr_assert_eq(serialized_file_write(path, version, nmeshes, dbl, flags, level), 0, "cannot write %s", path);
}

enum { NV = SERIALIZED_FILE_NV };

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
    /* zlib level 0 stores the data in the stream uncompressed */
    const struct { int version, dbl; unsigned flags; int level; } kinds[] = {
        {4, 0, 3, 9}, {4, 1, 3, 9}, {3, 0, 2 | 8, 9}, {4, 0, 0, 9}, {3, 1, 1, 0}};
    for (size_t c = 0; c < sizeof kinds / sizeof kinds[0]; c++) {
        write_file(path, kinds[c].version, 3, kinds[c].dbl, kinds[c].flags, kinds[c].level);
        for (int k = 0; k < 3; k++) {
            char extra[128], err[512];
            snprintf(extra, sizeof extra, "<integer name=\"shape_index\" value=\"%d\"/>", k);
            shape_t sh;
            cr_assert_eq(build(path, extra, &sh, err, sizeof err), 0, "%s", err);
            cr_assert_eq(sh.mesh.n_verts, NV);
            cr_assert_eq(sh.mesh.n_tris, NV - 2);
            for (int i = 0; i < NV; i++) {
                cr_expect_eq(sh.mesh.pos[3 * i], (float)i);
                cr_expect_eq(sh.mesh.pos[3 * i + 1], (float)(i * i + k), "mesh %d of version %d", k,
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
    write_file(path, 4, 2, 0, 3, 9);
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

/* Writes bytes to path. */
static void write_bytes(const unsigned char *b, size_t n)
{
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(b, 1, n, fp), n);
    fclose(fp);
}

/* A mesh's offset in the dictionary is the file's to choose: one near 2^64
 * is past the end (off + 4 wrapped around to pass the check). */
Test(shape_serialized, an_offset_past_the_end_is_refused)
{
    size_t n;
    unsigned char *b = serialized_file_bytes(4, 2, 0, 3, 9, &n);
    for (int i = 0; i < 8; i++) /* mesh 1's entry: the last before the count */
        b[n - 4 - 8 + i] = i ? 0xff : 0xfe;
    write_bytes(b, n);
    free(b);
    char err[512];
    shape_t sh;
    cr_assert_eq(build(path, "<integer name=\"shape_index\" value=\"1\"/>", &sh, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "past the end of the file"), "%s", err);
}

/* A small file may not claim more than its stream can hold (zlib expands a
 * byte to at most 1032): 2^27 vertices in a stream of 30 bytes are refused
 * before gigabytes are allocated for them. */
Test(shape_serialized, counts_beyond_what_the_stream_holds_are_refused)
{
    unsigned char raw[4 + 5 + 16] = {0x01, 0x10, 0, 0, 'm', 'e', 's', 'h', 0};
    uint64_t nv = 1u << 27, nt = 1;
    for (int i = 0; i < 8; i++) {
        raw[9 + i] = (unsigned char)(nv >> (8 * i));
        raw[17 + i] = (unsigned char)(nt >> (8 * i));
    }
    unsigned char file[4 + 128] = {0x1c, 0x04, 4, 0};
    uLongf zn = sizeof file - 4;
    cr_assert_eq(compress2(file + 4, &zn, raw, sizeof raw, 9), Z_OK);
    write_bytes(file, 4 + zn);
    char err[512];
    shape_t sh;
    cr_assert_eq(build(path, "", &sh, err, sizeof err), -1);
    cr_expect_not_null(strstr(err, "134217728 vertices and 1 triangles, more than its"), "%s", err);
}
