/* The integrators direct, depth, aov and moment, against references worked
 * out here: a plane's distance, the closed-form irradiance of a diffuse
 * plane under a sphere light and a point light (each strategy of `direct`
 * alone and combined), the geometry of a unit sphere seen orthographically
 * (positions, normals, uv and dp/du of Mitsuba's parametrisation), the
 * nested integrator's image bit for bit, and the variance of one sample
 * measured over independent renders. */
#include "test_render_util.h"

#include <math.h>

/* A rendered film with its channel names, developed. */
typedef struct {
    film_t film;
    float *px;
} rendered;

static void render_xml(const char *xml, long long seed, int threads, rendered *r)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256], err[1024];
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    scene_options o = scene_options_default();
    o.seed = seed;
    scene_t *s = scene_create_from_file(path, NULL, 0, &o, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    render_options ro = {.threads = threads};
    cr_assert_eq(render_scene(s, &ro, &r->film, NULL, err, sizeof err), 0, "%s", err);
    r->px = malloc(sizeof(float) * (size_t)r->film.width * r->film.height * r->film.nchannels);
    cr_assert_not_null(r->px);
    film_develop(&r->film, r->px);
    scene_destroy(s);
    render_fixture_close(&f);
}

static void rendered_free(rendered *r)
{
    film_free(&r->film);
    free(r->px);
}

static int channel(const rendered *r, const char *name)
{
    for (int c = 0; c < r->film.nchannels; c++)
        if (strcmp(r->film.names[c], name) == 0)
            return c;
    cr_assert_fail("no channel %s", name);
    return -1;
}

static double value(const rendered *r, int x, int y, int c)
{
    return r->px[((size_t)y * r->film.width + x) * r->film.nchannels + c];
}

/* An orthographic camera 4 units wide along +z from z = -5, box filter. */
#define ORTHO_SENSOR(spp, size)                                                                                    \
    "<sensor type=\"orthographic\"><transform name=\"to_world\"><scale x=\"2\" y=\"2\" z=\"1\"/>"                  \
    "<translate z=\"-5\"/></transform><sampler type=\"independent\"><integer name=\"sample_count\" value=\"" spp   \
    "\"/></sampler><film type=\"hdrfilm\"><integer name=\"width\" value=\"" size "\"/>"                            \
    "<integer name=\"height\" value=\"" size "\"/><rfilter type=\"box\"/></film></sensor>"

Test(render_integrators, depth_is_the_distance_to_a_tilted_plane)
{
    rendered r;
    render_xml("<scene version=\"3.0.0\"><integrator type=\"depth\"/>" ORTHO_SENSOR("64", "16")
               "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/>"
               "<rotate y=\"1\" angle=\"30\"/><translate z=\"1\"/></transform></shape></scene>",
               1, 2, &r);
    /* The plane through (0, 0, 1) with normal (sin 30, 0, cos 30): along +z
     * from (x, y, -4.99) it is met after 5.99 - x tan 30 (x the local x:
     * 2 - 4 (i + 1/2) / 16, linear over the pixel, so its mean is exact). */
    for (int y = 0; y < 16; y++)
        for (int i = 0; i < 16; i++) {
            double x = 2.0 - 4.0 * (i + 0.5) / 16;
            double want = 5.99 - x * tan(30.0 * M_PI / 180.0);
            cr_assert_float_eq(value(&r, i, y, 0), want, 4.0 * 0.25 * tan(M_PI / 6) / sqrt(12.0 * 64),
                               "pixel (%d, %d): %g, want %g", i, y, value(&r, i, y, 0), want);
            cr_assert_eq(value(&r, i, y, 1), value(&r, i, y, 0), "gray");
        }
    rendered_free(&r);
}

/* A diffuse plane of albedo 0.8 seen straight down; its radiance is
 * 0.8 / pi times the irradiance. */
