/* The exporters, read back by minimal OBJ and PLY readers written here from
 * the format specifications: counts, every value, the texture reference. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/mesh.h"
#include "test_curve_shapes.h"

static char tmpdir[64];

static void make_tmpdir(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/celadon-test-mesh-XXXXXX");
    cr_assert_not_null(mkdtemp(tmpdir));
}

/* Removes the folder, asserting it holds exactly n_expected entries (so no
 * temporary file was left behind). */
static void remove_tmpdir(int n_expected)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    int n = 0;
    char p[512];
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            n++;
            snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
            remove(p);
        }
    closedir(d);
    rmdir(tmpdir);
    cr_assert_eq(n, n_expected, "files left in the output folder: %d, expected %d", n, n_expected);
}

static mesh_t small_mesh(void)
{
    bspline_t c = test_vase_curve();
    mesh_t m;
    cr_assert_eq(mesh_revolve(&c, NULL, 6, 0.5, 11, MESH_CAP_BASE | MESH_CAP_MOUTH, &m), 0);
    bspline_free(&c);
    return m;
}

Test(mesh_export, obj_reads_back)
{
    make_tmpdir();
    mesh_t m = small_mesh();
    char path[128], err[256];
    snprintf(path, sizeof path, "%s/vase.obj", tmpdir);
    cr_assert_eq(mesh_write_obj(path, &m, "vase.mtl", err, sizeof err), 0, "%s", err);

    FILE *f = fopen(path, "r");
    char line[512], mtllib[64] = "", usemtl[64] = "";
    int nv = 0, nt = 0, nn = 0, nf = 0;
    while (fgets(line, sizeof line, f)) {
        float a, b, c;
        unsigned idx[9];
        if (sscanf(line, "v %f %f %f", &a, &b, &c) == 3) {
            cr_assert_float_eq(a, m.pos[3 * nv], 1e-6);
            cr_assert_float_eq(b, m.pos[3 * nv + 1], 1e-6);
            cr_assert_float_eq(c, m.pos[3 * nv + 2], 1e-6);
            nv++;
        } else if (sscanf(line, "vt %f %f", &a, &b) == 2) {
            cr_assert_float_eq(a, m.uv[2 * nt], 1e-6);
            cr_assert_float_eq(b, m.uv[2 * nt + 1], 1e-6);
            nt++;
        } else if (sscanf(line, "vn %f %f %f", &a, &b, &c) == 3) {
            cr_assert_float_eq(a, m.nrm[3 * nn], 1e-5);
            cr_assert_float_eq(b, m.nrm[3 * nn + 1], 1e-5);
            cr_assert_float_eq(c, m.nrm[3 * nn + 2], 1e-5);
            nn++;
        } else if (sscanf(line, "f %u/%u/%u %u/%u/%u %u/%u/%u", idx, idx + 1, idx + 2, idx + 3, idx + 4, idx + 5,
                          idx + 6, idx + 7, idx + 8) == 9) {
            for (int k = 0; k < 3; k++) {
                cr_assert_eq(idx[3 * k], m.tri[3 * nf + k] + 1, "face %d", nf);
                cr_assert_eq(idx[3 * k + 1], idx[3 * k]);
                cr_assert_eq(idx[3 * k + 2], idx[3 * k]);
            }
            nf++;
        } else {
            sscanf(line, "mtllib %63s", mtllib);
            sscanf(line, "usemtl %63s", usemtl);
        }
    }
    fclose(f);
    cr_assert_eq(nv, m.n_verts);
    cr_assert_eq(nt, m.n_verts);
    cr_assert_eq(nn, m.n_verts);
    cr_assert_eq(nf, m.n_tris);
    cr_assert_str_eq(mtllib, "vase.mtl");
    cr_assert_str_eq(usemtl, "celadon");

    snprintf(path, sizeof path, "%s/vase.mtl", tmpdir);
    cr_assert_eq(mesh_write_mtl(path, "texture.png", err, sizeof err), 0, "%s", err);
    f = fopen(path, "r");
    char newmtl[64] = "", map[64] = "";
    while (fgets(line, sizeof line, f)) {
        sscanf(line, "newmtl %63s", newmtl);
        sscanf(line, "map_Kd %63s", map);
    }
    fclose(f);
    cr_assert_str_eq(newmtl, "celadon");
    cr_assert_str_eq(map, "texture.png");
    mesh_free(&m);
    remove_tmpdir(2);
}

