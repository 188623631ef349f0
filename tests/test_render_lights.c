/* Emitters against closed forms: a diffuse plane (albedo rho) seen straight
 * down through a narrow camera, lit by one emitter, direct lighting only.
 * Its radiance is rho/pi times the irradiance E:
 *   point light, intensity I at height d:      E = I / d^2
 *   directional light, irradiance E0 along -y: E = E0
 *   disk of radiance L, radius R at height h:  E = pi L R^2 / (h^2 + R^2)
 *   sphere of radiance L, radius R, centre at distance d: E = pi L (R/d)^2 cos
 *   rectangle of radiance L parallel to the plane: E = pi L F, F its form
 *   factor (inclusion-exclusion of corner-anchored rectangles)
 * and the envmap's orientation, sampling density and lighting. Many lights
 * at once check the light tree's picks against the MIS weights: the sum of
 * their closed forms comes out only if both use the same probabilities. */
#include "celadon/film.h"
#include "celadon/rng.h"
#include "support/plugin_xml.h"
#include "test_bsdf_support.h"
#include "test_render_util.h"

static const char *plane_fmt =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>\n"
    "  <sensor type=\"perspective\"><float name=\"fov\" value=\"1\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0.5, 0\" target=\"0, 0, 0\" up=\"0, 0, -1\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"10\"/></transform>\n"
    "    <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf></shape>\n"
    "  %s\n"
    "</scene>\n";

/* The mean radiance of the plane's pixels at spp samples per pixel. */
static double plane_radiance_spp(const char *emitter, int spp)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[16384], path[256];
    snprintf(xml, sizeof xml, plane_fmt, spp, emitter);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 3, 2, 0, &w, &h, &nch);
    double sum = 0.0;
    for (int i = 0; i < w * h; i++)
        sum += px[i * nch + 1];
    free(px);
    render_fixture_close(&f);
    return sum / (w * h);
}

static double plane_radiance(const char *emitter) { return plane_radiance_spp(emitter, 64); }

Test(render_lights, point_and_directional)
{
    const double rho = 0.8;
    double lp = plane_radiance("<emitter type=\"point\"><point name=\"position\" value=\"0, 2, 0\"/>"
                               "<rgb name=\"intensity\" value=\"3\"/></emitter>");
    cr_expect_float_eq(lp, rho / M_PI * 3.0 / 4.0, 1e-3 * lp, "point: %g", lp);
    double ld = plane_radiance("<emitter type=\"directional\"><vector name=\"direction\" value=\"0, -1, 0\"/>"
                               "<rgb name=\"irradiance\" value=\"2\"/></emitter>");
    cr_expect_float_eq(ld, rho / M_PI * 2.0, 1e-6, "directional: %g", ld);
}

Test(render_lights, disk_and_sphere_area_lights)
{
    const double rho = 0.8;
    double ldisk = plane_radiance("<shape type=\"disk\"><transform name=\"to_world\"><scale value=\"1.5\"/>"
                                  "<rotate x=\"1\" angle=\"90\"/><translate y=\"1\"/></transform>"
                                  "<emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>");
    double e_disk = M_PI * 2.0 * 2.25 / (1.0 + 2.25);
    cr_expect_float_eq(ldisk, rho / M_PI * e_disk, 0.02 * ldisk, "disk: %g, want %g", ldisk, rho / M_PI * e_disk);
    double lsph = plane_radiance("<shape type=\"sphere\"><point name=\"center\" value=\"0, 2, 0\"/>"
                                 "<float name=\"radius\" value=\"0.5\"/>"
                                 "<emitter type=\"area\"><rgb name=\"radiance\" value=\"10\"/></emitter></shape>");
    double e_sph = M_PI * 10.0 * 0.0625;
    cr_expect_float_eq(lsph, rho / M_PI * e_sph, 0.02 * lsph, "sphere: %g, want %g", lsph, rho / M_PI * e_sph);
}

/* Brute-force direct light, independent of the emitters' sampling: the
 * irradiance at the origin (normal +y) from a planar emitter of radiance L,
 * summed over a fine grid of the hemisphere's directions (midpoint rule in
 * theta and phi, d(omega) = sin(theta) d(theta) d(phi)), each direction
 * intersected with the emitter. The emitter: the unit square (or disk) of
 * the z = 0 plane, scaled by (sx, sy), rotated about x by ax degrees, then
 * about y by ay, then moved by t; it emits on the side its +z faces. */
