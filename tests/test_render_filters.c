/* The reconstruction filters and splatting, against the filters' own
 * formulas integrated here: an orthographic view of a sharp vertical edge
 * (radiance 1 on the left half, 0 on the right) gives pixel values equal to
 * the filter-weighted mean of the step over the sampled part of the film,
 *   V(c) = int_D f(c - x) step(x) dx / int_D f(c - x) dx,
 * D the film ([0, W), or [-b, W + b) with sample_border, b = ceil(r - 1/2));
 * a flat field stays flat under every filter; and the image does not depend
 * on the thread count however far the filter reaches. */
#include "test_render_util.h"

#include <math.h>

enum { W = 32, H = 4 };

/* An orthographic camera along +z; a rectangle emitter over local x in
 * [0, 4] (the image's left half: local +x is the image's left), facing the
 * camera. */
static const char *edge_fmt =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"1\"/></integrator>\n"
    "  <sensor type=\"orthographic\">\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/><integer name=\"height\" value=\"%d\"/>\n"
    "      <boolean name=\"sample_border\" value=\"%s\"/>%s</film>\n"
    "  </sensor>\n"
    "  <shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/>\n"
    "    <transform name=\"to_world\"><scale x=\"2\" y=\"1\" z=\"1\"/><translate x=\"2\" z=\"5\"/></transform>\n"
    "    <emitter type=\"area\"/></shape>\n"
    "</scene>\n";

static float *render_edge(const char *rfilter, bool border, int spp, int threads)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[4096], path[256];
    snprintf(xml, sizeof xml, edge_fmt, spp, W, H, border ? "true" : "false", rfilter);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 5, threads, 0, &w, &h, &nch);
    cr_assert(w == W && h == H && nch == 3);
    render_fixture_close(&f);
    return px;
}

/* The filters as Mitsuba documents them. */
static double gaussian(double x, double stddev)
{
    double r = 4.0 * stddev;
    return fabs(x) < r ? exp(-x * x / (2 * stddev * stddev)) - exp(-r * r / (2 * stddev * stddev)) : 0.0;
}

static double tent(double x, double radius) { return fmax(0.0, 1.0 - fabs(x) / radius); }

/* int_a^b g(c - x) dx by Simpson's rule on a fine grid. */
static double integrate(double (*g)(double, double), double p, double c, double a, double b)
{
    const int n = 4000;
    double h = (b - a) / n, s = 0.0;
    for (int i = 0; i <= n; i++)
        s += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * g(c - (a + i * h), p);
    return s * h / 3.0;
}

/* V(c) at every pixel centre of a row; the film spans [lo, hi). */
static void check_profile(const float *px, double (*g)(double, double), double p, double radius, double lo,
                          double hi, const char *what)
{
    double worst = 0.0;
    for (int i = 0; i < W; i++) {
        double c = i + 0.5, a = fmax(lo, c - radius), b = fmin(hi, c + radius);
        double want = integrate(g, p, c, a, fmin(b, W / 2.0)) / integrate(g, p, c, a, b);
        if (c - radius >= W / 2.0)
            want = 0.0;
        /* The rows see the same edge: their mean has half the noise. */
        double got = 0.0;
        for (int y = 0; y < H; y++)
            got += px[(y * W + i) * 3 + 1] / H;
        worst = fmax(worst, fabs(got - want));
        cr_assert_float_eq(got, want, 0.02, "%s: column %d %.4f, want %.4f", what, i, got, want);
    }
    cr_log_info("%s: worst |pixel - V| = %.4f", what, worst);
}

Test(render_filters, box_keeps_the_edge_sharp)
{
    float *px = render_edge("<rfilter type=\"box\"/>", false, 16, 2);
    for (int y = 0; y < H; y++)
        for (int i = 0; i < W; i++)
            cr_assert_eq(px[(y * W + i) * 3], i < W / 2 ? 1.0f : 0.0f, "pixel (%d, %d)", i, y);
    free(px);
}

Test(render_filters, gaussian_edge_is_the_filtered_step, .timeout = 60)
{
    /* No <rfilter>: Mitsuba's default, a gaussian of stddev 0.5. */
    float *px = render_edge("", false, 1024, 2);
    check_profile(px, gaussian, 0.5, 2.0, 0.0, W, "gaussian 0.5");
    free(px);
    px = render_edge("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"1.5\"/></rfilter>", true, 1024, 2);
    check_profile(px, gaussian, 1.5, 6.0, -6.0, W + 6.0, "gaussian 1.5, sample_border");
    free(px);
}

Test(render_filters, tent_edge_is_the_filtered_step, .timeout = 60)
{
    float *px = render_edge("<rfilter type=\"tent\"/>", false, 1024, 2);
    check_profile(px, tent, 1.0, 1.0, 0.0, W, "tent 1");
    free(px);
    px = render_edge("<rfilter type=\"tent\"><float name=\"radius\" value=\"2.5\"/></rfilter>", false, 1024, 2);
    check_profile(px, tent, 2.5, 2.5, 0.0, W, "tent 2.5");
    free(px);
}

/* A constant environment seen everywhere: every sample is 1, so every
 * filter-weighted mean is 1, up to float rounding. */
Test(render_filters, flat_field_stays_flat)
{
    const char *filters[] = {"<rfilter type=\"box\"/>", "<rfilter type=\"tent\"/>", "",
                             "<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"3\"/></rfilter>"};
    for (int k = 0; k < 4; k++) {
        render_fixture f;
        render_fixture_open(&f);
        char xml[2048], path[256];
        snprintf(xml, sizeof xml,
                 "<scene version=\"3.0.0\"><sensor type=\"perspective\">"
                 "<film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"24\"/>"
                 "%s</film></sensor><emitter type=\"constant\"/></scene>",
                 filters[k]);
        render_write_file(&f, "scene.xml", xml, path, sizeof path);
        int w, h, nch;
        float *px = render_to_pixels(path, 0, 9, 2, 0, &w, &h, &nch);
        for (int i = 0; i < w * h * nch; i++)
            cr_assert_float_eq(px[i], 1.0f, 1e-6, "filter %d, value %d: %.9g", k, i, px[i]);
        free(px);
        render_fixture_close(&f);
    }
}

/* Splatting across tiles: a filter 12 pixels wide, rendered by one thread
 * and by two, gives the same bits. */
Test(render_filters, wide_filter_is_deterministic_across_threads, .timeout = 60)
{
    const char *wide = "<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"3\"/></rfilter>";
    float *a = render_edge(wide, true, 8, 1), *b = render_edge(wide, true, 8, 2);
    cr_assert(memcmp(a, b, sizeof(float) * W * H * 3) == 0, "the thread count changed the image");
    free(a);
    free(b);
}
