/* The obj and ply readers and the canonical shapes, through scene building:
 * triangle counts, world areas after to_world, smooth normals and uvs. */
#include "render/scene_impl.h"
#include "test_render_util.h"

static scene_t *load_one(render_fixture *f, const char *shape)
{
    char xml[2048], path[256], err[512];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><sensor type=\"perspective\"/>%s</scene>", shape);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    cr_assert_eq(s->shapes.count, 1);
    cr_assert(s->shapes.items[0].is_mesh);
    return s;
}

static void expect_mesh(render_fixture *f, const char *shape, int tris, double area, int has_uv)
{
    scene_t *s = load_one(f, shape);
    shape_t *sh = &s->shapes.items[0];
    cr_expect_eq(sh->mesh.n_tris, tris, "%s: %d triangles", shape, sh->mesh.n_tris);
    cr_expect(has_uv ? sh->mesh.uv != NULL : sh->mesh.uv == NULL, "%s: uv", shape);
    cr_assert_eq(shape_prepare_sampling(sh), 0);
    cr_expect_float_eq(sh->mesh.area, area, 1e-6 * area, "%s: area %g, want %g", shape, sh->mesh.area, area);
    scene_destroy(s);
}

Test(render_meshes, obj_ply_rectangle_cube)
{
    render_fixture f;
    render_fixture_open(&f);
    char p[256];
    /* A 2 x 1 quad as one polygon with uv and normals, then a triangle with
     * negative indices and no vt/vn. */
    render_write_file(&f, "quad.obj",
                      "# quad\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                      "o thing\nusemtl x\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
                      p, sizeof p);
    expect_mesh(&f, "<shape type=\"obj\"><string name=\"filename\" value=\"quad.obj\"/>"
                    "<transform name=\"to_world\"><scale value=\"3\"/></transform></shape>",
                2, 18.0, 1);
    render_write_file(&f, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", p, sizeof p);
    expect_mesh(&f, "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/></shape>", 1, 0.5, 0);
    render_write_file(&f, "sq.ply",
                      "ply\nformat ascii 1.0\ncomment unit square\nelement vertex 4\nproperty float x\n"
                      "property float y\nproperty float z\nproperty float u\nproperty float v\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                      "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n",
                      p, sizeof p);
    expect_mesh(&f, "<shape type=\"ply\"><string name=\"filename\" value=\"sq.ply\"/></shape>", 2, 1.0, 1);
    /* Binary little-endian: one triangle (0,0,0) (4,0,0) (0,3,0). */
    {
        snprintf(p, sizeof p, "%s/tri.ply", f.dir);
        FILE *fp = fopen(p, "wb");
        fputs("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
              "property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n",
              fp);
        const double v[9] = {0, 0, 0, 4, 0, 0, 0, 3, 0};
        fwrite(v, sizeof v, 1, fp);
        unsigned char cnt = 3;
        const unsigned idx[3] = {0, 1, 2};
        fwrite(&cnt, 1, 1, fp);
        fwrite(idx, sizeof idx, 1, fp);
        fclose(fp);
    }
    expect_mesh(&f, "<shape type=\"ply\"><string name=\"filename\" value=\"tri.ply\"/></shape>", 1, 6.0, 0);
    expect_mesh(&f, "<shape type=\"rectangle\"/>", 2, 4.0, 1);
    expect_mesh(&f,
                "<shape type=\"cube\"><transform name=\"to_world\"><scale x=\"1\" y=\"2\" z=\"3\"/></transform></shape>",
                12, 2.0 * (2 * 4 + 2 * 6 + 4 * 6), 1); /* a 2 x 4 x 6 box */
    render_fixture_close(&f);
}

/* Smooth normals: a file without vn gets area-weighted vertex normals
 * (Mitsuba does the same) unless face_normals is set. */
Test(render_meshes, smooth_normals_unless_face_normals)
{
    render_fixture f;
    render_fixture_open(&f);
    char p[256];
    /* A roof: two faces meeting at the ridge x = 0 with slopes +-45 degrees. */
    render_write_file(&f, "roof.obj", "v -1 0 0\nv 0 1 0\nv 0 1 1\nv -1 0 1\nv 1 0 0\nv 1 0 1\nf 1 4 3 2\nf 2 3 6 5\n", p,
                      sizeof p);
    scene_t *s = load_one(&f, "<shape type=\"obj\"><string name=\"filename\" value=\"roof.obj\"/></shape>");
    surface_hit h;
    ray3 r = {v3(0, 3, 0.5), v3(0, -1, 0)};
    cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, INFINITY, &h));
    cr_expect_float_eq(h.sh.n.y, 1.0, 1e-6, "ridge shading normal %g %g %g", h.sh.n.x, h.sh.n.y, h.sh.n.z);
    scene_destroy(s);
    s = load_one(&f, "<shape type=\"obj\"><string name=\"filename\" value=\"roof.obj\"/>"
                     "<boolean name=\"face_normals\" value=\"true\"/></shape>");
    r.o.x = -0.5;
    cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, INFINITY, &h));
    cr_expect_float_eq(h.sh.n.y, sqrt(0.5), 1e-6, "face normal %g %g %g", h.sh.n.x, h.sh.n.y, h.sh.n.z);
    scene_destroy(s);
    render_fixture_close(&f);
}

