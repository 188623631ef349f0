/* What makes Mitsuba's own scene files open (issue 12): <path> and where
 * files are found, objects declared at the top level and referenced by id,
 * scenes of Mitsuba 0.6 upgraded on reading, the plugins refused by name,
 * and instancing. Each test writes its own small scenes. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/render.h"
#include "celadon/scene.h"
#include "celadon/scene_xml.h"
#include "scene_xml/scene_xml_internal.h"
#include "support/scratch_dir.h"

static char dir[64];

static void make_dir(void) { scratch_dir_make(dir, sizeof dir, "mitsuba"); }

static void remove_dir(void) { scratch_dir_remove(dir); }

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

/* Mitsuba 3 finds a plugin as the file plugins/<type>.so: on the
 * case-insensitive file systems of macOS and Windows `Rectangle` is the
 * rectangle (as in some of Mitsuba's own scenes); a type that is no plugin in
 * any spelling is still refused. */
Test(scene_mitsuba, capitalised_plugin_names_are_their_lower_case_plugins)
{
    scene_desc *d = load_ok("cap.xml", V3 "\n  <shape type=\"Rectangle\"><bsdf type=\"Diffuse\"/></shape>\n</scene>\n");
    scene_obj *s = scene_obj_child(scene_desc_root(d), SCENE_SHAPE);
    cr_assert_str_eq(s->type, "rectangle");
    cr_assert_str_eq(scene_obj_child(s, SCENE_BSDF)->type, "diffuse");
    scene_desc_destroy(d);
    load_fails("capx.xml", V3 "\n  <shape type=\"Rectangles\"/>\n</scene>\n", "capx.xml", 3,
               "unknown plugin 'Rectangles' for <shape>");
}

/* ------------------------------------------------------ the 0.6 upgrade */
/* Whether two trees hold the same objects with the same properties (names,
 * types, values), ignoring where they were written. */
static void expect_same_tree(const scene_obj *a, const scene_obj *b)
{
    cr_assert_eq(a->cls, b->cls);
    cr_assert_str_eq(a->type, b->type);
    cr_assert_eq(!a->id, !b->id);
    cr_assert_eq(a->nprops, b->nprops, "<%s type=%s>: %d properties, not %d", scene_class_name(a->cls), a->type,
                 a->nprops, b->nprops);
    for (int i = 0; i < a->nprops; i++) {
        const scene_prop *p = &a->props[i], *q = NULL;
        for (int j = 0; j < b->nprops; j++)
            if (!strcmp(b->props[j].name, p->name))
                q = &b->props[j];
        cr_assert_not_null(q, "<%s type=%s>: no '%s' in the 3.0 scene", scene_class_name(a->cls), a->type, p->name);
        cr_assert_eq(p->type, q->type, "'%s'", p->name);
        switch (p->type) {
        case SCENE_FLOAT: cr_expect_eq(p->value.f, q->value.f, "'%s'", p->name); break;
        case SCENE_INTEGER: cr_expect_eq(p->value.i, q->value.i, "'%s'", p->name); break;
        case SCENE_BOOLEAN: cr_expect_eq(p->value.b, q->value.b, "'%s'", p->name); break;
        case SCENE_STRING: cr_expect_str_eq(p->value.s, q->value.s, "'%s'", p->name); break;
        case SCENE_RGB:
        case SCENE_SPECTRUM:
            cr_expect(p->value.rgb.r == q->value.rgb.r && p->value.rgb.g == q->value.rgb.g &&
                      p->value.rgb.b == q->value.rgb.b, "'%s'", p->name);
            break;
        case SCENE_POINT:
        case SCENE_VECTOR: cr_expect(v3_len(v3_sub(p->value.v, q->value.v)) == 0, "'%s'", p->name); break;
        case SCENE_TRANSFORM:
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                    cr_expect_float_eq(p->value.xf.m[r][c], q->value.xf.m[r][c], 1e-12, "'%s'", p->name);
            break;
        case SCENE_OBJECT: expect_same_tree(p->value.obj, q->value.obj); break;
        }
    }
    cr_assert_eq(a->nchildren, b->nchildren, "<%s type=%s>", scene_class_name(a->cls), a->type);
    for (int i = 0; i < a->nchildren; i++)
        expect_same_tree(a->children[i], b->children[i]);
}

