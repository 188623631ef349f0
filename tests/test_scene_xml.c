/* The scene parser: every supported element round-trips its values, and every
 * kind of bad input gives one error naming the exact file and line. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/scene.h"
#include "celadon/scene_xml.h"
#include "support/scratch_dir.h"

/* ------------------------------------------------------------- fixtures */
static char dir[64];

static void make_dir(void) { scratch_dir_make(dir, sizeof dir, "scene"); }

static void remove_dir(void) { scratch_dir_remove(dir); }

/* Writes dir/name and returns its path (static buffer per call site not
 * needed: callers copy). */
static const char *put(const char *name, const char *text)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "%s", path);
    fputs(text, f);
    fclose(f);
    return path;
}

static scene_desc *load_ok(const char *name, const char *text, const scene_define *defs, int ndefs)
{
    char path[256], err[1024] = "";
    snprintf(path, sizeof path, "%s", put(name, text));
    scene_desc *d = scene_desc_create_from_file(path, defs, ndefs, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "load failed: %s", err);
    return d;
}

/* Loads text that must fail, and checks the message begins with
 * "dir/file:line: " and contains needle. */
static void load_fails(const char *name, const char *text, const char *errfile, int line, const char *needle,
                       const scene_define *defs, int ndefs)
{
    char path[256], err[1024] = "", prefix[300];
    snprintf(path, sizeof path, "%s", put(name, text));
    scene_desc *d = scene_desc_create_from_file(path, defs, ndefs, scene_plugin_find, err, sizeof err);
    cr_assert_null(d, "expected an error for:\n%s", text);
    if (line > 0)
        snprintf(prefix, sizeof prefix, "%s/%s:%d: ", dir, errfile, line);
    else
        snprintf(prefix, sizeof prefix, "%s/%s: ", dir, errfile);
    cr_assert(strncmp(err, prefix, strlen(prefix)) == 0, "message '%s' does not start with '%s'", err, prefix);
    cr_assert_not_null(strstr(err, needle), "message '%s' lacks '%s'", err, needle);
    cr_assert_null(strchr(err, '\n'), "one line: '%s'", err);
}

TestSuite(scene_xml, .init = make_dir, .fini = remove_dir);

#define HEAD "<?xml version=\"1.0\"?>\n<scene version=\"3.0.0\">\n"

