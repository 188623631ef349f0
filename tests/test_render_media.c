/* Participating media and the `volpath` integrator against closed forms:
 * the phase functions' normalisation and mean cosine; the transmittance of a
 * cube of absorbing medium, e^{-sigma_t d} per channel, homogeneous and as a
 * grid (whose trilinear ramp integrates exactly); a white furnace (an
 * albedo-1 medium under a constant environment looks like the environment);
 * single scattering of a directional light in a homogeneous cube, whose
 * radiance along each camera ray is an integral in closed form; and the
 * refusals of a bad medium. */
#include <math.h>

#include "phases/phases.h"
#include "support/vol_file.h"
#include "test_render_util.h"

/* ------------------------------------------------------- phase functions */

static phase_t *hg_phase(double g)
{
    scene_prop p = {.name = (char *)"g", .type = SCENE_FLOAT, .value.f = g};
    scene_obj o = {.cls = SCENE_PHASE, .type = (char *)"hg", .file = "t.xml", .line = 1, .props = &p, .nprops = 1};
    char err[256];
    phase_t *ph = phase_create(&o, &o, err, sizeof err);
    cr_assert_not_null(ph, "%s", err);
    return ph;
}

Test(render_media, phase_functions_are_normalised_and_sampled_as_they_evaluate)
{
    const double gs[] = {0.0, 0.5, -0.7, 0.9};
    vec3 d = v3_norm(v3(0.3, -0.2, 0.9));
    for (int k = 0; k < 4; k++) {
        phase_t *ph = hg_phase(gs[k]);
        /* The integral over the sphere (midpoint rule in cos(theta) about d, phi) is 1. */
        frame3 f = frame3_from_normal(d);
        double sum = 0.0;
        const int n = 4000;
        for (int i = 0; i < n; i++) {
            double mu = -1.0 + (i + 0.5) * 2.0 / n, s = sqrt(1.0 - mu * mu);
            sum += phase_eval(ph, d, frame3_to_world(f, v3(s, 0.0, mu))) * 2.0 / n * 2.0 * M_PI;
        }
        cr_expect_float_eq(sum, 1.0, 1e-3, "g %g: integral %g", gs[k], sum);
        /* Samples: density equal to the value; mean cosine g (Henyey-Greenstein's
         * defining moment), to 4 standard errors of 1/sqrt(3 n). */
        double mean = 0.0;
        const int m = 20000;
        for (int i = 0; i < m; i++) {
            double pdf;
            vec2 u = v2((i + 0.5) / m, fmod(i * 0.6180339887498949, 1.0));
            vec3 w = phase_sample(ph, d, u, &pdf);
            cr_assert_float_eq(v3_len(w), 1.0, 1e-9);
            cr_assert_float_eq(pdf, phase_eval(ph, d, w), 1e-9 * pdf);
            mean += v3_dot(w, d) / m;
        }
        cr_expect_float_eq(mean, gs[k], 4.0 / sqrt(3.0 * m), "g %g: mean cosine %g", gs[k], mean);
        phase_destroy(ph);
    }
    phase_t *iso = phase_create(NULL, &(scene_obj){.file = "t.xml", .line = 1}, NULL, 0);
    cr_assert_float_eq(phase_eval(iso, d, v3(1, 0, 0)), 1.0 / (4.0 * M_PI), 1e-15, "the default is isotropic");
    phase_destroy(iso);
}

/* --------------------------------------------------------------- scenes */

/* A cube [-1, 1]^3 of medium (bounded by a null BSDF) seen by an
 * orthographic camera along -z that covers x, y in [-1, 1]; then the
 * lights. */
static const char *cube_xml = "<scene version=\"3.0.0\">\n"
                              "  <integrator type=\"volpath\"><integer name=\"max_depth\" value=\"%d\"/></integrator>\n"
                              "  <sensor type=\"orthographic\">\n"
                              "    <transform name=\"to_world\"><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
                              "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
                              "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/>"
                              "<rfilter type=\"box\"/></film>\n"
                              "  </sensor>\n"
                              "  %s\n"
                              "  <shape type=\"%s\"><bsdf type=\"null\"/>%s</shape>\n"
                              "  %s\n"
                              "</scene>\n";