static double plane_radiance(const char *integrator, const char *emitter)
{
    char xml[4096];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\">%s"
             "<sensor type=\"perspective\"><float name=\"fov\" value=\"1\"/>"
             "<transform name=\"to_world\"><lookat origin=\"0, 0.5, 0\" target=\"0, 0, 0\" up=\"0, 0, -1\"/></transform>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"64\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>"
             "</sensor><shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/>"
             "<scale value=\"10\"/></transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf>"
             "</shape>%s</scene>",
             integrator, emitter);
    rendered r;
    render_xml(xml, 3, 2, &r);
    double sum = 0.0;
    for (int i = 0; i < 64; i++)
        sum += r.px[i * r.film.nchannels + 1];
    rendered_free(&r);
    return sum / 64;
}

Test(render_integrators, direct_strategies_match_the_closed_form_irradiance, .timeout = 60)
{
    /* A sphere of radiance 10, radius 0.5, centre 2 above: E = pi L (R/d)^2. */
    const char *sphere = "<shape type=\"sphere\"><point name=\"center\" value=\"0, 2, 0\"/>"
                         "<float name=\"radius\" value=\"0.5\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"10\"/>"
                         "</emitter></shape>";
    const double want = 0.8 / M_PI * M_PI * 10.0 * 0.0625;
    const char *integrators[] = {
        "<integrator type=\"direct\"/>",
        "<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"3\"/>"
        "<integer name=\"bsdf_samples\" value=\"0\"/></integrator>",
        "<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"0\"/>"
        "<integer name=\"bsdf_samples\" value=\"8\"/></integrator>",
        "<integrator type=\"direct\"><integer name=\"shading_samples\" value=\"2\"/></integrator>",
    };
    /* BSDF sampling alone is the noisiest: a 3% tolerance covers it. */
    const double tol[] = {0.02, 0.02, 0.05, 0.02};
    for (int i = 0; i < 4; i++) {
        double got = plane_radiance(integrators[i], sphere);
        cr_log_info("direct %d: %.5f, closed form %.5f", i, got, want);
        cr_assert_float_eq(got, want, tol[i] * want, "%s: %g, want %g", integrators[i], got, want);
    }
    /* A point light of intensity 3 at height 2: E = 3 / 4, whatever the
     * number of emitter samples (Mitsuba would count it 4 times here). */
    double lp = plane_radiance("<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"4\"/>"
                               "</integrator>",
                               "<emitter type=\"point\"><point name=\"position\" value=\"0, 2, 0\"/>"
                               "<rgb name=\"intensity\" value=\"3\"/></emitter>");
    cr_assert_float_eq(lp, 0.8 / M_PI * 0.75, 1e-3 * lp, "point: %g", lp);
}

/* A unit sphere at the origin seen orthographically: positions, normals, uv
 * and dp/du of Mitsuba's parametrisation at pixels well inside the disc, and
 * the nested path integrator's image equal to path's own, bit for bit. */