/* --------------------------------------------------------- round trips */
Test(scene_xml, every_property_type_round_trips)
{
    put("mesh.obj", "v 0 0 0\n");
    scene_desc *d = load_ok("s.xml",
        HEAD
        "  <integrator type=\"path\">\n"
        "    <integer name=\"max_depth\" value=\"-1\"/>\n"
        "    <integer name=\"rr_depth\" value=\" 7 \"/>\n"
        "    <boolean name=\"hide_emitters\" value=\"True\"/>\n"
        "  </integrator>\n"
        "  <shape type=\"sphere\" id=\"ball\">\n"                      /* line 8 */
        "    <point name=\"center\" value=\"1, -2.5,3e1\"/>\n"
        "    <float name=\"radius\" value=\"-1.5e-1\"/>\n"
        "    <boolean name=\"flip_normals\" value=\"false\"/>\n"
        "    <bsdf type=\"roughconductor\">\n"
        "      <string name=\"distribution\" value=\"ggx\"/>\n"
        "      <float name=\"alpha_u\" value=\"0.25\"/>\n"
        "      <float name=\"alpha_v\" value=\"0.5\"/>\n"
        "      <rgb name=\"eta\" value=\"0.2 0.9 1.1\"/>\n"
        "      <spectrum name=\"k\" value=\"3.5\"/>\n"
        "      <rgb name=\"specular_reflectance\" value=\"0.7\"/>\n"
        "    </bsdf>\n"
        "  </shape>\n"
        "  <shape type=\"cylinder\">\n"
        "    <point name=\"p0\" x=\"1\" z=\"2\"/>\n"
        "    <point name=\"p1\" x=\"1\" y=\"4\" z=\"2\"/>\n"
        "    <float name=\"radius\" value=\"0.5\"/>\n"
        "  </shape>\n"
        "  <shape type=\"obj\"><string name=\"filename\" value=\"mesh.obj\"/>\n"
        "    <boolean name=\"face_normals\" value=\"true\"/></shape>\n"
        "  <emitter type=\"directional\"><vector name=\"direction\" value=\"0 -1 0\"/>\n"
        "    <rgb name=\"irradiance\" value=\"1, 2, 3\"/></emitter>\n"
        "</scene>\n", NULL, 0);
    scene_obj *root = scene_desc_root(d);
    cr_assert_eq(root->cls, SCENE_SCENE);

    scene_obj *integ = scene_obj_child(root, SCENE_INTEGRATOR);
    cr_assert_str_eq(integ->type, "path");
    cr_assert_eq(scene_obj_int(integ, "max_depth", 99), -1);
    cr_assert_eq(scene_obj_int(integ, "rr_depth", 5), 7);
    cr_assert_eq(scene_obj_bool(integ, "hide_emitters", false), true);

    scene_obj *shapes[4];
    cr_assert_eq(scene_obj_children(root, SCENE_SHAPE, shapes, 4), 3);
    scene_obj *ball = shapes[0];
    cr_assert_str_eq(ball->type, "sphere");
    cr_assert_str_eq(ball->id, "ball");
    cr_assert_eq(ball->line, 8);
    cr_assert_str_eq(ball->file, put("s.xml", "") /* same path */);
    vec3 c = scene_obj_point(ball, "center", v3(0, 0, 0));
    cr_assert(c.x == 1 && c.y == -2.5 && c.z == 30);
    cr_assert_eq(scene_obj_float(ball, "radius", 1), -0.15);
    cr_assert_eq(scene_obj_bool(ball, "flip_normals", true), false);
    cr_assert_eq(scene_obj_prop(ball, "center")->type, SCENE_POINT);

    scene_obj *b = scene_obj_child(ball, SCENE_BSDF);
    cr_assert_str_eq(b->type, "roughconductor");
    cr_assert_str_eq(scene_obj_string(b, "distribution", "beckmann"), "ggx");
    cr_assert_eq(scene_obj_float(b, "alpha_u", 0.1), 0.25);
    cr_assert_eq(scene_obj_float(b, "alpha_v", 0.1), 0.5);
    cr_assert_eq(scene_obj_float(b, "alpha", 0.1), 0.1, "absent: default");
    cr_assert(scene_obj_has(b, "alpha_u") && !scene_obj_has(b, "alpha"));
    scene_rgb eta = scene_obj_rgb(b, "eta", (scene_rgb){0, 0, 0});
    cr_assert(eta.r == 0.2 && eta.g == 0.9 && eta.b == 1.1);
    scene_rgb k = scene_obj_rgb(b, "k", (scene_rgb){0, 0, 0});
    cr_assert(k.r == 3.5 && k.g == 3.5 && k.b == 3.5, "a constant spectrum is gray");
    cr_assert_eq(scene_obj_prop(b, "k")->type, SCENE_SPECTRUM);
    scene_rgb sr = scene_obj_rgb(b, "specular_reflectance", (scene_rgb){0, 0, 0});
    cr_assert(sr.r == 0.7 && sr.g == 0.7 && sr.b == 0.7, "one rgb value is gray");

    vec3 p0 = scene_obj_point(shapes[1], "p0", v3(9, 9, 9)), p1 = scene_obj_point(shapes[1], "p1", v3(9, 9, 9));
    cr_assert(p0.x == 1 && p0.y == 0 && p0.z == 2, "missing y is 0");
    cr_assert(p1.x == 1 && p1.y == 4 && p1.z == 2);

    char want[300];
    snprintf(want, sizeof want, "%s/mesh.obj", dir);
    cr_assert_str_eq(scene_obj_string(shapes[2], "filename", ""), want, "resolved against the scene folder");
    cr_assert_eq(scene_obj_bool(shapes[2], "face_normals", false), true);

    scene_obj *e = scene_obj_child(root, SCENE_EMITTER);
    vec3 dir3 = scene_obj_vector(e, "direction", v3(0, 0, 0));
    cr_assert(dir3.x == 0 && dir3.y == -1 && dir3.z == 0);
    scene_rgb irr = scene_obj_rgb(e, "irradiance", (scene_rgb){0, 0, 0});
    cr_assert(irr.r == 1 && irr.g == 2 && irr.b == 3);

    char msg[512];
    cr_assert_eq(scene_obj_unconsumed(root, msg, sizeof msg), 1, "p0/p1 radius of the cylinder unread");
    cr_assert_not_null(strstr(msg, "<shape type=\"cylinder\"> property 'radius' was not used"), "%s", msg);
    scene_obj_float(shapes[1], "radius", 1);
    cr_assert_eq(scene_obj_unconsumed(root, msg, sizeof msg), 0, "%s", msg);
    scene_desc_destroy(d);
}