/* Mitsuba's uv conventions (its cube's vertex table; its PLY reader keeps
 * the file's texture coordinates, only OBJ flips v): each cube face maps
 * onto [0,1]^2 from one corner, e.g. +x from (1, -1, 1) with u along +y and
 * v along -z; a PLY vertex's (u, v) arrive as written. */
Test(render_meshes, cube_and_ply_uvs_are_mitsubas)
{
    render_fixture f;
    render_fixture_open(&f);
    scene_t *s = load_one(&f, "<shape type=\"cube\"/>");
    /* per face: a point on it, the ray's direction, and Mitsuba's uv there */
    static const struct {
        vec3 p, d;
        double u, v;
    } faces[] = {
        {{1, 0.5, -0.25}, {-1, 0, 0}, 0.75, 0.625},  /* +x: u = (1 + y)/2, v = (1 - z)/2 */
        {{-1, 0.5, -0.25}, {1, 0, 0}, 0.75, 0.375},  /* -x: u = (1 + y)/2, v = (1 + z)/2 */
        {{0.5, 1, -0.25}, {0, -1, 0}, 0.25, 0.625},  /* +y: u = (1 - x)/2, v = (1 - z)/2 */
        {{0.5, -1, -0.25}, {0, 1, 0}, 0.375, 0.75},  /* -y: u = (1 + z)/2, v = (1 + x)/2 */
        {{0.5, -0.25, 1}, {0, 0, -1}, 0.375, 0.75},  /* +z: u = (1 + y)/2, v = (1 + x)/2 */
        {{0.5, -0.25, -1}, {0, 0, 1}, 0.625, 0.75},  /* -z: u = (1 - y)/2, v = (1 + x)/2 */
    };
    for (int i = 0; i < 6; i++) {
        surface_hit h;
        ray3 r = {v3_sub(faces[i].p, v3_scale(faces[i].d, 3.0)), faces[i].d};
        cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, INFINITY, &h));
        cr_expect_float_eq(h.uv.x, faces[i].u, 1e-6, "face %d: u %g, want %g", i, h.uv.x, faces[i].u);
        cr_expect_float_eq(h.uv.y, faces[i].v, 1e-6, "face %d: v %g, want %g", i, h.uv.y, faces[i].v);
    }
    scene_destroy(s);
    char p[256];
    render_write_file(&f, "sq.ply",
                      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                      "property float z\nproperty float u\nproperty float v\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n"
                      "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n",
                      p, sizeof p);
    s = load_one(&f, "<shape type=\"ply\"><string name=\"filename\" value=\"sq.ply\"/></shape>");
    surface_hit h;
    ray3 r = {v3(0.25, 0.75, 1.0), v3(0, 0, -1)};
    cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, INFINITY, &h));
    cr_expect_float_eq(h.uv.x, 0.25, 1e-6, "ply u %g", h.uv.x);
    cr_expect_float_eq(h.uv.y, 0.75, 1e-6, "ply v %g, want 0.75 (as written)", h.uv.y);
    scene_destroy(s);
    s = load_one(&f, "<shape type=\"ply\"><string name=\"filename\" value=\"sq.ply\"/>"
                     "<boolean name=\"flip_tex_coords\" value=\"true\"/></shape>");
    cr_assert(shape_list_intersect(&s->shapes, &r, 0.0, INFINITY, &h));
    cr_expect_float_eq(h.uv.y, 0.25, 1e-6, "flipped ply v %g, want 0.25", h.uv.y);
    scene_destroy(s);
    render_fixture_close(&f);
}