typedef struct {
    double sx, sy, ax, ay;
    vec3 t;
    int disk;
} planar_emitter;

static vec3 rotate_xy(vec3 v, double ax, double ay)
{
    double a = ax * M_PI / 180.0, b = ay * M_PI / 180.0;
    vec3 r = v3(v.x, v.y * cos(a) - v.z * sin(a), v.y * sin(a) + v.z * cos(a));
    return v3(r.x * cos(b) + r.z * sin(b), r.y, -r.x * sin(b) + r.z * cos(b));
}

static double brute_force_irradiance(const planar_emitter *e, double radiance)
{
    vec3 e1 = rotate_xy(v3(e->sx, 0, 0), e->ax, e->ay), e2 = rotate_xy(v3(0, e->sy, 0), e->ax, e->ay);
    vec3 n = rotate_xy(v3(0, 0, 1), e->ax, e->ay);
    enum { NT = 1500, NP = 3000 };
    double sum = 0.0, dt = 0.5 * M_PI / NT, dp = 2.0 * M_PI / NP;
    for (int i = 0; i < NT; i++) {
        double th = (i + 0.5) * dt;
        for (int j = 0; j < NP; j++) {
            double ph = (j + 0.5) * dp;
            vec3 d = v3(sin(th) * cos(ph), cos(th), sin(th) * sin(ph));
            double dn = v3_dot(d, n);
            if (dn >= 0.0) /* parallel, or the emitter's back */
                continue;
            double t = v3_dot(e->t, n) / dn;
            if (t <= 0.0)
                continue;
            vec3 q = v3_sub(v3_scale(d, t), e->t);
            double u = v3_dot(q, e1) / v3_dot(e1, e1), v = v3_dot(q, e2) / v3_dot(e2, e2);
            if (e->disk ? u * u + v * v <= 1.0 : fabs(u) <= 1.0 && fabs(v) <= 1.0)
                sum += cos(th) * sin(th);
        }
    }
    return radiance * sum * dt * dp;
}

/* A tilted rectangle and a tilted disk, off the axis: the light sampled
 * by area (its pdf converted to solid angle, the cosine at the light)
 * against the hemisphere's brute force. */
Test(render_lights, tilted_area_lights_against_a_brute_force_hemisphere, .timeout = 120)
{
    const double rho = 0.8, radiance = 3.0;
    static const planar_emitter lights[] = {
        {0.6, 0.3, 115.0, 30.0, {0.5, 1.0, 0.3}, 0},
        {0.4, 0.4, 70.0, -40.0, {-0.6, 0.8, -0.2}, 1},
    };
    for (size_t k = 0; k < sizeof lights / sizeof *lights; k++) {
        const planar_emitter *e = &lights[k];
        char xml[1024];
        snprintf(xml, sizeof xml,
                 "<shape type=\"%s\"><transform name=\"to_world\"><scale x=\"%g\" y=\"%g\"/>"
                 "<rotate x=\"1\" angle=\"%g\"/><rotate y=\"1\" angle=\"%g\"/>"
                 "<translate x=\"%g\" y=\"%g\" z=\"%g\"/></transform>"
                 "<emitter type=\"area\"><rgb name=\"radiance\" value=\"%g\"/></emitter></shape>",
                 e->disk ? "disk" : "rectangle", e->sx, e->sy, e->ax, e->ay, e->t.x, e->t.y, e->t.z, radiance);
        double got = plane_radiance(xml), want = rho / M_PI * brute_force_irradiance(e, radiance);
        cr_log_info("%s: rendered %g, brute force %g", e->disk ? "disk" : "rectangle", got, want);
        cr_expect_gt(want, 0.01, "the emitter does not light the origin");
        cr_expect_float_eq(got, want, 0.02 * want, "%s: rendered %g, brute force %g", e->disk ? "disk" : "rectangle",
                           got, want);
    }
}

/* The form factor from a point to the rectangle [0,a] x [0,b] parallel to
 * its plane at height h, the corner above the point. */
