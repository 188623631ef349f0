/* celadon mesh end to end: the binary from CELADON_BIN on a saved profile,
 * good and bad. */
#include <criterion/criterion.h>
#include <math.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/profile.h"
#include "support/cli_run.h"
#include "test_curve_shapes.h"


static char dir[64];

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/celadon-test-meshcli-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

static void teardown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

/* Runs celadon with args; stderr goes to err (NUL-terminated). Returns the exit code. */
static int run(const char *const *args, char *err, size_t errlen)
{
    cli_result r = cli_run(dir, args);
    snprintf(err, errlen, "%s", r.err);
    cli_result_free(&r);
    return r.status;
}

static void write_profile(const char *path, int version_edit)
{
    profile_t p;
    memset(&p, 0, sizeof p);
    snprintf(p.source_path, sizeof p.source_path, "photo.jpg");
    p.axis_direction = v2(0, -1);
    snprintf(p.side, sizeof p.side, "right");
    p.curve = test_vase_curve();
    vec2 poly[2] = {{30, 0}, {33, 140}};
    p.polyline = poly;
    p.n_polyline = 2;
    double dom[] = {0, 0.1, 0.35, 0.5, 0.7, 1};
    p.domains = dom;
    p.n_domains = 6;
    char err[256];
    cr_assert_eq(profile_write_json(path, &p, err, sizeof err), 0, "%s", err);
    bspline_free(&p.curve);
    if (version_edit) { /* turn it into a version-2 file */
        FILE *f = fopen(path, "r+");
        char buf[1 << 16];
        size_t n = fread(buf, 1, sizeof buf - 1, f);
        buf[n] = '\0';
        char *v = strstr(buf, "\"version\": 1");
        cr_assert_not_null(v);
        v[11] = '2';
        rewind(f);
        fwrite(buf, 1, n, f);
        fclose(f);
    }
}

static int exists(const char *path) { return access(path, F_OK) == 0; }

static int count_prefix(const char *path, const char *prefix)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int n = 0;
    while (fgets(line, sizeof line, f))
        n += !strncmp(line, prefix, strlen(prefix));
    fclose(f);
    return n;
}

Test(mesh_cli, obj_with_material_and_ply, .init = setup, .fini = teardown)
{
    char prof[128], tex[128], obj[128], mtl[128], ply[128], err[4096];
    snprintf(prof, sizeof prof, "%s/profile.json", dir);
    snprintf(tex, sizeof tex, "%s/texture.png", dir);
    snprintf(obj, sizeof obj, "%s/vase.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/vase.mtl", dir);
    snprintf(ply, sizeof ply, "%s/vase.ply", dir);
    write_profile(prof, 0);
    fclose(fopen(tex, "w")); /* the material only needs it to exist */

    cr_assert_eq(run((const char *[]){"mesh", prof, "-o", obj, "--segments", "24", NULL}, err, sizeof err), 0, "%s",
                 err);
    cr_assert_str_empty(err);
    /* 6 rings of 24, plus the base cap's ring and its 24 centre vertices. */
    cr_assert_eq(count_prefix(obj, "v "), 6 * 24 + 2 * 24);
    cr_assert_eq(count_prefix(obj, "f "), 2 * 24 * 5 + 24);
    cr_assert_eq(count_prefix(obj, "mtllib vase.mtl"), 1);
    cr_assert_eq(count_prefix(mtl, "map_Kd texture.png"), 1);

    cr_assert_eq(run((const char *[]){"mesh", prof, "-o", ply, "--segments", "10", "--height", "0.3", "--mouth-cap",
                                      NULL},
                     err, sizeof err),
                 0, "%s", err);
    cr_assert_eq(count_prefix(ply, "element vertex 100"), 1); /* 6*10 + 2*2*10 */
    cr_assert_eq(count_prefix(ply, "element face 120"), 1);  /* 2*10*5 + 2*10 */
}

/* A bad run: exit 2, exactly one stderr line naming want, and no output. */
static void expect_bad(const char *const *args, const char *want, const char *out)
{
    char err[4096];
    int rc = run(args, err, sizeof err);
    cr_assert_eq(rc, 2, "exit %d; stderr: %s", rc, err);
    size_t len = strlen(err);
    cr_assert(len > 0 && err[len - 1] == '\n' && !memchr(err, '\n', len - 1), "one line: '%s'", err);
    cr_assert_not_null(strstr(err, want), "stderr '%s' lacks '%s'", err, want);
    cr_assert(!exists(out), "%s was written", out);
}

Test(mesh_cli, bad_input_exits_2_with_one_line_and_no_output, .init = setup, .fini = teardown)
{
    char prof[128], bad[128], obj[128], mtl[128], txt[128];
    snprintf(prof, sizeof prof, "%s/profile.json", dir);
    snprintf(bad, sizeof bad, "%s/v2.json", dir);
    snprintf(obj, sizeof obj, "%s/out.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/out.mtl", dir);
    snprintf(txt, sizeof txt, "%s/out.txt", dir);
    write_profile(prof, 0);
    write_profile(bad, 1);
    char expect[256];
    snprintf(expect, sizeof expect, "celadon: %s: unsupported version", bad);
    expect_bad((const char *[]){"mesh", bad, "-o", obj, NULL}, expect, obj);
    cr_assert(!exists(mtl));
    expect_bad((const char *[]){"mesh", "/nonexistent.json", "-o", obj, NULL}, "/nonexistent.json", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", obj, "--segments", "2", NULL}, "--segments", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", obj, "--segments", "12x", NULL}, "--segments", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", obj, "--height", "-1", NULL}, "--height", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", obj, "--height", "nan", NULL}, "--height", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", txt, NULL}, "unknown mesh format", txt);
    expect_bad((const char *[]){"mesh", prof, NULL}, "missing -o", obj);
    expect_bad((const char *[]){"mesh", prof, "-o", obj, "--bogus", NULL}, "unknown option", obj);
    char deep[160];
    snprintf(deep, sizeof deep, "%s/no/such/dir/out.obj", dir);
    expect_bad((const char *[]){"mesh", prof, "-o", deep, NULL}, deep, deep);
    /* The profile is a folder, or garbage. */
    expect_bad((const char *[]){"mesh", dir, "-o", obj, NULL}, dir, obj);
    FILE *f = fopen(bad, "w");
    fputs("{\"version\": 1, \"bspline\": [", f);
    fclose(f);
    expect_bad((const char *[]){"mesh", bad, "-o", obj, NULL}, "not valid JSON", obj);
}