Test(scene_xml, transforms_compose_in_document_order)
{
    scene_desc *d = load_ok("t.xml",
        HEAD
        "  <shape type=\"rectangle\">\n"
        "    <transform name=\"to_world\">\n"
        "      <scale value=\"2\"/>\n"
        "      <translate x=\"1\"/>\n"
        "      <rotate z=\"1\" angle=\"90\"/>\n"
        "    </transform>\n"
        "  </shape>\n"
        "  <shape type=\"disk\">\n"
        "    <transform name=\"to_world\">\n"
        "      <matrix value=\"0 -1 0 5  1 0 0 6  0 0 1 7  0 0 0 1\"/>\n"
        "      <scale x=\"2\" y=\"3\"/>\n"
        "      <matrix value=\"1 0 0, 0 1 0, 0 0 -1\"/>\n"
        "    </transform>\n"
        "  </shape>\n"
        "  <shape type=\"cube\">\n"
        "    <transform name=\"to_world\">\n"
        "      <rotate value=\"0 1 0\" angle=\"-90\"/>\n"
        "      <scale value=\"1, 2, 3\"/>\n"
        "      <translate value=\"-1, 3, 4\"/>\n"
        "    </transform>\n"
        "  </shape>\n"
        "</scene>\n", NULL, 0);
    scene_obj *s[3];
    cr_assert_eq(scene_obj_children(scene_desc_root(d), SCENE_SHAPE, s, 3), 3);

    /* scale 2, then +x 1, then 90 deg about z: p -> R(2p + (1,0,0)).
     * Hand-computed: [[0,-2,0,0],[2,0,0,1],[0,0,2,0]]. */
    transform4 a = scene_obj_transform(s[0], "to_world");
    const double wa[16] = {0, -2, 0, 0, 2, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 1};
    transform4 want;
    cr_assert_eq(transform_from_rows(wa, &want), 0);
    cr_assert_leq(transform_max_diff(&a, &want), 1e-15);

    /* M3 · S · M1 with M1 the first matrix, S = diag(2,3,1), M3 = diag(1,1,-1):
     * rows of S·M1 = [0,-2,0,10],[3,0,0,18],[0,0,1,7]; flipping z negates row 3. */
    transform4 b = scene_obj_transform(s[1], "to_world");
    const double wb[16] = {0, -2, 0, 10, 3, 0, 0, 18, 0, 0, -1, -7, 0, 0, 0, 1};
    cr_assert_eq(transform_from_rows(wb, &want), 0);
    cr_assert_leq(transform_max_diff(&b, &want), 1e-15);

    /* rotate -90 about y maps (x,y,z) -> (-z, y, x); scale (1,2,3); translate:
     * p=(1,1,1) -> (-1,1,1) -> (-1,2,3) -> (-2,5,7). */
    transform4 c = scene_obj_transform(s[2], "to_world");
    vec3 q = transform_point(&c, v3(1, 1, 1));
    cr_assert(fabs(q.x + 2) < 1e-15 && fabs(q.y - 5) < 1e-15 && fabs(q.z - 7) < 1e-15, "%g %g %g", q.x, q.y, q.z);
    transform4 none = scene_obj_transform(scene_desc_root(d), "to_world");
    transform4 id = transform_identity();
    cr_assert_eq(transform_max_diff(&none, &id), 0, "absent transform is the identity");
    scene_desc_destroy(d);
}