Test(scene_mitsuba, a_mitsuba_06_scene_reads_as_its_3_0_rewrite)
{
    char path[256];
    put("tex.png", "only existence is checked", path, sizeof path);
    put("mesh.obj", "v 0 0 0\n", path, sizeof path);
    scene_desc *old = load_ok("old.xml",
        "<scene version=\"0.6.0\">\n"
        "  <integrator type=\"path\"><integer name=\"maxDepth\" value=\"65\"/>"
        "<boolean name=\"strictNormals\" value=\"true\"/></integrator>\n"
        "  <sensor type=\"perspective\"><float name=\"fov\" value=\"35\"/><string name=\"fovAxis\" value=\"smaller\"/>\n"
        "    <float name=\"nearClip\" value=\"0.1\"/><float name=\"focusDistance\" value=\"3\"/>\n"
        "    <transform name=\"toWorld\"><lookAt origin=\"0 1 -4\" target=\"0 0 0\" up=\"0 1 0\"/></transform>\n"
        "    <sampler type=\"independent\"><integer name=\"sampleCount\" value=\"16\"/></sampler>\n"
        "    <film type=\"ldrfilm\"><integer name=\"width\" value=\"64\"/><integer name=\"height\" value=\"48\"/>\n"
        "      <string name=\"fileFormat\" value=\"png\"/><float name=\"gamma\" value=\"2.2\"/>"
        "<boolean name=\"banner\" value=\"false\"/><rfilter type=\"tent\"/></film>\n"
        "  </sensor>\n"
        "  <bsdf type=\"diffuse\" id=\"wood\"><texture type=\"bitmap\" name=\"diffuseReflectance\">\n"
        "    <string name=\"filename\" value=\"tex.png\"/><string name=\"filterType\" value=\"trilinear\"/>\n"
        "    <float name=\"uoffset\" value=\"0.25\"/><float name=\"vscale\" value=\"4\"/></texture></bsdf>\n"
        "  <bsdf type=\"roughplastic\" id=\"plastic\"><float name=\"intIOR\" value=\"1.5\"/>"
        "<rgb name=\"diffuseReflectance\" value=\"0.2 0.3 0.4\"/><string name=\"distribution\" value=\"ggx\"/></bsdf>\n"
        "  <shape type=\"obj\"><string name=\"filename\" value=\"mesh.obj\"/><boolean name=\"faceNormals\" value=\"true\"/>\n"
        "    <transform name=\"toWorld\"><scale value=\"2\"/></transform><ref id=\"wood\"/></shape>\n"
        "  <shape type=\"sphere\"><ref id=\"plastic\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"3\"/></emitter></shape>\n"
        "</scene>\n");
    scene_desc *now = load_ok("now.xml",
        "<scene version=\"3.0.0\">\n"
        "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"65\"/></integrator>\n"
        "  <sensor type=\"perspective\"><float name=\"fov\" value=\"35\"/><string name=\"fov_axis\" value=\"smaller\"/>\n"
        "    <float name=\"near_clip\" value=\"0.1\"/><float name=\"focus_distance\" value=\"3\"/>\n"
        "    <transform name=\"to_world\"><lookat origin=\"0 1 -4\" target=\"0 0 0\" up=\"0 1 0\"/></transform>\n"
        "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"16\"/></sampler>\n"
        "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"64\"/><integer name=\"height\" value=\"48\"/>\n"
        "      <rfilter type=\"tent\"/></film>\n"
        "  </sensor>\n"
        "  <bsdf type=\"diffuse\" id=\"wood\"><texture type=\"bitmap\" name=\"reflectance\">\n"
        "    <string name=\"filename\" value=\"tex.png\"/><string name=\"filter_type\" value=\"bilinear\"/>\n"
        "    <transform name=\"to_uv\"><translate x=\"0.25\" y=\"0\"/><scale x=\"1\" y=\"4\"/></transform></texture></bsdf>\n"
        "  <bsdf type=\"roughplastic\" id=\"plastic\"><float name=\"int_ior\" value=\"1.5\"/>"
        "<rgb name=\"diffuse_reflectance\" value=\"0.2 0.3 0.4\"/><string name=\"distribution\" value=\"ggx\"/></bsdf>\n"
        "  <shape type=\"obj\"><string name=\"filename\" value=\"mesh.obj\"/><boolean name=\"face_normals\" value=\"true\"/>\n"
        "    <transform name=\"to_world\"><scale value=\"2\"/></transform><ref id=\"wood\"/></shape>\n"
        "  <shape type=\"sphere\"><ref id=\"plastic\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"3\"/></emitter></shape>\n"
        "</scene>\n");
    expect_same_tree(scene_desc_root(old), scene_desc_root(now));
    scene_desc_destroy(old);
    scene_desc_destroy(now);

    char snake[64];
    const char *cases[][2] = {{"toWorld", "to_world"}, {"intIOR", "int_ior"}, {"sampleCount", "sample_count"},
                              {"alphaU", "alpha_u"}, {"radius", "radius"}, {"aBcD", "a_bc_d"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene_snake_case(cases[i][0], snake, sizeof snake);
        cr_expect_str_eq(snake, cases[i][1]);
    }
    /* an upgraded scene is checked like any other: a 0.6 name with no 3.0
     * counterpart is refused with its new name */
    load_fails("odd.xml", "<scene version=\"0.5.0\">\n  <shape type=\"obj\">\n"
                          "    <float name=\"maxSmoothAngle\" value=\"30\"/>\n  </shape>\n</scene>\n",
               "odd.xml", 3, "unknown parameter 'max_smooth_angle' for <shape type=\"obj\">");
}

/* ------------------------------------------------------------ instancing */
/* The image of a scene text, rendered at 24x16, 4 spp, seed 3. */
static float *render_text(const char *name, const char *text)
{
    char path[256], err[512];
    put(name, text, path, sizeof path);
    scene_options so = scene_options_default();
    so.width = 24, so.height = 16, so.spp = 4, so.seed = 3;
    scene_t *s = scene_create_from_file(path, NULL, 0, &so, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    render_options ro = {.threads = 1};
    film_t film;
    render_stats st;
    cr_assert_eq(render_scene(s, &ro, &film, &st, err, sizeof err), 0, "%s", err);
    float *px = malloc(sizeof(float) * 24 * 16 * 3);
    cr_assert_not_null(px);
    film_develop(&film, px);
    film_free(&film);
    scene_destroy(s);
    return px;
}

#define INSTANCE_HEAD                                                                                                 \
    V3 "  <sensor type=\"perspective\"><transform name=\"to_world\">"                                               \
       "<lookat origin=\"0 2 -12\" target=\"0 0 0\" up=\"0 1 0\"/></transform></sensor>\n"                           \
       "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.5\"/></emitter>\n"                             \
       "  <shape type=\"rectangle\"><transform name=\"to_world\"><translate x=\"3\" y=\"6\"/></transform>"           \
       "<emitter type=\"area\"><rgb name=\"radiance\" value=\"8\"/></emitter></shape>\n"

Test(scene_mitsuba, instances_render_as_the_shapes_written_out)
{
    /* placements exact in floating point, so the two scenes have the same
     * transforms bit for bit */
    float *inst = render_text("inst.xml", INSTANCE_HEAD
        "  <shape type=\"shapegroup\" id=\"pair\">\n"
        "    <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/>"
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8 0.2 0.1\"/></bsdf></shape>\n"
        "    <shape type=\"cube\"><transform name=\"to_world\"><scale value=\"0.5\"/><translate x=\"1\"/></transform>"
        "</shape>\n"
        "  </shape>\n"
        "  <shape type=\"instance\"><ref id=\"pair\"/></shape>\n"
        "  <shape type=\"instance\"><ref id=\"pair\"/><transform name=\"to_world\">"
        "<scale value=\"2\"/><translate x=\"-3\" y=\"1\"/></transform></shape>\n"
        "</scene>\n");
    float *flat = render_text("flat.xml", INSTANCE_HEAD
        "  <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/>"
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8 0.2 0.1\"/></bsdf></shape>\n"
        "  <shape type=\"cube\"><transform name=\"to_world\"><scale value=\"0.5\"/><translate x=\"1\"/></transform>"
        "</shape>\n"
        "  <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/><transform name=\"to_world\">"
        "<scale value=\"2\"/><translate x=\"-3\" y=\"1\"/></transform>"
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8 0.2 0.1\"/></bsdf></shape>\n"
        "  <shape type=\"cube\"><transform name=\"to_world\"><scale value=\"0.5\"/><translate x=\"1\"/>"
        "<scale value=\"2\"/><translate x=\"-3\" y=\"1\"/></transform></shape>\n"
        "</scene>\n");
    double sum = 0;
    for (int i = 0; i < 24 * 16 * 3; i++) {
        cr_assert_eq(inst[i], flat[i], "value %d: %g (instanced) vs %g (written out)", i, inst[i], flat[i]);
        sum += inst[i];
    }
    cr_assert_gt(sum, 1.0, "the scene is not black");
    free(inst);
    free(flat);

    load_fails("refshape.xml", V3 "  <shape type=\"sphere\" id=\"s\"/>\n  <shape type=\"instance\">\n"
                               "    <ref id=\"s\"/>\n  </shape>\n</scene>\n",
               "refshape.xml", 4, "only a shapegroup can be referenced");
    char err[512];
    scene_desc *d = load("glow.xml", V3 "  <sensor type=\"perspective\"/>\n  <shape type=\"shapegroup\" id=\"g\">\n"
                                        "    <shape type=\"sphere\"><emitter type=\"area\"/></shape>\n  </shape>\n"
                                        "  <shape type=\"instance\"><ref id=\"g\"/></shape>\n</scene>\n",
                         err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    cr_assert_null(scene_create(d, NULL, err, sizeof err));
    cr_assert_not_null(strstr(err, "glow.xml:4: a shape in a shapegroup cannot emit light"), "%s", err);
    scene_desc_destroy(d);
}

/* Integrators read as others with the same expectation render the same
 * numbers: ptracer as path, volpathmis as volpath (docs/scene-format.md). */
Test(scene_mitsuba, ptracer_and_volpathmis_render_as_path_and_volpath)
{
    const char *pairs[2][2] = {{"ptracer", "path"}, {"volpathmis", "volpath"}};
    for (int k = 0; k < 2; k++) {
        char a[1024], b[1024];
        const char *fmt = INSTANCE_HEAD "  <integrator type=\"%s\"><integer name=\"max_depth\" value=\"4\"/>%s"
                                        "</integrator>\n  <shape type=\"sphere\"/>\n</scene>\n";
        snprintf(a, sizeof a, fmt, pairs[k][0], k == 0 ? "<integer name=\"samples_per_pass\" value=\"64\"/>" : "");
        snprintf(b, sizeof b, fmt, pairs[k][1], "");
        float *pa = render_text("a.xml", a), *pb = render_text("b.xml", b);
        cr_assert_eq(memcmp(pa, pb, sizeof(float) * 24 * 16 * 3), 0, "%s differs from %s", pairs[k][0], pairs[k][1]);
        free(pa);
        free(pb);
    }
}

/* --spp N is the fallback for $spp: used where the scene declares no
 * <default>, beaten by one, and no error where the scene has no $spp. */
Test(scene_mitsuba, a_fallback_define_gives_way_to_the_scene)
{
    const char *uses = V3 "  <sensor type=\"perspective\"><sampler type=\"independent\">"
                          "<integer name=\"sample_count\" value=\"$spp\"/></sampler></sensor>\n</scene>\n";
    const char *declares = V3 "  <default name=\"spp\" value=\"64\"/>\n  <sensor type=\"perspective\">"
                              "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/>"
                              "</sampler></sensor>\n</scene>\n";
    const scene_define fb[] = {{"spp", "3", true}};
    char path[256], err[512];
    long long want[2] = {3, 64};
    const char *texts[2] = {uses, declares};
    for (int i = 0; i < 2; i++) {
        put("fb.xml", texts[i], path, sizeof path);
        scene_desc *d = scene_desc_create_from_file(path, fb, 1, scene_plugin_find, err, sizeof err);
        cr_assert_not_null(d, "%s", err);
        scene_obj *smp = scene_obj_child(scene_obj_child(scene_desc_root(d), SCENE_SENSOR), SCENE_SAMPLER);
        cr_expect_eq(scene_obj_int(smp, "sample_count", 0), want[i]);
        scene_desc_destroy(d);
    }
    put("none.xml", V3 "</scene>\n", path, sizeof path);
    scene_desc *d = scene_desc_create_from_file(path, fb, 1, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "an unused fallback is no error: %s", err);
    scene_desc_destroy(d);
}
