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
