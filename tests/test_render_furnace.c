/* White furnace tests: under a constant environment of radiance 1, a closed
 * object that neither absorbs nor emits must look exactly like the
 * environment, so every pixel renders 1 within Monte Carlo noise. A
 * diffuse albedo-1 surface checks NEE + MIS + Russian roulette; a dielectric
 * checks that refraction, total internal reflection and the 1/eta^2
 * radiance scaling conserve energy. */
#include "test_render_util.h"

static const char *furnace_xml =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"/>\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"30\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0.4, 0.9, 2.6\" target=\"0, 0.5, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"20\"/><integer name=\"height\" value=\"20\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"%s\">%s\n"
    "    %s\n"
    "  </shape>\n"
    "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n"
    "</scene>\n";

static const char *diffuse1 = "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1\"/></bsdf>";
static const char *glass = "<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"1.5\"/></bsdf>";

/* Renders the furnace and checks: the object covers a good part of the
 * image (depth AOV), every pixel is 1 within tol, the mean within mean_tol. */
static void furnace(const char *shape, const char *params, const char *bsdf, int mesh_segments, int spp, double tol,
                    double mean_tol)
{
    render_fixture f;
    render_fixture_open(&f);
    render_write_profile(&f, "profile.json", "plum");
    char xml[4096], path[256];
    snprintf(xml, sizeof xml, furnace_xml, spp, shape, params, bsdf);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, mesh_segments, 7, 2, RENDER_AOV_DEPTH, &w, &h, &nch);
    int covered = 0;
    double sum = 0.0, worst = 0.0;
    for (int i = 0; i < w * h; i++) {
        const float *p = &px[i * nch];
        covered += p[3] > 0.0f;
        for (int c = 0; c < 3; c++) {
            sum += p[c];
            worst = fmax(worst, fabs(p[c] - 1.0));
        }
    }
    double mean = sum / (3.0 * w * h);
    cr_expect_gt(covered, w * h / 4, "the object covers only %d of %d pixels", covered, w * h);
    cr_expect_leq(worst, tol, "a pixel is off by %g", worst);
    cr_expect_leq(fabs(mean - 1.0), mean_tol, "mean %g", mean);
    free(px);
    render_fixture_close(&f);
}

static const char *sor_params = "<string name=\"filename\" value=\"profile.json\"/>";
static const char *sphere_params =
    "<point name=\"center\" value=\"0, 0.5, 0\"/><float name=\"radius\" value=\"0.5\"/>";

/* Per-sample standard deviations are ~0.25 here: at 64 spp a pixel's is
 * ~0.03, so 0.18 is six of them, and the mean of 1200 values is good to
 * ~0.002. */
Test(render_furnace, diffuse_sor_analytic) { furnace("sor", sor_params, diffuse1, 0, 64, 0.18, 0.01); }
Test(render_furnace, diffuse_sphere) { furnace("sphere", sphere_params, diffuse1, 0, 64, 0.18, 0.01); }
Test(render_furnace, diffuse_sor_meshed) { furnace("sor", sor_params, diffuse1, 256, 64, 0.18, 0.01); }
Test(render_furnace, glass_sphere) { furnace("sphere", sphere_params, glass, 0, 64, 0.18, 0.01); }
Test(render_furnace, glass_sor_analytic) { furnace("sor", sor_params, glass, 0, 64, 0.18, 0.01); }
Test(render_furnace, glass_sor_meshed) { furnace("sor", sor_params, glass, 256, 64, 0.18, 0.01); }

/* Inside a closed box whose walls emit L_e = 1 and reflect diffusely with
 * albedo a, the radiance is L_e / (1 - a) everywhere (the Neumann series
 * L_e (1 + a + a^2 + ...)); Russian roulette starts at the first bounce
 * (rr_depth 1), so it decides every path's length. Renders the box's 8x8
 * image at spp samples; the image's mean and its worst pixel. */
static void closed_box(double albedo, int spp, double *mean, double *worst)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256], xml[2048];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\">\n"
             "  <integrator type=\"path\"><integer name=\"rr_depth\" value=\"1\"/></integrator>\n"
             "  <sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>\n"
             "    <transform name=\"to_world\"><lookat origin=\"0.2, -0.1, 0.3\" target=\"0, 0, -1\" "
             "up=\"0, 1, 0\"/></transform>\n"
             "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
             "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" "
             "value=\"8\"/></film>\n"
             "  </sensor>\n"
             "  <shape type=\"cube\"><boolean name=\"flip_normals\" value=\"true\"/>\n"
             "    <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"%g\"/></bsdf>\n"
             "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n"
             "</scene>\n",
             spp, albedo);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 11, 2, 0, &w, &h, &nch);
    double sum = 0.0, want = 1.0 / (1.0 - albedo);
    *worst = 0.0;
    for (int i = 0; i < w * h; i++)
        for (int c = 0; c < 3; c++) {
            sum += px[i * nch + c];
            *worst = fmax(*worst, fabs(px[i * nch + c] - want));
        }
    *mean = sum / (3.0 * w * h);
    free(px);
    render_fixture_close(&f);
}

/* The deep-path furnace, albedo 0.9: paths average ten bounces; without
 * roulette's 1/q compensation the image would come out at about 5.3. Each
 * sample sums a geometric number of terms (sd about 9.5): at 256 spp a
 * pixel's mean is good to 0.6 and the image's to 0.07. */
Test(render_furnace, closed_box_with_roulette_from_the_first_bounce)
{
    double mean, worst;
    closed_box(0.9, 256, &mean, &worst);
    cr_expect_float_eq(mean, 10.0, 0.25, "mean %g, want 10", mean);
    cr_expect_leq(worst, 3.0, "a pixel is off by %g", worst);
}

/* The dark furnace, albedo 0.25: roulette's survival probability is the
 * path's throughput, 0.25 at every bounce, far below one half, where a
 * compensation weight clamped or floored anywhere (1/max(q, 0.5) gives 2
 * for 4) shows: the radiance is 1/(1 - 0.25) = 4/3, and with the weight
 * floored at one half it would be 1/(1 - 0.25 * 0.25 * 2) = 1.143. A path
 * that survives carries throughput 1, so a sample is its number of
 * vertices, 1 + a geometric count (sd sqrt(0.25)/0.75 = 0.67): at 64 spp
 * over 64 pixels the image's mean is good to 0.011, a pixel's to 0.09. */
Test(render_furnace, dark_closed_box_with_roulette_below_one_half)
{
    double mean, worst;
    closed_box(0.25, 64, &mean, &worst);
    cr_expect_float_eq(mean, 4.0 / 3.0, 0.05, "mean %g, want 4/3", mean);
    cr_expect_leq(worst, 0.5, "a pixel is off by %g", worst);
}