Test(scene_xml, sensor_film_sampler_and_lookat_basis)
{
    scene_desc *d = load_ok("cam.xml",
        HEAD
        "  <sensor type=\"perspective\">\n"
        "    <float name=\"fov\" value=\"45\"/>\n"
        "    <string name=\"fov_axis\" value=\"smaller\"/>\n"
        "    <float name=\"near_clip\" value=\"0.1\"/>\n"
        "    <float name=\"far_clip\" value=\"100\"/>\n"
        "    <transform name=\"to_world\">\n"
        "      <lookat origin=\"0, 1, 5\" target=\"0, 1, 0\" up=\"0, 1, 0\"/>\n"
        "    </transform>\n"
        "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"64\"/>\n"
        "      <integer name=\"seed\" value=\"3\"/></sampler>\n"
        "    <film type=\"hdrfilm\">\n"
        "      <integer name=\"width\" value=\"320\"/><integer name=\"height\" value=\"240\"/>\n"
        "      <string name=\"pixel_format\" value=\"rgb\"/>\n"
        "      <string name=\"component_format\" value=\"float32\"/>\n"
        "      <rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/></rfilter>\n"
        "    </film>\n"
        "  </sensor>\n"
        "</scene>\n", NULL, 0);
    scene_obj *sensor = scene_obj_child(scene_desc_root(d), SCENE_SENSOR);
    cr_assert_str_eq(sensor->type, "perspective");
    cr_assert_eq(scene_obj_float(sensor, "fov", 0), 45);
    cr_assert_str_eq(scene_obj_string(sensor, "fov_axis", "x"), "smaller");
    cr_assert_eq(scene_obj_float(sensor, "near_clip", 0), 0.1);
    cr_assert_eq(scene_obj_float(sensor, "far_clip", 0), 100);
    transform4 m = scene_obj_transform(sensor, "to_world");
    /* Looking down -z from (0,1,5) with +y up: local z -> -z, local y -> +y,
     * local x (left) -> up x dir = (0,1,0) x (0,0,-1) = (-1,0,0). */
    vec3 z = transform_vector(&m, v3(0, 0, 1)), y = transform_vector(&m, v3(0, 1, 0)),
         x = transform_vector(&m, v3(1, 0, 0)), o = transform_point(&m, v3(0, 0, 0));
    cr_assert(z.x == 0 && z.y == 0 && z.z == -1);
    cr_assert(y.x == 0 && y.y == 1 && y.z == 0);
    cr_assert(x.x == -1 && x.y == 0 && x.z == 0);
    cr_assert(o.x == 0 && o.y == 1 && o.z == 5);

    scene_obj *sampler = scene_obj_child(sensor, SCENE_SAMPLER);
    cr_assert_eq(scene_obj_int(sampler, "sample_count", 4), 64);
    cr_assert_eq(scene_obj_int(sampler, "seed", 0), 3);
    scene_obj *film = scene_obj_child(sensor, SCENE_FILM);
    cr_assert_eq(scene_obj_int(film, "width", 768), 320);
    cr_assert_eq(scene_obj_int(film, "height", 576), 240);
    scene_obj *rf = scene_obj_child(film, SCENE_RFILTER);
    cr_assert_str_eq(rf->type, "gaussian");
    cr_assert_eq(scene_obj_float(rf, "stddev", 0.5), 0.25);
    scene_desc_destroy(d);
}

Test(scene_xml, defaults_and_overrides)
{
    const char *text =
        HEAD
        "  <default name=\"spp\" value=\"16\"/>\n"
        "  <default name=\"res\" value=\"64\"/>\n"
        "  <default name=\"kind\" value=\"independent\"/>\n"
        "  <sensor type=\"perspective\">\n"
        "    <sampler type=\"$kind\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
        "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$res$res\"/></film>\n"
        "  </sensor>\n"
        "</scene>\n";
    scene_desc *d = load_ok("p.xml", text, NULL, 0);
    scene_obj *sensor = scene_obj_child(scene_desc_root(d), SCENE_SENSOR);
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_SAMPLER), "sample_count", 0), 16);
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_FILM), "width", 0), 6464);
    scene_desc_destroy(d);

    const scene_define defs[] = {{"spp", "256", false}, {"res", "3", false}};
    d = load_ok("p.xml", text, defs, 2);
    sensor = scene_obj_child(scene_desc_root(d), SCENE_SENSOR);
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_SAMPLER), "sample_count", 0), 256, "-D wins");
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_FILM), "width", 0), 33);
    scene_desc_destroy(d);

    /* A parameter with no default must come from -D. */
    const char *bare = HEAD "  <shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>\n</scene>\n";
    const scene_define r[] = {{"r", "2.5", false}};
    d = load_ok("bare.xml", bare, r, 1);
    cr_assert_eq(scene_obj_float(scene_obj_child(scene_desc_root(d), SCENE_SHAPE), "radius", 0), 2.5);
    scene_desc_destroy(d);
    load_fails("bare.xml", bare, "bare.xml", 3, "undefined parameter '$r'", NULL, 0);
    const scene_define typo[] = {{"r", "1", false}, {"rr", "2", false}};
    load_fails("bare.xml", bare, "bare.xml", 0, "-D rr=2: the scene has no parameter", typo, 2);
}

