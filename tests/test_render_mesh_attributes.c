/* Mesh attributes (PLY properties beyond positions, normals and uvs) read
 * as Mitsuba names them and looked up by the `mesh_attribute` texture: a
 * square of two triangles whose face property weight_0 is 0.25 and 0.75 and
 * whose vertices carry red green blue, facing an orthographic camera under
 * a white environment (a diffuse surface there has the radiance of its
 * reflectance): each triangle shows its face value; the vertex colour is
 * interpolated linearly across the square. */
#include <math.h>

#include "test_render_util.h"

static const char *square_ply = "ply\nformat ascii 1.0\nelement vertex 4\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "property float red\nproperty float green\nproperty float blue\n"
                                "element face 2\nproperty list uchar int vertex_indices\nproperty float weight_0\n"
                                "end_header\n"
                                "-1 -1 0 0 0 1\n1 -1 0 1 0 1\n1 1 0 1 1 1\n-1 1 0 0 1 1\n"
                                "3 0 1 2 0.25\n3 0 2 3 0.75\n";

static const char *scene_xml =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>\n"
    "  <sensor type=\"orthographic\">\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"64\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/>"
    "<rfilter type=\"box\"/></film>\n"
    "  </sensor>\n"
    "  <emitter type=\"constant\"/>\n"
    "  <shape type=\"ply\"><string name=\"filename\" value=\"square.ply\"/>\n"
    "    <bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\">"
    "<string name=\"name\" value=\"%s\"/></texture></bsdf></shape>\n"
    "</scene>\n";

/* The 16 x 16 RGB image with the reflectance from attribute name. */
static float *render_square(const char *name)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256], xml[2048];
    render_write_file(&f, "square.ply", square_ply, path, sizeof path);
    snprintf(xml, sizeof xml, scene_xml, name);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h;
    float *rgb = render_to_rgb(path, 9, &w, &h);
    cr_assert(w == 16 && h == 16);
    render_fixture_close(&f);
    return rgb;
}

Test(render_mesh_attributes, face_values_fill_their_triangles)
{
    float *px = render_square("face_weight");
    /* Pixels away from the diagonal lie in one triangle: the two means
     * (the image may run either way, so the diagonal is the one that splits
     * the values most). */
    double sum[2][2] = {{0, 0}, {0, 0}};
    int n[2][2] = {{0, 0}, {0, 0}};
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++)
            for (int diag = 0; diag < 2; diag++) {
                int d = diag ? x - y : x + y - 15;
                if (abs(d) < 2)
                    continue;
                sum[diag][d > 0] += px[3 * (y * 16 + x)];
                n[diag][d > 0]++;
            }
    int k = fabs(sum[0][0] / n[0][0] - sum[0][1] / n[0][1]) > fabs(sum[1][0] / n[1][0] - sum[1][1] / n[1][1]) ? 0 : 1;
    double sumk[2] = {sum[k][0], sum[k][1]};
    int nk[2] = {n[k][0], n[k][1]};
    double a = sumk[0] / nk[0], b = sumk[1] / nk[1], lo = fmin(a, b), hi = fmax(a, b);
    cr_expect_float_eq(lo, 0.25, 0.01, "one triangle: %g", lo);
    cr_expect_float_eq(hi, 0.75, 0.02, "the other: %g", hi);
    free(px);
}

Test(render_mesh_attributes, vertex_values_are_interpolated)
{
    float *px = render_square("vertex_color");
    /* red = (x + 1) / 2 across, green = (y + 1) / 2 up, blue 1: column means
     * of red are linear in the column (either way round). */
    double col[16] = {0}, blue = 0.0;
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            col[x] += px[3 * (y * 16 + x)] / 16.0;
            blue += px[3 * (y * 16 + x) + 2] / 256.0;
        }
    bool rising = col[15] > col[0];
    double worst = 0.0;
    for (int x = 0; x < 16; x++) {
        double want = (x + 0.5) / 16.0;
        worst = fmax(worst, fabs(col[x] - (rising ? want : 1.0 - want)));
    }
    cr_expect_lt(worst, 0.03, "red off its ramp by %g", worst);
    cr_expect_float_eq(blue, 1.0, 0.02, "blue %g", blue);
    free(px);
}

/* A mesh_attribute texture on a surface without that attribute (another
 * shape, or a mesh that lacks it) is refused in one line naming the
 * texture's file:line and the shape, as Mitsuba refuses the scene. */
Test(render_mesh_attributes, a_missing_attribute_is_refused)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256], xml[2048], err[1024];
    render_write_file(&f, "square.ply", square_ply, path, sizeof path);
    snprintf(xml, sizeof xml, scene_xml, "vertex_weight");
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_expect_null(s);
    cr_expect(strstr(err, "scene.xml:10:") && strstr(err, "<shape type=\"ply\"> at line 9") &&
                  strstr(err, "'vertex_weight'") && !strchr(err, '\n'),
              "%s", err);
    scene_destroy(s);
    static const char *sphere = "<scene version=\"3.0.0\">\n  <sensor type=\"orthographic\"/>\n"
                                "  <shape type=\"sphere\"><bsdf type=\"twosided\"><bsdf type=\"diffuse\">\n"
                                "    <texture type=\"mesh_attribute\" name=\"reflectance\">"
                                "<string name=\"name\" value=\"face_weight\"/></texture>\n"
                                "  </bsdf></bsdf></shape>\n</scene>\n";
    render_write_file(&f, "sphere.xml", sphere, path, sizeof path);
    s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_expect_null(s);
    cr_expect(strstr(err, "sphere.xml:4:") && strstr(err, "<shape type=\"sphere\"> at line 3") &&
                  strstr(err, "'face_weight'"),
              "%s", err);
    scene_destroy(s);
    render_fixture_close(&f);
}