static uint32_t get_u32le(const unsigned char *b) { return b[0] | b[1] << 8 | b[2] << 16 | (uint32_t)b[3] << 24; }
static float get_f32le(const unsigned char *b)
{
    uint32_t v = get_u32le(b);
    float f;
    memcpy(&f, &v, sizeof f);
    return f;
}

Test(mesh_export, ply_reads_back_bit_exact)
{
    make_tmpdir();
    mesh_t m = small_mesh();
    char path[128], err[256];
    snprintf(path, sizeof path, "%s/vase.ply", tmpdir);
    cr_assert_eq(mesh_write_ply(path, &m, err, sizeof err), 0, "%s", err);

    FILE *f = fopen(path, "rb");
    char line[256];
    int nv = -1, nf = -1, n_props = 0, binary_le = 0;
    const char *want_props[] = {"x", "y", "z", "nx", "ny", "nz", "s", "t"};
    while (fgets(line, sizeof line, f) && strcmp(line, "end_header\n")) {
        char name[32];
        sscanf(line, "element vertex %d", &nv);
        sscanf(line, "element face %d", &nf);
        if (!strcmp(line, "format binary_little_endian 1.0\n"))
            binary_le = 1;
        if (sscanf(line, "property float %31s", name) == 1) {
            cr_assert_lt(n_props, 8);
            cr_assert_str_eq(name, want_props[n_props]);
            n_props++;
        }
    }
    cr_assert(binary_le);
    cr_assert_eq(n_props, 8);
    cr_assert_eq(nv, m.n_verts);
    cr_assert_eq(nf, m.n_tris);
    unsigned char rec[32];
    for (int v = 0; v < nv; v++) {
        cr_assert_eq(fread(rec, 1, 32, f), 32u);
        for (int k = 0; k < 3; k++) {
            cr_assert_eq(get_f32le(rec + 4 * k), m.pos[3 * v + k]);
            cr_assert_eq(get_f32le(rec + 12 + 4 * k), m.nrm[3 * v + k]);
        }
        cr_assert_eq(get_f32le(rec + 24), m.uv[2 * v]);
        cr_assert_eq(get_f32le(rec + 28), m.uv[2 * v + 1]);
    }
    for (int t = 0; t < nf; t++) {
        cr_assert_eq(fread(rec, 1, 13, f), 13u);
        cr_assert_eq(rec[0], 3);
        for (int k = 0; k < 3; k++)
            cr_assert_eq(get_u32le(rec + 1 + 4 * k), m.tri[3 * t + k]);
    }
    cr_assert_eq(fgetc(f), EOF, "trailing bytes after the last face");
    fclose(f);
    mesh_free(&m);
    remove_tmpdir(1);
}

Test(mesh_export, unwritable_path_fails_cleanly)
{
    make_tmpdir();
    mesh_t m = small_mesh();
    char path[128], err[256] = "";
    snprintf(path, sizeof path, "%s/no/such/dir/vase.obj", tmpdir);
    cr_assert_eq(mesh_write_obj(path, &m, NULL, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, path), "error names the file: %s", err);
    cr_assert_null(strchr(err, '\n'));
    snprintf(path, sizeof path, "%s/no/such/dir/vase.ply", tmpdir);
    cr_assert_eq(mesh_write_ply(path, &m, err, sizeof err), -1);
    cr_assert_not_null(strstr(err, path));
    snprintf(path, sizeof path, "%s/no/such/dir/vase.mtl", tmpdir);
    cr_assert_eq(mesh_write_mtl(path, "texture.png", err, sizeof err), -1);
    mesh_free(&m);
    remove_tmpdir(0);
}