Test(scene_xml, include_and_references)
{
    cr_assert_eq(mkdir(strcat(strcpy((char[128]){0}, dir), "/sub"), 0755), 0);
    put("sub/tex.png", "not really a png; only existence is checked");
    put("sub/materials.xml",
        HEAD
        "  <default name=\"gray\" value=\"0.25\"/>\n"
        "  <texture type=\"bitmap\" id=\"wood\">\n"
        "    <string name=\"filename\" value=\"tex.png\"/>\n"
        "    <string name=\"wrap_mode\" value=\"clamp\"/>\n"
        "  </texture>\n"
        "  <bsdf type=\"diffuse\" id=\"matte\"><ref name=\"reflectance\" id=\"wood\"/></bsdf>\n"
        "</scene>\n");
    scene_desc *d = load_ok("main.xml",
        HEAD
        "  <include filename=\"sub/materials.xml\"/>\n"
        "  <shape type=\"sphere\"><ref id=\"matte\"/></shape>\n"
        "  <shape type=\"cube\">\n"
        "    <bsdf type=\"twosided\"><ref id=\"matte\"/></bsdf>\n"
        "  </shape>\n"
        "  <shape type=\"disk\"><bsdf type=\"plastic\">\n"
        "    <rgb name=\"diffuse_reflectance\" value=\"$gray\"/>\n"
        "    <string name=\"int_ior\" value=\"bk7\"/>\n"
        "    <float name=\"ext_ior\" value=\"1.0\"/>\n"
        "    <texture type=\"checkerboard\" name=\"specular_reflectance\">\n"
        "      <rgb name=\"color0\" value=\"0.1\"/><ref name=\"color1\" id=\"wood\"/>\n"
        "    </texture>\n"
        "  </bsdf></shape>\n"
        "</scene>\n", NULL, 0);
    scene_obj *root = scene_desc_root(d), *s[3];
    cr_assert_eq(scene_obj_children(root, SCENE_SHAPE, s, 3), 3);
    scene_obj *matte = scene_obj_child(s[0], SCENE_BSDF);
    cr_assert_str_eq(matte->id, "matte");
    cr_assert_eq(matte->line, 8);
    cr_assert_not_null(strstr(matte->file, "sub/materials.xml"), "%s", matte->file);
    scene_obj *wood = scene_obj_texture(matte, "reflectance");
    cr_assert_not_null(wood);
    cr_assert_str_eq(wood->type, "bitmap");
    char want[300];
    snprintf(want, sizeof want, "%s/sub/tex.png", dir);
    cr_assert_str_eq(scene_obj_string(wood, "filename", ""), want, "relative to the including file's folder");
    scene_rgb none = scene_obj_rgb(matte, "reflectance", (scene_rgb){-1, -1, -1});
    cr_assert_eq(none.r, -1, "a texture is not a constant color");

    scene_obj *two = scene_obj_child(s[1], SCENE_BSDF);
    cr_assert_str_eq(two->type, "twosided");
    cr_assert_eq(scene_obj_child(two, SCENE_BSDF), matte, "shared by reference");

    scene_obj *pl = scene_obj_child(s[2], SCENE_BSDF);
    scene_rgb dr = scene_obj_rgb(pl, "diffuse_reflectance", (scene_rgb){0, 0, 0});
    cr_assert_eq(dr.g, 0.25, "<default> from an included file");
    cr_assert_eq(scene_obj_prop(pl, "int_ior")->type, SCENE_STRING);
    cr_assert_eq(scene_obj_prop(pl, "ext_ior")->type, SCENE_FLOAT);
    scene_obj *check = scene_obj_texture(pl, "specular_reflectance");
    cr_assert_str_eq(check->type, "checkerboard");
    cr_assert_eq(scene_obj_rgb(check, "color0", (scene_rgb){0, 0, 0}).b, 0.1);
    cr_assert_eq(scene_obj_texture(check, "color1"), wood);
    scene_desc_destroy(d);
}