Test(render_integrators, aov_sphere_geometry_and_nested_image)
{
    const char *scene_fmt = "<scene version=\"3.0.0\">%s" ORTHO_SENSOR("64", "32")
                            "<shape type=\"sphere\"/><emitter type=\"constant\"/></scene>";
    char xml[4096];
    snprintf(xml, sizeof xml, scene_fmt,
             "<integrator type=\"aov\"><string name=\"aovs\" value=\"pp:position, nn:geo_normal,sn:sh_normal, tex:uv,"
             " du:dp_du, dd.y:depth, id:shape_index\"/><integrator type=\"path\" name=\"img\"/></integrator>");
    rendered a, p;
    render_xml(xml, 7, 2, &a);
    snprintf(xml, sizeof xml, scene_fmt, "<integrator type=\"path\"/>");
    render_xml(xml, 7, 1, &p);
    cr_assert_eq(a.film.nchannels, 3 + 4 + 3 + 3 + 3 + 2 + 3 + 1 + 1, "R G B, img.R G B A, the AOVs");
    int img = channel(&a, "img.R"), pos = channel(&a, "pp.X"), ng = channel(&a, "nn.X"), sn = channel(&a, "sn.X");
    int uv = channel(&a, "tex.U"), du = channel(&a, "du.X"), depth = channel(&a, "dd.y.T"), id = channel(&a, "id.I");
    cr_assert_eq(channel(&a, "img.A"), img + 3);
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) {
            cr_assert_eq(value(&a, x, y, 0), value(&p, x, y, 0), "the image is the nested path's");
            cr_assert_eq(value(&a, x, y, img), value(&p, x, y, 0), "img.R is path's image");
            double lx = 2.0 - 4.0 * (x + 0.5) / 32, ly = 2.0 - 4.0 * (y + 0.5) / 32;
            if (hypot(lx, ly) > 0.6) /* the AOVs vary over a pixel: compare where they vary slowly */
                continue;
            vec3 want = v3(lx, ly, -sqrt(1.0 - lx * lx - ly * ly));
            vec3 got = v3(value(&a, x, y, pos), value(&a, x, y, pos + 1), value(&a, x, y, pos + 2));
            cr_assert_lt(v3_len(v3_sub(got, want)), 0.03, "position at (%d, %d)", x, y);
            for (int c = 0; c < 3; c++) {
                cr_assert_float_eq(value(&a, x, y, ng + c), value(&a, x, y, pos + c), 0.03, "unit sphere: n = p");
                cr_assert_float_eq(value(&a, x, y, sn + c), value(&a, x, y, ng + c), 1e-6, "no perturbation");
            }
            /* Mitsuba's sphere: uv = (phi / 2 pi, theta / pi), dp/du = 2 pi (-y, x, 0). */
            double phi = atan2(want.y, want.x);
            double u = (phi < 0 ? phi + 2 * M_PI : phi) / (2 * M_PI), v = acos(want.z) / M_PI;
            if (fabs(u - 0.5) < 0.45 && hypot(lx, ly) > 0.3) /* away from the seam and the pole */
                cr_assert_float_eq(value(&a, x, y, uv), u, 0.02, "u at (%d, %d)", x, y);
            cr_assert_float_eq(value(&a, x, y, uv + 1), v, 0.02, "v at (%d, %d)", x, y);
            cr_assert_float_eq(value(&a, x, y, du), -2 * M_PI * want.y, 0.15);
            cr_assert_float_eq(value(&a, x, y, du + 1), 2 * M_PI * want.x, 0.15);
            cr_assert_float_eq(value(&a, x, y, depth), 4.99 - sqrt(1.0 - lx * lx - ly * ly), 0.03);
            cr_assert_eq(value(&a, x, y, id), 1.0, "the first shape");
        }
    rendered_free(&a);
    rendered_free(&p);
}

Test(render_integrators, aov_refuses_what_it_cannot_make)
{
    char err[1024];
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    render_write_file(&f, "scene.xml",
                      "<scene version=\"3.0.0\"><integrator type=\"aov\">\n"
                      "<string name=\"aovs\" value=\"d:duv_dx\"/></integrator><sensor type=\"perspective\"/></scene>",
                      path, sizeof path);
    cr_assert_null(scene_create_from_file(path, NULL, 0, NULL, err, sizeof err));
    cr_assert_not_null(strstr(err, "scene.xml:1: <integrator type=\"aov\">: AOV type 'duv_dx' needs ray "
                                   "differentials"), "%s", err);
    render_fixture_close(&f);
}

/* Y of a linear sRGB colour (the test's own copy of the CIE matrix row). */
static double luminance_y(double r, double g, double b) { return 0.212671 * r + 0.715160 * g + 0.072169 * b; }

/* A diffuse sphere in a white furnace at a few bounces: each pixel's one
 * sample varies. The moment integrator's m2 - m1^2 over 256 samples is the
 * variance of one sample's Y; 64 renders of one sample each (other seeds)
 * measure the same variance directly. */