static double corner_form_factor(double a, double b, double h)
{
    double x = a / h, y = b / h;
    return (x / sqrt(1.0 + x * x) * atan(y / sqrt(1.0 + x * x)) + y / sqrt(1.0 + y * y) * atan(x / sqrt(1.0 + y * y))) /
           (2.0 * M_PI);
}

/* A 2 x 1.2 rectangle light facing down at height 0.6 above the origin,
 * its centre off to the side (spherical rectangles, large solid angle). */
Test(render_lights, rectangle_light)
{
    const double rho = 0.8, L = 2.0, h = 0.6, x0 = -0.4, x1 = 1.6, z0 = -0.3, z1 = 0.9;
    double lr = plane_radiance_spp("<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"1\" y=\"0.6\"/>"
                               "<rotate x=\"1\" angle=\"90\"/><translate x=\"0.6\" y=\"0.6\" z=\"0.3\"/></transform>"
                               "<emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>",
                               1024);
    /* [x0,x1] x [z0,z1] = four corner rectangles around the origin. */
    double F = corner_form_factor(x1, z1, h) + corner_form_factor(-x0, z1, h) + corner_form_factor(x1, -z0, h) +
               corner_form_factor(-x0, -z0, h);
    double want = rho / M_PI * M_PI * L * F;
    cr_expect_float_eq(lr, want, 0.01 * want, "rectangle: %g, want %g", lr, want);
}

/* Twelve sphere lights of different sizes and radiances, near and far,
 * some large and close (where BSDF sampling takes a real share of the MIS
 * weight), and an environment: E = sum of pi L_i (R_i/d_i)^2 cos(theta_i)
 * (each sphere wholly above the plane) + pi L_env. */
Test(render_lights, many_lights_through_the_light_tree)
{
    const double rho = 0.8, env = 0.05;
    char body[8192];
    int n = snprintf(body, sizeof body, "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"%g\"/></emitter>", env);
    double e = M_PI * env;
    for (int i = 0; i < 12; i++) {
        double r = 0.05 + 0.04 * i, L = 1.0 + (i * 7 % 5), a = 0.5236 * i;
        vec3 c = v3((0.3 + 0.25 * i) * cos(a), r + 0.02 + 0.15 * (i % 4), (0.3 + 0.25 * i) * sin(a));
        double d = v3_len(c);
        e += M_PI * (L - env) * (r / d) * (r / d) * (c.y / d); /* it hides that much environment */
        n += snprintf(body + n, sizeof body - (size_t)n,
                      "<shape type=\"sphere\"><point name=\"center\" value=\"%.17g, %.17g, %.17g\"/>"
                      "<float name=\"radius\" value=\"%.17g\"/><emitter type=\"area\">"
                      "<rgb name=\"radiance\" value=\"%g\"/></emitter></shape>",
                      c.x, c.y, c.z, r, L);
    }
    double l = plane_radiance_spp(body, 1024), want = rho / M_PI * e;
    cr_expect_float_eq(l, want, 0.01 * want, "twelve spheres: %g, want %g", l, want);
}

/* The envmap of w x h RGB texels px, written to path as a float EXR. */
static const emitter_t *envmap_of(plugin_xml *fx, const char *path, int w, int h, const float *px)
{
    char err[256], xml[400];
    const char *names[] = {"R", "G", "B"};
    cr_assert_eq(exr_write_float(path, w, h, 3, names, px, NULL, err, sizeof err), 0, "%s", err);
    snprintf(xml, sizeof xml, "<emitter type='envmap'><string name='filename' value='%s'/></emitter>", path);
    const emitter_t *env = plugin_xml_emitter(fx, xml, err, sizeof err);
    cr_assert_not_null(env, "%s", err);
    return env;
}

/* A 4x2 envmap with a distinct value per texel: Mitsuba's convention puts
 * the top row around +y, u = 0 at -z, u = 0.25 at +x, u = 0.5 at +z. The
 * direction of (u, v) is (sin t sin p, cos t, -sin t cos p), p = 2 pi u,
 * t = pi v; column c is centred on u = (c + 0.5) / 4 and row r lies at
 * v = r / (2 - 1), i.e. the rows are the poles, interpolated bilinearly. */
