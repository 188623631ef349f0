/* What makes Mitsuba's own scene files open (issue 12): <path> and where
 * files are found, objects declared at the top level and referenced by id,
 * scenes of Mitsuba 0.6 upgraded on reading, the plugins refused by name,
 * and instancing. Each test writes its own small scenes. */
#include <criterion/criterion.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/render.h"
#include "celadon/scene.h"
#include "celadon/scene_xml.h"

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/celadon-mitsuba-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

static int rm_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_dir(void) { nftw(dir, rm_entry, 8, FTW_DEPTH | FTW_PHYS); }

TestSuite(scene_mitsuba, .init = make_dir, .fini = remove_dir);

static void mkdir_in(const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    cr_assert_eq(mkdir(path, 0755), 0, "%s", path);
}

/* Writes dir/name; its path into path. */
static void put(const char *name, const char *text, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "%s", path);
    fputs(text, f);
    fclose(f);
}

static scene_desc *load(const char *name, const char *text, char *err, size_t errlen)
{
    char path[256];
    put(name, text, path, sizeof path);
    return scene_desc_create_from_file(path, NULL, 0, scene_plugin_find, err, errlen);
}

static scene_desc *load_ok(const char *name, const char *text)
{
    char err[1024] = "";
    scene_desc *d = load(name, text, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    return d;
}

/* The text must fail with "dir/file:line: " and needle, on one line. */
static void load_fails(const char *name, const char *text, const char *errfile, int line, const char *needle)
{
    char err[1024] = "", prefix[300];
    scene_desc *d = load(name, text, err, sizeof err);
    cr_assert_null(d, "expected an error for:\n%s", text);
    snprintf(prefix, sizeof prefix, "%s/%s:%d: ", dir, errfile, line);
    cr_assert(strncmp(err, prefix, strlen(prefix)) == 0, "message '%s' does not start with '%s'", err, prefix);
    cr_assert_not_null(strstr(err, needle), "message '%s' lacks '%s'", err, needle);
    cr_assert_null(strchr(err, '\n'), "one line: '%s'", err);
}

#define V3 "<scene version=\"3.0.0\">\n"

/* ------------------------------------------------------ files and <path> */
Test(scene_mitsuba, files_are_found_beside_the_naming_file_then_the_scene_then_each_path)
{
    char path[256];
    mkdir_in("common");
    mkdir_in("common/meshes");
    mkdir_in("parts");
    mkdir_in("parts/include");
    put("common/meshes/a.obj", "v 0 0 0\n", path, sizeof path);
    put("parts/b.obj", "v 0 0 0\n", path, sizeof path);
    put("shared.xml", V3 "  <bsdf type=\"diffuse\" id=\"m\"/>\n</scene>\n", path, sizeof path);
    /* an included file in parts/ names a mesh beside itself, one found only
     * through <path>, and includes a file found only in the scene's folder */
    put("parts/include/shapes.xml",
        V3 "  <include filename=\"shared.xml\"/>\n"
           "  <shape type=\"obj\"><string name=\"filename\" value=\"../b.obj\"/><ref id=\"m\"/></shape>\n"
           "  <shape type=\"obj\"><string name=\"filename\" value=\"meshes/a.obj\"/></shape>\n</scene>\n",
        path, sizeof path);
    scene_desc *d = load_ok("scene.xml", V3 "  <path value=\"common\"/>\n"
                                            "  <include filename=\"parts/include/shapes.xml\"/>\n</scene>\n");
    scene_obj *s[2];
    cr_assert_eq(scene_obj_children(scene_desc_root(d), SCENE_SHAPE, s, 2), 2);
    char want[300];
    snprintf(want, sizeof want, "%s/parts/include/../b.obj", dir);
    cr_assert_str_eq(scene_obj_string(s[0], "filename", ""), want, "beside the file that names it");
    snprintf(want, sizeof want, "%s/common/meshes/a.obj", dir);
    cr_assert_str_eq(scene_obj_string(s[1], "filename", ""), want, "through <path>");
    cr_assert_str_eq(scene_obj_child(s[0], SCENE_BSDF)->id, "m", "include found in the scene's folder");
    scene_desc_destroy(d);

    load_fails("nopath.xml", V3 "\n  <path value=\"nowhere\"/>\n</scene>\n", "nopath.xml", 3,
               "<path>: folder 'nowhere' not found");
    load_fails("deep.xml", V3 "  <shape type=\"sphere\">\n    <path value=\"common\"/>\n  </shape>\n</scene>\n",
               "deep.xml", 3, "<path> must be a direct child of <scene>");
    /* a later <path> is searched first, as Mitsuba prepends it */
    mkdir_in("other");
    mkdir_in("other/meshes");
    put("other/meshes/a.obj", "v 1 1 1\n", path, sizeof path);
    d = load_ok("two.xml", V3 "  <path value=\"common\"/>\n  <path value=\"other\"/>\n"
                              "  <shape type=\"obj\"><string name=\"filename\" value=\"meshes/a.obj\"/></shape>\n"
                              "</scene>\n");
    snprintf(want, sizeof want, "%s/other/meshes/a.obj", dir);
    cr_assert_str_eq(scene_obj_string(scene_obj_child(scene_desc_root(d), SCENE_SHAPE), "filename", ""), want);
    scene_desc_destroy(d);
}

/* ----------------------------------------------- top-level declarations */
Test(scene_mitsuba, objects_of_every_kind_declared_at_the_top_and_referenced)
{
    scene_desc *d = load_ok("decl.xml",
        V3 "  <sampler type=\"independent\" id=\"smp\"><integer name=\"sample_count\" value=\"7\"/></sampler>\n"
           "  <film type=\"hdrfilm\" id=\"flm\"><integer name=\"width\" value=\"5\"/>"
           "<integer name=\"height\" value=\"3\"/><ref id=\"flt\"/></film>\n"
           "  <rfilter type=\"box\" id=\"flt\"/>\n"
           "  <emitter type=\"area\" id=\"glow\"><rgb name=\"radiance\" value=\"2\"/></emitter>\n"
           "  <sampler type=\"independent\" id=\"unused\"/>\n"
           "  <sensor type=\"perspective\"><ref id=\"smp\"/><ref id=\"flm\"/></sensor>\n"
           "  <shape type=\"sphere\"><ref id=\"glow\"/></shape>\n"
           "  <shape type=\"cube\"><ref name=\"bsdf\" id=\"mat\"/></shape>\n"
           "  <bsdf type=\"diffuse\" id=\"mat\"/>\n"
           "</scene>\n");
    scene_obj *root = scene_desc_root(d);
    cr_assert_eq(scene_obj_children(root, SCENE_SAMPLER, NULL, 0), 0, "declared, not held by the scene");
    cr_assert_eq(scene_obj_children(root, SCENE_EMITTER, NULL, 0), 0);
    scene_obj *sensor = scene_obj_child(root, SCENE_SENSOR);
    cr_assert_str_eq(scene_obj_child(sensor, SCENE_SAMPLER)->id, "smp");
    scene_obj *film = scene_obj_child(sensor, SCENE_FILM);
    cr_assert_str_eq(scene_obj_child(film, SCENE_RFILTER)->id, "flt");
    scene_obj *s[2];
    scene_obj_children(root, SCENE_SHAPE, s, 2);
    cr_assert_str_eq(scene_obj_child(s[0], SCENE_EMITTER)->id, "glow");
    cr_assert_str_eq(scene_obj_child(s[1], SCENE_BSDF)->id, "mat", "<ref name=\"bsdf\"> as Mitsuba writes it");
    char err[512];
    scene_t *scene = scene_create(d, NULL, err, sizeof err);
    cr_assert_not_null(scene, "%s", err);
    int w, h;
    scene_film_size(scene, &w, &h);
    cr_assert(w == 5 && h == 3, "the referenced film: %dx%d", w, h);
    scene_destroy(scene);
    scene_desc_destroy(d);

    /* without an id a top-level sampler has nowhere to go */
    load_fails("noid.xml", V3 "\n  <sampler type=\"independent\"/>\n</scene>\n", "noid.xml", 3,
               "cannot contain a <sampler>");
}

/* ------------------------------------------------------------ refusals */
Test(scene_mitsuba, polarized_spectral_and_dropped_plugins_are_refused_by_name)
{
    load_fails("p.xml", V3 "\n  <bsdf type=\"pplastic\"/>\n</scene>\n", "p.xml", 3,
               "unknown plugin 'pplastic' for <bsdf> (polarized");
    load_fails("s.xml", V3 "  <integrator type=\"stokes\"/>\n</scene>\n", "s.xml", 2,
               "unknown plugin 'stokes' for <integrator> (polarized");
    load_fails("m.xml", V3 "  <bsdf type=\"measured\"/>\n</scene>\n", "m.xml", 2, "(spectral measurements");
    load_fails("pm.xml", "<scene version=\"0.6.0\">\n  <integrator type=\"photonmapper\"/>\n</scene>\n", "pm.xml", 2,
               "unknown plugin 'photonmapper' for <integrator> (Mitsuba 0.6's; Mitsuba 3 dropped it)");
    load_fails("v4.xml", "<scene version=\"4.0.0\">\n</scene>\n", "v4.xml", 1, "not supported");
    /* what Mitsuba 3 ignores and changes nothing is dropped: banner */
    scene_desc *d = load_ok("banner.xml", V3 "  <sensor type=\"perspective\"><film type=\"hdrfilm\">"
                                             "<boolean name=\"banner\" value=\"false\"/></film></sensor>\n</scene>\n");
    cr_assert_not(scene_obj_has(scene_obj_child(scene_obj_child(scene_desc_root(d), SCENE_SENSOR), SCENE_FILM),
                                "banner"));
    scene_desc_destroy(d);
}