static const char *env1 = "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>";

/* Renders the cube scene with the medium given, into a 16 x 16 RGB image
 * (malloc'd, 3 floats a pixel); shape is "cube" or "sphere". */
static float *render_medium(const char *medium, const char *shape, const char *lights, int max_depth, int spp,
                            const char *extra_file, const void *extra, size_t extra_len)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[8192], path[256];
    const char *ref = "<ref id=\"m\" name=\"interior\"/>";
    snprintf(xml, sizeof xml, cube_xml, max_depth, spp, medium, shape, ref, lights);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    if (extra_file) {
        char p2[256];
        snprintf(p2, sizeof p2, "%s/%s", f.dir, extra_file);
        FILE *fp = fopen(p2, "wb");
        cr_assert_not_null(fp);
        cr_assert_eq(fwrite(extra, 1, extra_len, fp), extra_len);
        fclose(fp);
    }
    int w, h;
    float *rgb = render_to_rgb(path, 3, &w, &h);
    cr_assert(w == 16 && h == 16);
    render_fixture_close(&f);
    return rgb;
}

static void image_mean(const float *rgb, double mean[3])
{
    mean[0] = mean[1] = mean[2] = 0.0;
    for (int i = 0; i < 256; i++)
        for (int c = 0; c < 3; c++)
            mean[c] += rgb[3 * i + c] / 256.0;
}

/* ---------------------------------------------------------- transmittance */

/* Absorption only (albedo 0) under a constant white environment: each
 * pixel is the transmittance across the cube. */
Test(render_media, an_absorbing_cube_transmits_exp_minus_sigma_t_d)
{
    const double sigma[3] = {0.5, 0.4, 0.3}, scale = 1.5;
    float *px = render_medium("<medium type=\"homogeneous\" id=\"m\"><rgb name=\"sigma_t\" value=\"0.5, 0.4, 0.3\"/>"
                              "<float name=\"scale\" value=\"1.5\"/><rgb name=\"albedo\" value=\"0\"/></medium>",
                              "cube", env1, -1, 64, NULL, NULL, 0);
    double mean[3];
    image_mean(px, mean);
    /* 16384 samples of a weight whose standard deviation is about 0.45: a
     * standard error of 0.0035, and 0.011 is three of them. */
    for (int c = 0; c < 3; c++)
        cr_expect_float_eq(mean[c], exp(-sigma[c] * scale * 2.0), 0.011, "channel %d: %g, not %g", c, mean[c],
                           exp(-sigma[c] * scale * 2.0));
    free(px);
}

/* A grid of two layers a, b along z filling z in [-1, 0] only (its box):
 * trilinear interpolation between the voxel centres makes the optical
 * depth along z exactly (a + b) / 2 over that unit, and the medium is empty
 * in the rest of the cube, as Mitsuba's heterogeneous medium outside its
 * sigma_t's box. */
Test(render_media, a_grid_medium_transmits_its_exact_optical_depth)
{
    const float layers[2] = {0.4f, 2.0f};
    unsigned char buf[64];
    size_t len = vol_file_bytes(buf, 1, 1, 2, 1, layers);
    float *px = render_medium("<medium type=\"heterogeneous\" id=\"m\"><rgb name=\"albedo\" value=\"0\"/>"
                              "<volume type=\"gridvolume\" name=\"sigma_t\"><string name=\"filename\" value=\"g.vol\"/>"
                              "<transform name=\"to_world\"><scale x=\"2\" y=\"2\" z=\"1\"/>"
                              "<translate x=\"-1\" y=\"-1\" z=\"-1\"/></transform></volume></medium>",
                              "cube", env1, -1, 64, "g.vol", buf, len);
    double mean[3], want = exp(-0.5 * (layers[0] + layers[1]));
    image_mean(px, mean);
    for (int c = 0; c < 3; c++)
        cr_expect_float_eq(mean[c], want, 0.012, "channel %d: %g, not %g", c, mean[c], want);
    free(px);
}

