/* The orthographic and thin-lens cameras against geometry worked out here:
 * an orthographic view of a unit sphere is a disc of radius 1 (its area,
 * counted by the alpha channel, is pi; its depth is the sphere's height
 * field); a thin lens images a sharp edge at its focus distance as a step,
 * and an edge at depth z as the step seen through a disc of radius
 * A |1/z - 1/F| on the plane at distance 1 (A the aperture radius, F the
 * focus distance). */
#include "test_render_util.h"

#include <math.h>

/* An orthographic view 4 x 4 units wide (to_world scales local [-1, 1]^2 by
 * 2) of a unit sphere 5 units ahead, alpha and depth. */
Test(render_cameras, orthographic_sphere_is_a_disc_of_its_radius)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    render_write_file(&f, "scene.xml",
                      "<scene version=\"3.0.0\"><sensor type=\"orthographic\">"
                      "<transform name=\"to_world\"><scale x=\"2\" y=\"2\" z=\"1\"/><translate z=\"-5\"/></transform>"
                      "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"16\"/></sampler>"
                      "<film type=\"hdrfilm\"><integer name=\"width\" value=\"64\"/><integer name=\"height\" value=\"64\"/>"
                      "<string name=\"pixel_format\" value=\"rgba\"/><rfilter type=\"box\"/></film></sensor>"
                      "<shape type=\"sphere\"/></scene>",
                      path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 1, 2, RENDER_AOV_DEPTH, &w, &h, &nch);
    cr_assert_eq(nch, 5, "R G B A depth");
    const double pixel = 4.0 / 64;
    double area = 0.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *p = px + (y * w + x) * nch;
            double lx = 2.0 - (x + 0.5) * pixel, ly = 2.0 - (y + 0.5) * pixel, r = hypot(lx, ly);
            area += p[3] * pixel * pixel;
            if (r < 0.95)
                cr_assert_eq(p[3], 1.0f, "pixel (%d, %d) inside the disc", x, y);
            /* Rays start on the near plane (z = -5 + 0.01) and meet the sphere
             * at z = -sqrt(1 - r^2): the depth AOV is the mean of 16 samples
             * over the pixel, its value at the centre within 4 standard
             * deviations (slope x pixel / sqrt(12 x 16)). */
            double slope = r / sqrt(1.0 - r * r);
            if (r < 0.8)
                cr_assert_float_eq(p[4], 5.0 - 0.01 - sqrt(1.0 - r * r), 0.002 + 4.0 * slope * pixel / sqrt(192.0), "depth at r = %g: %.5f, want %.5f", r, p[4], 5.0 - 0.01 - sqrt(1.0 - r * r));
            if (r > 1.05)
                cr_assert_eq(p[3], 0.0f, "pixel (%d, %d) outside the disc", x, y);
        }
    cr_log_info("orthographic disc: area %.5f (pi = %.5f)", area, M_PI);
    cr_assert_float_eq(area, M_PI, 0.01 * M_PI, "area %g", area);
    free(px);
    render_fixture_close(&f);
}

enum { LW = 48, LH = 4 };

/* A thin lens at the origin looking along +z (fov 20 along x), and an
 * emitter covering local x > 0 (the image's left half) at depth z. */
static float *render_lens_edge(double aperture, double focus, double z, int spp)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[4096], path[256];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"1\"/></integrator>"
             "<sensor type=\"thinlens\"><float name=\"fov\" value=\"20\"/>"
             "<float name=\"aperture_radius\" value=\"%g\"/><float name=\"focus_distance\" value=\"%g\"/>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/><integer name=\"height\" value=\"%d\"/>"
             "<rfilter type=\"box\"/></film></sensor>"
             "<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/>"
             "<transform name=\"to_world\"><scale x=\"2\" y=\"1\" z=\"1\"/><translate x=\"2\" z=\"%g\"/></transform>"
             "<emitter type=\"area\"/></shape></scene>",
             aperture, focus, spp, LW, LH, z);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 11, 2, 0, &w, &h, &nch);
    render_fixture_close(&f);
    return px;
}

/* The lit fraction of the lens seen from the image-plane point u (tan
 * units, local x): lit when u + a_x k > 0 with k = 1/z - 1/F, a_x the
 * lens point's x, uniform on the disc of radius A: the area fraction of a
 * circular segment. */
static double lit_fraction(double u, double aperture, double k)
{
    if (k == 0.0)
        return u > 0.0;
    double rho = -u / (aperture * k); /* lit where a_x / A > rho (k > 0) */
    double frac = rho <= -1.0 ? 1.0 : rho >= 1.0 ? 0.0 : (acos(rho) - rho * sqrt(1.0 - rho * rho)) / M_PI;
    return k > 0.0 ? frac : 1.0 - frac;
}

Test(render_cameras, thinlens_focus_and_circle_of_confusion, .timeout = 60)
{
    const double tan_x = tan(10.0 * M_PI / 180.0), aperture = 0.2, focus = 2.0;
    /* In focus: every lens point sees the edge at the same film position. */
    float *px = render_lens_edge(aperture, focus, focus, 16);
    for (int y = 0; y < LH; y++)
        for (int x = 0; x < LW; x++)
            cr_assert_eq(px[(y * LW + x) * 3], x < LW / 2 ? 1.0f : 0.0f, "in focus: pixel (%d, %d)", x, y);
    free(px);
    /* At depth 4 the circle of confusion has radius A |1/4 - 1/2| = 0.05 on
     * the plane at distance 1: 0.05 W / (2 tan_x) = 6.8 pixels. */
    const double z = 4.0, k = 1.0 / z - 1.0 / focus;
    px = render_lens_edge(aperture, focus, z, 2048);
    double worst = 0.0;
    for (int x = 0; x < LW; x++) {
        /* The box-filtered pixel: the mean of the lit fraction over it. */
        double want = 0.0;
        for (int s = 0; s < 200; s++) {
            double fx = (x + (s + 0.5) / 200) / LW;
            want += lit_fraction((1.0 - 2.0 * fx) * tan_x, aperture, k) / 200;
        }
        /* The rows see the same edge: their mean has half the noise. */
        double got = 0.0;
        for (int y = 0; y < LH; y++)
            got += px[(y * LW + x) * 3] / LH;
        worst = fmax(worst, fabs(got - want));
        cr_assert_float_eq(got, want, 0.03, "z = 4: column %d %.4f, want %.4f", x, got, want);
    }
    cr_log_info("thinlens: circle of confusion %.2f px, worst |pixel - prediction| = %.4f",
                aperture * fabs(k) * LW / (2.0 * tan_x), worst);
    /* The blur is there: pixels 3 from the edge are neither lit nor dark. */
    cr_assert(px[(LW / 2 + 3) * 3] > 0.05 && px[(LW / 2 - 4) * 3] < 0.95);
    free(px);
}