Test(render_lights, envmap_orientation_and_density)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    snprintf(path, sizeof path, "%s/env.exr", f.dir);
    float px[4 * 2 * 3];
    for (int i = 0; i < 8; i++)
        px[3 * i] = px[3 * i + 1] = px[3 * i + 2] = (float)(i + 1);
    plugin_xml fx;
    plugin_xml_open(&fx);
    const emitter_t *env = envmap_of(&fx, path, 4, 2, px);
    const double s = sqrt(0.5);
    /* phi = atan2(x, -z): column 0's centre is x > 0, z < 0; column 1 x > 0,
     * z > 0; column 2 x < 0, z > 0; column 3 x < 0, z < 0. At theta = 45
     * degrees (v = 1/4) a column c holds 3/4 (c + 1) + 1/4 (c + 5) = c + 2,
     * at 135 degrees c + 4. */
    cr_expect_float_eq(emitter_eval_env(env, v3(0.5, s, -0.5)).g, 2.0, 1e-6);
    cr_expect_float_eq(emitter_eval_env(env, v3(0.5, s, 0.5)).g, 3.0, 1e-6);
    cr_expect_float_eq(emitter_eval_env(env, v3(-0.5, s, 0.5)).g, 4.0, 1e-6);
    cr_expect_float_eq(emitter_eval_env(env, v3(-0.5, s, -0.5)).g, 5.0, 1e-6);
    cr_expect_float_eq(emitter_eval_env(env, v3(-0.5, -s, -0.5)).g, 7.0, 1e-6);
    /* between column centres 0 and 1 (u = 1/4, +x) and on the seam (u = 0,
     * -z: halfway between column 3 and column 0) */
    cr_expect_float_eq(emitter_eval_env(env, v3(s, s, 0.0)).g, 2.5, 1e-6);
    cr_expect_float_eq(emitter_eval_env(env, v3(0.0, s, -s)).g, 3.5, 1e-6);
    /* Sampled directions carry the density emitter_pdf_env reports, and
     * the density integrates to 1 over the sphere. */
    rng_t rng;
    rng_seed(&rng, 9, 1);
    double integral = 0.0;
    enum { N = 20000 };
    for (int i = 0; i < N; i++) {
        emitter_sample_rec es;
        vec2 u = v2(rng_next_double(&rng), rng_next_double(&rng));
        if (emitter_sample(env, v3(0, 0, 0), v3(u.x, u.y, 0.0), &es)) {
            cr_assert_float_eq(emitter_pdf_env(env, es.wi), es.pdf, 1e-6 * es.pdf);
            cr_assert_float_eq(emitter_eval_env(env, es.wi).g, es.value.g, 1e-9);
        }
        vec3 w = warp_square_to_uniform_sphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        integral += emitter_pdf_env(env, w) * 4.0 * M_PI / N;
    }
    cr_expect_float_eq(integral, 1.0, 0.03, "density integrates to %g", integral);
    /* The histogram of sampled directions over the texels matches the
     * density MIS weighs them with: texel (c, r) should get N times the
     * integral of emitter_pdf_env over it, pdf(centre) 2 pi^2 sin(theta) / 8
     * (the density is constant per texel in (u, v), whose area element is
     * d omega / (2 pi^2 sin theta)). */
    double obs[8] = {0}, expect[8];
    for (int i = 0; i < N; i++) {
        emitter_sample_rec es;
        cr_assert(emitter_sample(env, v3(0, 0, 0), v3((i + 0.5) / N, rng_next_double(&rng), 0.0), &es));
        double phi = atan2(es.wi.x, -es.wi.z), theta = acos(fmax(-1.0, fmin(1.0, es.wi.y)));
        phi = phi < 0.0 ? phi + 2.0 * M_PI : phi;
        int c = (int)(phi / (2.0 * M_PI) * 4), r = (int)(theta / M_PI * 2);
        obs[(r < 2 ? r : 1) * 4 + (c < 4 ? c : 3)] += 1.0;
    }
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < 4; c++) {
            double theta = M_PI * (r + 0.5) / 2, phi = 2.0 * M_PI * (c + 0.5) / 4;
            vec3 d = v3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
            expect[r * 4 + c] = N * emitter_pdf_env(env, d) * 2.0 * M_PI * M_PI * sin(theta) / 8.0;
        }
    double p = chi2_pvalue_counts(obs, expect, 8, NULL);
    cr_expect_gt(p, chi2_threshold(), "texel histogram: chi-square p = %g", p);
    /* And a plane under it, NEE of the map and BSDF sampling weighed by
     * MIS: averaged over phi, the map is 2.5 + 4 v (the rows' means 2.5 and
     * 6.5 at v = 0 and 1), so E = 2 pi int (2.5 + 4 t / pi) cos t sin t dt
     * over the upper hemisphere = 3.5 pi. */
    char body[512];
    snprintf(body, sizeof body, "<emitter type='envmap'><string name='filename' value='%s'/></emitter>", path);
    double lp = plane_radiance_spp(body, 256), want = 0.8 / M_PI * 3.5 * M_PI;
    cr_expect_float_eq(lp, want, 0.01 * want, "plane under the envmap: %g, want %g", lp, want);
    plugin_xml_close(&fx);
    render_fixture_close(&f);
}