Test(scene_xml, parse_from_memory_and_sor_shape)
{
    put("profile.json", "{}");
    char path[256], err[512];
    snprintf(path, sizeof path, "%s/virtual.xml", dir);
    const char *text = HEAD
        "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
        "    <float name=\"height\" value=\"0.32\"/><boolean name=\"caps\" value=\"false\"/>\n"
        "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"4\"/></emitter>\n"
        "  </shape>\n"
        "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.5\"/></emitter>\n"
        "</scene>\n";
    scene_desc *d = scene_desc_create_from_text(text, strlen(text), path, NULL, 0, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    scene_obj *sor = scene_obj_child(scene_desc_root(d), SCENE_SHAPE);
    cr_assert_eq(scene_obj_float(sor, "height", 1), 0.32);
    cr_assert_eq(scene_obj_bool(sor, "caps", true), false);
    cr_assert_str_eq(scene_obj_child(sor, SCENE_EMITTER)->type, "area");
    cr_assert_eq(scene_obj_rgb(scene_obj_child(scene_desc_root(d), SCENE_EMITTER), "radiance",
                               (scene_rgb){0, 0, 0}).r, 0.5);
    scene_desc_destroy(d);
}

/* ------------------------------------------------------------- errors */
Test(scene_xml, malformed_xml)
{
    load_fails("bad.xml", HEAD "  <shape type=\"sphere\">\n  </shap>\n</scene>\n", "bad.xml", 4, "malformed XML", NULL,
               0);
    load_fails("nover.xml", "<scene>\n</scene>\n", "nover.xml", 1, "needs a 'version' attribute", NULL, 0);
    load_fails("new.xml", "<scene version=\"4.0.0\">\n</scene>\n", "new.xml", 1, "not supported", NULL, 0);
    load_fails("root.xml", "<?xml version=\"1.0\"?>\n<shape type=\"sphere\"/>\n", "root.xml", 2, "root element", NULL,
               0);
    load_fails("text.xml", HEAD "  <shape type=\"sphere\">radius</shape>\n</scene>\n", "text.xml", 3,
               "unexpected text", NULL, 0);
}

Test(scene_xml, unknown_things)
{
    load_fails("a.xml", HEAD "\n  <bsdf type=\"velvet\"/>\n</scene>\n", "a.xml", 4,
               "unknown plugin 'velvet' for <bsdf>", NULL, 0);
    load_fails("b.xml", HEAD "  <fog type=\"homogeneous\"/>\n</scene>\n", "b.xml", 3, "unknown tag <fog>", NULL, 0);
    /* a medium is declared at the top with an id, and placed by reference */
    load_fails("b2.xml", HEAD "  <medium type=\"homogeneous\"/>\n</scene>\n", "b2.xml", 3,
               "<scene> cannot contain a <medium>", NULL, 0);
    load_fails("c.xml", HEAD "  <bsdf type=\"diffuse\">\n    <rgb name=\"albedo\" value=\"1\"/>\n  </bsdf>\n</scene>\n",
               "c.xml", 4, "unknown parameter 'albedo' for <bsdf type=\"diffuse\">", NULL, 0);
    load_fails("d.xml", HEAD "  <shape type=\"sphere\" color=\"red\"/>\n</scene>\n", "d.xml", 3,
               "unexpected attribute 'color'", NULL, 0);
    load_fails("e.xml", HEAD "  <shape type=\"sphere\">\n    <integer name=\"radius\" value=\"2\"/>\n  </shape>\n</scene>\n",
               "e.xml", 4, "must be <float>, not <integer>", NULL, 0);
    load_fails("f.xml", HEAD "  <sensor type=\"perspective\">\n    <string name=\"fov_axis\" value=\"z\"/>\n"
               "  </sensor>\n</scene>\n", "f.xml", 4, "bad value 'z' for 'fov_axis'", NULL, 0);
    load_fails("g.xml", HEAD "  <shape type=\"sphere\"><float name=\"radius\" value=\"1\"/>\n"
               "    <float name=\"radius\" value=\"2\"/></shape>\n</scene>\n", "g.xml", 4, "given twice", NULL, 0);
    load_fails("h.xml", HEAD "  <emitter type=\"area\"/>\n</scene>\n", "h.xml", 3, "must be nested in a <shape>",
               NULL, 0);
    load_fails("i.xml", HEAD "  <shape type=\"cube\">\n    <bsdf type=\"diffuse\"/>\n    <bsdf type=\"diffuse\"/>\n"
               "  </shape>\n</scene>\n", "i.xml", 5, "at most 1 <bsdf>", NULL, 0);
    load_fails("j.xml", HEAD "  <bsdf type=\"twosided\">\n  </bsdf>\n</scene>\n", "j.xml", 3,
               "needs at least 1 nested <bsdf>", NULL, 0);
    load_fails("k.xml", HEAD "  <bsdf type=\"diffuse\">\n    <spectrum name=\"reflectance\" value=\"400:0.1, 5x00:0.2\"/>\n"
               "  </bsdf>\n</scene>\n", "k.xml", 4, "bad wavelength:value pair", NULL, 0);
    load_fails("l.xml", HEAD "  <shape type=\"obj\"/>\n</scene>\n", "l.xml", 3, "needs the parameter 'filename'",
               NULL, 0);
    load_fails("m.xml", HEAD "  <bsdf type=\"diffuse\">\n    <texture type=\"checkerboard\"/>\n  </bsdf>\n</scene>\n",
               "m.xml", 4, "needs a name", NULL, 0);
    load_fails("n.xml", HEAD "  <emitter type=\"point\"><point name=\"position\" value=\"1 2 3\"/>\n"
               "    <transform name=\"to_world\"/></emitter>\n</scene>\n", "n.xml", 4,
               "takes 'position' or 'to_world', not both", NULL, 0);
}

Test(scene_xml, bad_numbers)
{
    load_fails("a.xml", HEAD "  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"1.5x\"/>\n  </shape>\n</scene>\n",
               "a.xml", 4, "bad number '1.5x'", NULL, 0);
    load_fails("b.xml", HEAD "  <integrator type=\"path\">\n    <integer name=\"max_depth\" value=\"2.5\"/>\n"
               "  </integrator>\n</scene>\n", "b.xml", 4, "bad integer '2.5'", NULL, 0);
    load_fails("c.xml", HEAD "  <shape type=\"sphere\">\n    <float name=\"radius\" value=\"nan\"/>\n  </shape>\n</scene>\n",
               "c.xml", 4, "bad number 'nan'", NULL, 0);
    load_fails("d.xml", HEAD "  <shape type=\"sphere\">\n    <point name=\"center\" value=\"1, 2\"/>\n  </shape>\n</scene>\n",
               "d.xml", 4, "not three numbers", NULL, 0);
    load_fails("e.xml", HEAD "  <bsdf type=\"diffuse\">\n    <rgb name=\"reflectance\" value=\"0.1, 0.2\"/>\n"
               "  </bsdf>\n</scene>\n", "e.xml", 4, "bad color", NULL, 0);
    load_fails("f.xml", HEAD "  <integrator type=\"path\">\n    <boolean name=\"hide_emitters\" value=\"yes\"/>\n"
               "  </integrator>\n</scene>\n", "f.xml", 4, "bad boolean 'yes'", NULL, 0);
    load_fails("g.xml", HEAD "  <shape type=\"cube\"><transform name=\"to_world\">\n\n"
               "    <rotate x=\"1\" angle=\"ninety\"/></transform></shape>\n</scene>\n", "g.xml", 5,
               "bad number 'ninety'", NULL, 0);
    load_fails("h.xml", HEAD "  <shape type=\"cube\"><transform name=\"to_world\">\n"
               "    <scale x=\"0\"/></transform></shape>\n</scene>\n", "h.xml", 4, "nonzero", NULL, 0);
    load_fails("h2.xml", HEAD "  <shape type=\"cube\"><transform name=\"to_world\">\n"
               "    <scale value=\"2\" y=\"3\"/></transform></shape>\n</scene>\n", "h2.xml", 4, "not both", NULL, 0);
    load_fails("i.xml", HEAD "  <shape type=\"cube\"><transform name=\"to_world\">\n"
               "    <matrix value=\"1 2 3\"/></transform></shape>\n</scene>\n", "i.xml", 4, "16 or 9 numbers", NULL, 0);
    load_fails("j.xml", HEAD "  <sensor type=\"perspective\"><transform name=\"to_world\">\n"
               "    <lookat origin=\"0 0 0\" target=\"0 1 0\" up=\"0 1 0\"/></transform></sensor>\n</scene>\n", "j.xml",
               4, "degenerate", NULL, 0);
}

Test(scene_xml, missing_files_refs_and_cycles)
{
    load_fails("a.xml", HEAD "  <shape type=\"obj\">\n    <string name=\"filename\" value=\"nope.obj\"/>\n"
               "  </shape>\n</scene>\n", "a.xml", 4, "file 'nope.obj' not found", NULL, 0);
    load_fails("b.xml", HEAD "  <shape type=\"sphere\">\n    <ref id=\"ghost\"/>\n  </shape>\n</scene>\n", "b.xml", 4,
               "<ref id=\"ghost\">: no object has this id", NULL, 0);
    load_fails("c.xml", HEAD "  <texture type=\"checkerboard\" id=\"t\"/>\n  <shape type=\"sphere\">\n"
               "    <ref id=\"t\"/>\n  </shape>\n</scene>\n", "c.xml", 5, "needs a name", NULL, 0);
    load_fails("d.xml", HEAD "  <bsdf type=\"diffuse\" id=\"m\"/>\n  <bsdf type=\"diffuse\" id=\"m\"/>\n</scene>\n",
               "d.xml", 4, "duplicate id 'm'", NULL, 0);
    load_fails("e.xml", HEAD "  <bsdf type=\"twosided\" id=\"loop\">\n    <ref id=\"loop\"/>\n  </bsdf>\n</scene>\n",
               "e.xml", 3, "reference cycle", NULL, 0);
    load_fails("f.xml", HEAD "  <include filename=\"missing.xml\"/>\n</scene>\n", "f.xml", 3,
               "cannot read included file 'missing.xml'", NULL, 0);
    char err[512], sub[128];
    snprintf(sub, sizeof sub, "%s/folder.xml", dir);
    cr_assert_eq(mkdir(sub, 0755), 0);
    cr_assert_null(scene_desc_create_from_file(sub, NULL, 0, scene_plugin_find, err, sizeof err));
    cr_assert_not_null(strstr(err, "is a folder, not a file"), "%s", err);
    cr_assert_null(scene_desc_create_from_file("/nonexistent/scene.xml", NULL, 0, scene_plugin_find, err, sizeof err));
    cr_assert_str_eq(err, "/nonexistent/scene.xml: cannot open: No such file or directory");
    /* x.xml includes y.xml which includes x.xml again: the error is in y.xml. */
    put("y.xml", HEAD "\n  <include filename=\"x.xml\"/>\n</scene>\n");
    load_fails("x.xml", HEAD "  <include filename=\"y.xml\"/>\n</scene>\n", "y.xml", 4,
               "include cycle: 'x.xml' is already being included", NULL, 0);
    /* An error inside an included file names that file. */
    put("inner.xml", HEAD "  <bsdf type=\"diffuse\">\n    <float name=\"reflectance\" value=\"oops\"/>\n"
        "  </bsdf>\n</scene>\n");
    load_fails("outer.xml", HEAD "  <include filename=\"inner.xml\"/>\n</scene>\n", "inner.xml", 4, "bad number 'oops'",
               NULL, 0);
}

/* The bundled fixture scene (also valid Mitsuba 3) loads and is fully read
 * by a consumer that asks for every property it holds. */
Test(scene_xml, bundled_studio_scene)
{
    char err[1024];
    const scene_define defs[] = {{"spp", "4", false}};
    scene_desc *d = scene_desc_create_from_file("tests/data/scenes/studio.xml", defs, 1, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    scene_obj *root = scene_desc_root(d), *shapes[3];
    scene_obj *sensor = scene_obj_child(root, SCENE_SENSOR);
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_SAMPLER), "sample_count", 0), 4);
    cr_assert_eq(scene_obj_int(scene_obj_child(sensor, SCENE_FILM), "width", 0), 160);
    cr_assert_eq(scene_obj_children(root, SCENE_SHAPE, shapes, 3), 3);
    /* rotate -90 about x then scale 5: the rectangle's normal +z becomes +y. */
    transform4 m = scene_obj_transform(shapes[0], "to_world");
    vec3 n = v3_norm(transform_normal(&m, v3(0, 0, 1)));
    cr_assert(fabs(n.y - 1) < 1e-15, "%g %g %g", n.x, n.y, n.z);
    scene_obj *floor = scene_obj_child(shapes[0], SCENE_BSDF);
    cr_assert_str_eq(floor->id, "floor");
    scene_obj *checker = scene_obj_texture(floor, "reflectance");
    cr_assert_str_eq(checker->type, "checkerboard");
    transform4 uv = scene_obj_transform(checker, "to_uv");
    cr_assert_eq(transform_point(&uv, v3(1, 1, 0)).x, 8);
    /* The disk light: rotate +90 about x, then up 3: it faces down (-y). */
    transform4 lm = scene_obj_transform(shapes[2], "to_world");
    vec3 ln = v3_norm(transform_normal(&lm, v3(0, 0, 1)));
    cr_assert(fabs(ln.y + 1) < 1e-15 && transform_point(&lm, v3(0, 0, 0)).y == 3);
    cr_assert_eq(scene_obj_rgb(scene_obj_child(shapes[2], SCENE_EMITTER), "radiance", (scene_rgb){0, 0, 0}).g, 6);
    scene_desc_destroy(d);
}