/* ---------------------------------------------------------------- furnace */

/* An albedo-1 medium of RGB extinction (null collisions for the thinner
 * channels), forward-scattering, under a constant environment of radiance 1:
 * nothing is absorbed or emitted, so every pixel is 1. */
static void medium_furnace(const char *medium, const char *extra_file, const void *extra, size_t extra_len)
{
    float *px = render_medium(medium, "sphere", env1, -1, 16, extra_file, extra, extra_len);
    double mean[3];
    image_mean(px, mean);
    for (int c = 0; c < 3; c++)
        cr_expect_float_eq(mean[c], 1.0, 0.02, "channel %d: %g", c, mean[c]);
    free(px);
}

Test(render_media, a_white_medium_in_a_furnace_is_invisible)
{
    medium_furnace("<medium type=\"homogeneous\" id=\"m\"><rgb name=\"sigma_t\" value=\"0.5, 1, 2\"/>"
                   "<float name=\"scale\" value=\"2\"/><rgb name=\"albedo\" value=\"1\"/>"
                   "<phase type=\"hg\"><float name=\"g\" value=\"0.6\"/></phase></medium>",
                   NULL, NULL, 0);
    const float grid[8] = {0.5f, 3.0f, 1.0f, 0.0f, 2.0f, 0.2f, 4.0f, 1.5f};
    unsigned char buf[96];
    size_t len = vol_file_bytes(buf, 2, 2, 2, 1, grid);
    medium_furnace("<medium type=\"heterogeneous\" id=\"m\"><rgb name=\"albedo\" value=\"1\"/>"
                   "<volume type=\"gridvolume\" name=\"sigma_t\"><string name=\"filename\" value=\"g.vol\"/>"
                   "<transform name=\"to_world\"><scale value=\"2\"/><translate value=\"-1, -1, -1\"/></transform>"
                   "</volume><phase type=\"hg\"><float name=\"g\" value=\"-0.3\"/></phase></medium>",
                   "g.vol", buf, len);
}

/* ------------------------------------------------------ single scattering */

/* A directional light of irradiance 1 travelling along -x into the cube
 * (sigma_t per channel, albedo 0.8, isotropic), max_depth 2: the camera ray
 * at x gathers L(x) = sigma_s / (4 pi) e^{-sigma_t (1 - x)} (1 - e^{-2 sigma_t})
 * / sigma_t, the light's path into the cube times the camera ray's
 * transmittance integrated over depth; its mean over x in [-1, 1] is
 * 0.8 / (4 pi) (1 - e^{-2 sigma_t})^2 / (2 sigma_t). */
Test(render_media, single_scattering_matches_its_closed_form)
{
    const double sigma[3] = {0.5, 1.0, 2.0};
    float *px = render_medium("<medium type=\"homogeneous\" id=\"m\"><rgb name=\"sigma_t\" value=\"0.5, 1, 2\"/>"
                              "<rgb name=\"albedo\" value=\"0.8\"/></medium>",
                              "cube", "<emitter type=\"directional\"><vector name=\"direction\" value=\"-1, 0, 0\"/></emitter>",
                              2, 64, NULL, NULL, 0);
    double mean[3];
    image_mean(px, mean);
    for (int c = 0; c < 3; c++) {
        double e = 1.0 - exp(-2.0 * sigma[c]), want = 0.8 / (4.0 * M_PI) * e * e / (2.0 * sigma[c]);
        cr_expect_float_eq(mean[c], want, 0.03 * want, "channel %d: %g, not %g", c, mean[c], want);
    }
    /* Across x: the columns facing the light over those away from it, each
     * column's mean of e^{sigma_t x} over its 1/8 of a unit:
     * e^{sigma_t (2 - 1/8)} for the red channel. */
    double col[16] = {0};
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++)
            col[x] += px[3 * (y * 16 + x)] / 16.0;
    double ratio = fmax(col[0] / col[15], col[15] / col[0]), want = exp(sigma[0] * 1.875);
    cr_expect_float_eq(ratio, want, 0.1 * want, "edge columns' ratio %g, not %g", ratio, want);
    free(px);
}