/* An analytic environment L(d) = 1 + 0.5 d.y - 0.4 d.z sampled where
 * Mitsuba puts its texels (column i at phi = 2 pi (i + 0.5) / W, row j at
 * theta = pi j / (H - 1)): the map returns each texel at its own direction
 * exactly, and between texels L within the bilinear error (~1e-3 at 64x32),
 * not the ~3% that a half-texel shift in u or v costs here. */
Test(render_lights, envmap_matches_analytic_environment)
{
    enum { W = 64, H = 32 };
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    snprintf(path, sizeof path, "%s/analytic.exr", f.dir);
    static float px[W * H * 3];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double t = M_PI * j / (H - 1), p = 2.0 * M_PI * (i + 0.5) / W;
            double l = 1.0 + 0.5 * cos(t) + 0.4 * sin(t) * cos(p);
            for (int c = 0; c < 3; c++)
                px[3 * (j * W + i) + c] = (float)l;
        }
    plugin_xml fx;
    plugin_xml_open(&fx);
    const emitter_t *env = envmap_of(&fx, path, W, H, px);
    for (int j = 1; j < H - 1; j += 5)
        for (int i = 0; i < W; i += 7) {
            double t = M_PI * j / (H - 1), p = 2.0 * M_PI * (i + 0.5) / W;
            vec3 d = v3(sin(t) * sin(p), cos(t), -sin(t) * cos(p));
            cr_expect_float_eq(emitter_eval_env(env, d).g, px[3 * (j * W + i) + 1], 1e-5, "texel (%d, %d)", i, j);
        }
    rng_t rng;
    rng_seed(&rng, 27, 1);
    double worst = 0.0;
    for (int k = 0; k < 2000; k++) {
        vec3 d = warp_square_to_uniform_sphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        worst = fmax(worst, fabs(emitter_eval_env(env, d).g - (1.0 + 0.5 * d.y - 0.4 * d.z)));
    }
    cr_expect_lt(worst, 3e-3, "largest error against the analytic environment: %g", worst);
    plugin_xml_close(&fx);
    render_fixture_close(&f);
}

/* Integrator settings: max_depth = 1 shows only emitters seen directly
 * (the sphere is black, the background the environment's 0.5);
 * hide_emitters hides that background too. */
static void depth_one(const char *extra, double want_bg)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[2048], path[256];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"1\"/>%s"
             "</integrator><sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>"
             "<transform name=\"to_world\"><lookat origin=\"0, 0, 4\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/></film>"
             "</sensor><shape type=\"sphere\"/><emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.5\"/></emitter>"
             "</scene>",
             extra);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 1, 2, 0, &w, &h, &nch);
    cr_expect_float_eq(px[(8 * w + 8) * nch], 0.0, 1e-12, "centre (the sphere)");
    cr_expect_float_eq(px[0], want_bg, 1e-12, "corner (the background)");
    free(px);
    render_fixture_close(&f);
}

Test(render_lights, max_depth_one_and_hide_emitters)
{
    depth_one("", 0.5);
    depth_one("<boolean name=\"hide_emitters\" value=\"true\"/>", 0.0);
}
