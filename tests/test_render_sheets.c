/* Shadow rays through thin glass sheets (thindielectric): a diffuse plane
 * seen straight down through a narrow camera, lit by a disk light of
 * radiance L and radius R at height h through a horizontal sheet between
 * them, direct lighting only (max_depth 3: camera, plane, sheet, light).
 * The plane's radiance is rho/pi times
 *   E = 2 pi L \int_0^{theta_max} T(theta) cos(theta) sin(theta) dtheta,
 * tan(theta_max) = R / h, where T = 1 - R' is the sheet's transmittance
 * (R' = R + T^2 R / (1 - R^2), R the Fresnel reflectance, computed here from
 * the s and p amplitudes). Next-event estimation reaches the light through the
 * sheet; without that (Mitsuba blocks shadow rays at every surface) only
 * BSDF-sampled paths see the light, with the same mean and far more noise,
 * and if the paths sampled through the sheet were weighted as if nothing
 * else had found the light the mean would come out too bright. */
#include "test_render_util.h"

static const char *sheet_fmt =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/></integrator>\n"
    "  <sensor type=\"perspective\"><float name=\"fov\" value=\"1\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0.2, 0\" target=\"0, 0, 0\" up=\"0, 0, -1\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"128\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"10\"/></transform>\n"
    "    <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"10\"/>"
    "<translate y=\"0.5\"/></transform>\n"
    "    <bsdf type=\"thindielectric\"><float name=\"int_ior\" value=\"%g\"/></bsdf></shape>\n"
    "  <shape type=\"disk\"><transform name=\"to_world\"><scale value=\"%g\"/><rotate x=\"1\" angle=\"90\"/>"
    "<translate y=\"%g\"/></transform>\n"
    "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>\n"
    "</scene>\n";

/* Unpolarised Fresnel reflectance from the s and p amplitudes, light in
 * the medium of index 1 meeting one of index eta. */
static double fresnel_ref(double cos_i, double eta)
{
    double sin_t = sqrt(1 - cos_i * cos_i) / eta, cos_t = sqrt(1 - sin_t * sin_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

static double sheet_transmittance(double cos_i, double eta)
{
    double r = fresnel_ref(cos_i, eta), t = 1 - r;
    return 1 - (r + t * t * r / (1 - r * r));
}

/* The closed form above by the midpoint rule. */
static double expected_radiance(double int_ior, double radius, double height)
{
    const double rho = 0.5, L = 2.0, eta = int_ior / 1.000277; /* Mitsuba's default ext_ior: air */
    double theta_max = atan(radius / height), e = 0;
    enum { STEPS = 20000 };
    for (int i = 0; i < STEPS; i++) {
        double th = (i + 0.5) * theta_max / STEPS;
        e += sheet_transmittance(cos(th), eta) * cos(th) * sin(th) * theta_max / STEPS;
    }
    return rho / M_PI * 2 * M_PI * L * e;
}

/* Mean and relative standard deviation over the pixels (green channel). */
static void render_sheet(double int_ior, double radius, double height, double *mean, double *rel_sd)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[4096], path[256];
    snprintf(xml, sizeof xml, sheet_fmt, int_ior, radius, height);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 5, 2, 0, &w, &h, &nch);
    double s = 0, s2 = 0;
    for (int i = 0; i < w * h; i++) {
        s += px[i * nch + 1];
        s2 += px[i * nch + 1] * (double)px[i * nch + 1];
    }
    int n = w * h;
    *mean = s / n;
    *rel_sd = sqrt(fmax(s2 / n - *mean * *mean, 0)) / *mean;
    free(px);
    render_fixture_close(&f);
}

/* A large light (found by BSDF sampling often): the two estimators' MIS
 * weights must sum to one through the sheet. */
Test(render_sheets, large_light_through_glass_matches_closed_form)
{
    const double iors[] = {1.000277, 1.5, 2.4};
    for (int i = 0; i < 3; i++) {
        double mean, sd, want = expected_radiance(iors[i], 1.5, 1.0);
        render_sheet(iors[i], 1.5, 1.0, &mean, &sd);
        cr_expect_float_eq(mean, want, 0.01 * want, "ior %g: %g, expected %g", iors[i], mean, want);
    }
    /* The sheet is not transparent: the glass of ior 1.5 takes 8 to 10%. */
    cr_expect_lt(expected_radiance(1.5, 1.5, 1.0), 0.93 * expected_radiance(1.000277, 1.5, 1.0));
}

/* A small light (BSDF sampling finds it in ~2% of the paths): the estimate
 * is as smooth behind glass as in the open. */
Test(render_sheets, small_light_through_glass_is_not_noisy)
{
    double mean, sd, want = expected_radiance(1.5, 0.3, 2.0);
    render_sheet(1.5, 0.3, 2.0, &mean, &sd);
    cr_expect_float_eq(mean, want, 0.01 * want, "%g, expected %g", mean, want);
    cr_expect_lt(sd, 0.02, "relative noise %g over the pixels", sd);
}