/* The bundled Cornell box: every wall faces into the room, and the light
 * faces down, as computed from the transforms the file gives. */
Test(scene_xml, bundled_cbox_walls_face_inward)
{
    char err[1024];
    scene_desc *d = scene_desc_create_from_file("tests/data/scenes/cbox.xml", NULL, 0, scene_plugin_find, err, sizeof err);
    cr_assert_not_null(d, "%s", err);
    scene_obj *root = scene_desc_root(d), *shapes[16];
    int n = scene_obj_children(root, SCENE_SHAPE, shapes, 16);
    cr_assert_eq(n, 8);
    int walls = 0;
    for (int i = 0; i < n; i++) {
        if (strcmp(shapes[i]->type, "rectangle") != 0)
            continue;
        transform4 m = scene_obj_transform(shapes[i], "to_world");
        vec3 c = transform_point(&m, v3(0, 0, 0)), nn = v3_norm(transform_normal(&m, v3(0, 0, 1)));
        /* The centre lies on the box surface (one coordinate at +-1, or the
         * light just below the ceiling) and the normal points to the origin. */
        cr_assert_lt(v3_dot(nn, c), -0.98, "%s faces away from the room", shapes[i]->id);
        cr_assert_float_eq(v3_dot(nn, v3_neg(v3_norm(c))), 1.0, 1e-12, "%s", shapes[i]->id);
        walls++;
    }
    cr_assert_eq(walls, 6);
    scene_obj *sensor = scene_obj_child(root, SCENE_SENSOR);
    cr_assert_str_eq(scene_obj_child(root, SCENE_INTEGRATOR)->type, "path");
    cr_assert_eq(scene_obj_bool(scene_obj_child(sensor, SCENE_FILM), "sample_border", false), true);
    cr_assert_str_eq(scene_obj_child(shapes[7], SCENE_BSDF)->type, "dielectric");
    scene_desc_destroy(d);
}