Test(render_integrators, moment_variance_matches_the_sample_variance, .timeout = 120)
{
    const char *fmt = "<scene version=\"3.0.0\">%s"
                      "<sensor type=\"perspective\"><float name=\"fov\" value=\"45\"/>"
                      "<transform name=\"to_world\"><lookat origin=\"0, 0, -3\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>"
                      "</transform><sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>"
                      "<film type=\"hdrfilm\"><integer name=\"width\" value=\"12\"/><integer name=\"height\" value=\"12\"/>"
                      "<rfilter type=\"box\"/></film></sensor>"
                      "<shape type=\"sphere\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.6, 0.7, 0.8\"/>"
                      "</bsdf></shape><emitter type=\"envmap\"><string name=\"filename\" value=\"%s\"/></emitter></scene>";
    /* A bright band in the environment makes the samples vary. */
    render_fixture f;
    render_fixture_open(&f);
    char env[256], err[256];
    snprintf(env, sizeof env, "%s/env.exr", f.dir);
    float texels[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; i++)
        texels[i] = i / 3 >= 8 && i / 3 < 16 ? 4.0f : 0.5f;
    const char *names[3] = {"R", "G", "B"};
    cr_assert_eq(exr_write_float(env, 8, 4, 3, names, texels, NULL, err, sizeof err), 0, "%s", err);
    const char *path_int = "<integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/></integrator>";
    char xml[4096], moment[256];
    snprintf(moment, sizeof moment, "<integrator type=\"moment\">%s</integrator>", path_int);
    snprintf(xml, sizeof xml, fmt, moment, 256, env);
    rendered m;
    render_xml(xml, 1, 2, &m);
    int y1 = channel(&m, "_arg_0.Y"), y2 = channel(&m, "m2__arg_0.Y");
    cr_assert_eq(channel(&m, "m2__arg_0.X"), y2 - 1);
    const int K = 64, npix = 144;
    double *sum = calloc(npix, sizeof *sum), *sum2 = calloc(npix, sizeof *sum2);
    snprintf(xml, sizeof xml, fmt, path_int, 1, env);
    for (int k = 0; k < K; k++) {
        rendered one;
        render_xml(xml, 100 + k, 2, &one);
        for (int p = 0; p < npix; p++) {
            const float *v = one.px + p * one.film.nchannels;
            double y = luminance_y(v[0], v[1], v[2]);
            sum[p] += y, sum2[p] += y * y;
        }
        rendered_free(&one);
    }
    double var_moment = 0.0, var_sample = 0.0, mean_moment = 0.0, mean_sample = 0.0;
    for (int p = 0; p < npix; p++) {
        double a = m.px[p * m.film.nchannels + y1], b = m.px[p * m.film.nchannels + y2];
        cr_assert_geq(b, a * a * (1 - 1e-5), "m2 >= m1^2");
        cr_assert_float_eq(a, luminance_y(m.px[p * m.film.nchannels], m.px[p * m.film.nchannels + 1],
                                          m.px[p * m.film.nchannels + 2]),
                           1e-5 * (1 + a), "the mean's Y is the image's");
        var_moment += (b - a * a) / npix;
        mean_moment += a / npix;
        double mean = sum[p] / K;
        var_sample += (sum2[p] - K * mean * mean) / (K - 1) / npix;
        mean_sample += mean / npix;
    }
    cr_log_info("moment: mean %.4f vs %.4f, variance %.4f vs sample variance %.4f", mean_moment, mean_sample,
                var_moment, var_sample);
    cr_assert_gt(var_sample, 0.01, "the samples vary");
    cr_assert_float_eq(var_moment, var_sample, 0.06 * var_sample, "variance %g, sample variance %g", var_moment,
                       var_sample);
    cr_assert_float_eq(mean_moment, mean_sample, 0.03 * mean_sample);
    free(sum);
    free(sum2);
    rendered_free(&m);
    render_fixture_close(&f);
}