Test(mesh_cli, help_exits_0, .init = setup, .fini = teardown)
{
    char err[4096];
    cr_assert_eq(run((const char *[]){"mesh", "--help", NULL}, err, sizeof err), 0);
    cr_assert_str_empty(err);
}

/* The vertices of a binary PLY written by celadon (x y z nx ny nz s t). */
static float *ply_vertices(const char *path, int *n)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    char line[256];
    *n = 0;
    while (fgets(line, sizeof line, f) && strncmp(line, "end_header", 10))
        sscanf(line, "element vertex %d", n);
    float *v = malloc(sizeof(float) * 8 * (size_t)*n);
    cr_assert_eq(fread(v, sizeof(float) * 8, (size_t)*n, f), (size_t)*n);
    fclose(f);
    return v;
}

/* A researcher's own profile (the B-spline alone) meshes and renders; the
 * material names the texture relative to the OBJ; --up z turns the mesh so
 * that the axis is +z and the front faces -y. */
Test(mesh_cli, minimal_profile_relative_texture_and_z_up, .init = setup, .fini = teardown)
{
    char prof[128], tex[128], obj[160], mtl[160], sub[128], ply_y[128], ply_z[128], scene[128], png[128], err[4096];
    snprintf(prof, sizeof prof, "%s/profile.json", dir);
    snprintf(tex, sizeof tex, "%s/texture.png", dir);
    snprintf(sub, sizeof sub, "%s/export", dir);
    snprintf(obj, sizeof obj, "%s/export/vase.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/export/vase.mtl", dir);
    FILE *f = fopen(prof, "w");
    fputs("{\"version\": 1, \"bspline\": {\"degree\": 3, \"knots\": [0, 0, 0, 0, 1, 1, 1, 1],\n"
          "  \"control_points\": [[40, 0], [90, 60], [20, 150], [35, 200]]}}\n", f);
    fclose(f);
    fclose(fopen(tex, "w"));
    cr_assert_eq(mkdir(sub, 0755), 0);
    cr_assert_eq(run((const char *[]){"mesh", prof, "-o", obj, "--segments", "12", NULL}, err, sizeof err), 0, "%s",
                 err);
    cr_assert_eq(count_prefix(mtl, "map_Kd ../texture.png"), 1, "relative to the OBJ");

    snprintf(ply_y, sizeof ply_y, "%s/y.ply", dir);
    snprintf(ply_z, sizeof ply_z, "%s/z.ply", dir);
    cr_assert_eq(run((const char *[]){"mesh", prof, "-o", ply_y, "--segments", "12", NULL}, err, sizeof err), 0);
    cr_assert_eq(run((const char *[]){"mesh", prof, "-o", ply_z, "--segments", "12", "--up", "z", NULL}, err,
                     sizeof err), 0, "%s", err);
    int ny, nz;
    float *y = ply_vertices(ply_y, &ny), *z = ply_vertices(ply_z, &nz);
    cr_assert_eq(ny, nz);
    float zmax = 0, front = 0;
    for (int i = 0; i < ny; i++) {
        const float *a = y + 8 * i, *b = z + 8 * i;
        cr_assert(b[0] == a[0] && b[1] == -a[2] && b[2] == a[1], "vertex %d", i);
        cr_assert(b[3] == a[3] && b[4] == -a[5] && b[5] == a[4], "normal %d", i);
        cr_assert(b[6] == a[6] && b[7] == a[7], "uv %d", i);
        zmax = fmaxf(zmax, b[2]);
        if (fabsf(a[6] - 0.5f) < 1e-6f) /* the front meridian, u = 0.5 */
            front = fminf(front, b[1]);
    }
    cr_assert_float_eq(zmax, 1.0f, 1e-6, "the rim at z = 1");
    cr_assert_lt(front, 0.0f, "the front faces -y");
    free(y);
    free(z);
    expect_bad((const char *[]){"mesh", prof, "-o", ply_z, "--up", "x", NULL}, "--up must be y or z", "/nonexistent");

    snprintf(scene, sizeof scene, "%s/scene.xml", dir);
    snprintf(png, sizeof png, "%s/r.png", dir);
    f = fopen(scene, "w");
    fputs("<scene version=\"3.0.0\"><sensor type=\"perspective\"><transform name=\"to_world\">"
          "<lookat origin=\"0 0.5 -4\" target=\"0 0.5 0\" up=\"0 1 0\"/></transform></sensor>"
          "<shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/></shape>"
          "<emitter type=\"constant\"/></scene>\n", f);
    fclose(f);
    cr_assert_eq(run((const char *[]){"render", scene, "-o", png, "--res", "16x16", "--spp", "1", NULL}, err,
                     sizeof err), 0, "%s", err);
    cr_assert(exists(png));
}
