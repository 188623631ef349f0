/* Area sampling of emitting shapes: E[1 / pdf] over sampled points is the
 * surface area (checked against closed forms and, for the SOR, against the
 * area of a fine revolved mesh), and the density a ray hit reports for a
 * point equals the density the sampler gave it (what MIS relies on). */
#include "render/scene_impl.h"
#include "test_render_util.h"

static const char *scene_fmt =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/>"
    "<integer name=\"height\" value=\"4\"/></film></sensor>\n"
    "  <shape type=\"%s\">%s<emitter type=\"area\"/></shape>\n"
    "</scene>\n";

static scene_t *load_shape(render_fixture *f, const char *type, const char *params, int mesh_segments)
{
    char xml[2048], path[256], err[512];
    snprintf(xml, sizeof xml, scene_fmt, type, params);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    scene_options bo = scene_options_default();
    bo.mesh_segments = mesh_segments;
    scene_t *s = scene_create_from_file(path, NULL, 0, &bo, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    return s;
}

/* Mean of 1/pdf over n stratified samples, and the worst relative mismatch
 * between the sampled density and the density of the same point found by a
 * ray cast at it along its normal. */
static double sampled_area(const scene_t *s, int n, double *worst_mismatch)
{
    int checked = 0;
    const shape_t *sh = &s->shapes.items[0];
    rng_t rng;
    rng_seed(&rng, 42, 7);
    double sum = 0.0;
    *worst_mismatch = 0.0;
    for (int i = 0; i < n; i++) {
        vec3 u = v3((i + rng_next_double(&rng)) / n, rng_next_double(&rng), rng_next_double(&rng));
        surface_hit h;
        double pdf;
        shape_sample_area(sh, u, &h, &pdf);
        cr_assert_gt(pdf, 0.0);
        sum += 1.0 / pdf;
        /* A ray arriving from outside along the normal finds the same point. */
        ray3 r = {v3_add(h.p, v3_scale(h.ng, 1e-3)), v3_neg(h.ng)};
        surface_hit g;
        if (shape_list_intersect(&s->shapes, &r, 0.0, 2e-3, &g) && v3_len(v3_sub(g.p, h.p)) < 1e-6) {
            double q = shape_pdf_area(sh, &g);
            *worst_mismatch = fmax(*worst_mismatch, fabs(q - pdf) / pdf);
            checked++;
        }
    }
    cr_expect_gt(checked, n * 9 / 10, "only %d of %d sampled points were found again by a ray", checked, n);
    return sum / n;
}

Test(render_sampling, sphere_and_stretched_disk_areas)
{
    render_fixture f;
    render_fixture_open(&f);
    double mismatch;
    scene_t *s = load_shape(&f, "sphere", "<float name=\"radius\" value=\"2\"/>", 0);
    cr_expect_float_eq(sampled_area(s, 4000, &mismatch), 16.0 * M_PI, 1e-9 * 16 * M_PI);
    cr_expect_lt(mismatch, 1e-9);
    scene_destroy(s);
    s = load_shape(&f, "disk",
                   "<transform name=\"to_world\"><scale x=\"2\" y=\"3\" z=\"1\"/><rotate x=\"1\" angle=\"30\"/>"
                   "</transform>",
                   0);
    cr_expect_float_eq(sampled_area(s, 4000, &mismatch), 6.0 * M_PI, 1e-9 * 6 * M_PI);
    cr_expect_lt(mismatch, 1e-9);
    scene_destroy(s);
    render_fixture_close(&f);
}

Test(render_sampling, sor_area_matches_its_fine_mesh)
{
    render_fixture f;
    render_fixture_open(&f);
    render_write_profile(&f, "profile.json", "plum");
    const char *params = "<string name=\"filename\" value=\"profile.json\"/><float name=\"height\" value=\"2\"/>"
                         "<transform name=\"to_world\"><rotate z=\"1\" angle=\"20\"/><translate x=\"1\"/></transform>";
    /* At 512 segments (835k triangles) the mesh's area is within 1.5e-5 of
     * the surface's (extrapolated from 128 ... 2048 segments; 2048, 11M
     * triangles, are within 1e-6 for ten times the CPU): far inside the
     * bound, and the sampled area lies within 2e-5 of either. */
    scene_t *mesh = load_shape(&f, "sor", params, 512);
    double mesh_area = mesh->shapes.items[0].mesh.area, mismatch;
    scene_destroy(mesh);
    scene_t *s = load_shape(&f, "sor", params, 0);
    double area = sampled_area(s, 20000, &mismatch);
    /* The tabulated u-CDF is piecewise constant, so 1/pdf varies within a
     * cell and the estimate carries Monte Carlo error (~0.3% here). */
    cr_expect_float_eq(area, mesh_area, 0.01 * mesh_area, "sampled %g, mesh %g", area, mesh_area);
    cr_expect_lt(mismatch, 1e-6, "hit and sample densities differ by %g", mismatch);
    scene_destroy(s);
    render_fixture_close(&f);
}