/* ---------------------------------------------------------------- refusals */

static void medium_refused(const char *medium, const char *needle)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[8192], path[256], err[1024];
    snprintf(xml, sizeof xml, cube_xml, -1, 1, medium, "cube", "<ref id=\"m\" name=\"interior\"/>", env1);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_expect_null(s, "%s accepted", medium);
    cr_expect(strstr(err, "scene.xml:") && strstr(err, needle), "%s", err);
    scene_destroy(s);
    render_fixture_close(&f);
}

Test(render_media, bad_media_are_refused_naming_file_and_line)
{
    medium_refused("<medium type=\"homogeneous\" id=\"m\"><float name=\"scale\" value=\"-1\"/></medium>", "scale");
    medium_refused("<medium type=\"homogeneous\" id=\"m\"><phase type=\"hg\"><float name=\"g\" value=\"1\"/></phase></medium>",
                   "g must be in (-1, 1)");
    medium_refused("<medium type=\"homogeneous\" id=\"m\"><volume type=\"gridvolume\" name=\"sigma_t\">"
                   "<string name=\"filename\" value=\"scene.xml\"/></volume></medium>",
                   "not a Mitsuba .vol file");
    medium_refused("<medium type=\"homogeneous\" id=\"m\"><texture type=\"checkerboard\" name=\"albedo\"/></medium>",
                   "albedo must be a <volume> or a color");
    medium_refused("<texture type=\"checkerboard\" id=\"m\"/>", "interior must be a <medium>");
}

/* The camera inside a medium (the sensor's nested <medium>, Mitsuba's
 * m_medium): a pinhole at the centre of a sphere of radius 2 whose inside
 * is an absorbing medium (null boundary) under a white sky sees
 * e^{-sigma_t 2} in every direction (less the near clip's 0.01 of the
 * path); without the sensor's medium, camera rays start in none and see the
 * sky whole. */
Test(render_media, a_camera_inside_a_medium_sees_through_it)
{
    static const char *xml =
        "<scene version=\"3.0.0\">\n"
        "  <integrator type=\"volpath\"/>\n"
        "  <medium type=\"homogeneous\" id=\"m\"><rgb name=\"sigma_t\" value=\"0.5, 0.25, 0.1\"/>"
        "<rgb name=\"albedo\" value=\"0\"/></medium>\n"
        "  <sensor type=\"perspective\"><float name=\"fov\" value=\"90\"/>\n"
        "    <transform name=\"to_world\"><lookat origin=\"0, 0, 0\" target=\"1, 0.3, 0.2\" up=\"0, 1, 0\"/></transform>\n"
        "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"64\"/></sampler>\n"
        "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/>"
        "<rfilter type=\"box\"/></film>%s\n"
        "  </sensor>\n"
        "  <shape type=\"sphere\"><float name=\"radius\" value=\"2\"/><bsdf type=\"null\"/>"
        "<ref id=\"m\" name=\"interior\"/></shape>\n"
        "  <emitter type=\"constant\"/>\n"
        "</scene>\n";
    const double sigma[3] = {0.5, 0.25, 0.1};
    for (int inside = 0; inside < 2; inside++) {
        render_fixture f;
        render_fixture_open(&f);
        char text[4096], path[256];
        snprintf(text, sizeof text, xml, inside ? "\n    <ref id=\"m\"/>" : "");
        render_write_file(&f, "scene.xml", text, path, sizeof path);
        int w, h;
        float *px = render_to_rgb(path, 3, &w, &h);
        cr_assert(w == 16 && h == 16);
        double mean[3];
        image_mean(px, mean);
        for (int c = 0; c < 3; c++) {
            /* 16384 Bernoulli samples: a standard error under 0.004 */
            double want = inside ? exp(-sigma[c] * 2.0) : 1.0;
            cr_expect_float_eq(mean[c], want, 0.013, "inside %d, channel %d: %g, not %g", inside, c, mean[c], want);
        }
        free(px);
        render_fixture_close(&f);
    }
}
