/* The spot and projector lights on a diffuse plane (albedo 0.8) seen
 * straight down by an orthographic camera, against the formulas worked out
 * here: the spot's falloff profile (full within the beam width, linear in
 * the angle to zero at the cutoff) times cos theta / d^2, and the texture
 * each projects: the quadrants of a checkerboard for the spot, the texels
 * of a 2 x 2 image for the projector, whose constant irradiance is
 * pi scale E / z^2 on a plane at distance z. */
#include "test_render_util.h"

#include <math.h>

enum { N = 48 };

/* The lights sit 2 above the plane y = 0, looking down, local +x along
 * world +x and local +y along world +z; the camera sees x, z in
 * [-1.5, 1.5], image left = +x, image top = +z. */
static float *render_plane(const char *emitter, int spp)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[4096], path[256];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>"
             "<sensor type=\"orthographic\"><transform name=\"to_world\"><scale x=\"1.5\" y=\"1.5\" z=\"1\"/>"
             "<lookat origin=\"0, 3, 0\" target=\"0, 0, 0\" up=\"0, 0, 1\"/></transform>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/><integer name=\"height\" value=\"%d\"/>"
             "<rfilter type=\"box\"/></film></sensor>"
             "<shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"10\"/>"
             "</transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf></shape>%s</scene>",
             spp, N, N, emitter);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 2, 2, 0, &w, &h, &nch);
    render_fixture_close(&f);
    return px;
}

/* The world (x, z) of film position (fx, fy) in pixels. */
static void plane_point(double fx, double fy, double *x, double *z)
{
    *x = 1.5 * (1.0 - 2.0 * fx / N);
    *z = 1.5 * (1.0 - 2.0 * fy / N);
}

/* Mitsuba's spot falloff at angle theta (radians) from the axis. */
static double falloff(double theta, double beam, double cutoff)
{
    return theta >= cutoff ? 0.0 : theta <= beam ? 1.0 : (cutoff - theta) / (cutoff - beam);
}

Test(render_spot_projector, spot_falloff_profile, .timeout = 60)
{
    const double beam = 15 * M_PI / 180, cutoff = 30 * M_PI / 180, intensity = 5.0;
    float *px = render_plane("<emitter type=\"spot\"><rgb name=\"intensity\" value=\"5\"/>"
                             "<float name=\"cutoff_angle\" value=\"30\"/><float name=\"beam_width\" value=\"15\"/>"
                             "<transform name=\"to_world\"><lookat origin=\"0, 2, 0\" target=\"0, 0, 0\" up=\"0, 0, 1\"/>"
                             "</transform></emitter>",
                             64);
    double worst = 0.0, peak = 0.8 / M_PI * intensity / 4.0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            /* The pixel's mean of rho / pi I falloff cos / d^2, on a sub-grid. */
            double want = 0.0;
            for (int a = 0; a < 8; a++)
                for (int b = 0; b < 8; b++) {
                    double x, z;
                    plane_point(i + (a + 0.5) / 8, j + (b + 0.5) / 8, &x, &z);
                    double d2 = 4.0 + x * x + z * z, theta = atan(sqrt(x * x + z * z) / 2.0);
                    want += 0.8 / M_PI * intensity * falloff(theta, beam, cutoff) * (2.0 / sqrt(d2)) / d2 / 64;
                }
            double got = px[(j * N + i) * 3];
            worst = fmax(worst, fabs(got - want));
            cr_assert_float_eq(got, want, 0.03 * peak, "pixel (%d, %d): %g, want %g", i, j, got, want);
        }
    cr_log_info("spot: worst |pixel - profile| = %.4f of a peak %.4f", worst, peak);
    free(px);
}

Test(render_spot_projector, spot_projects_its_texture)
{
    float *px = render_plane("<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"40\"/>"
                             "<texture type=\"checkerboard\" name=\"texture\"><rgb name=\"color0\" value=\"1\"/>"
                             "<rgb name=\"color1\" value=\"0\"/></texture>"
                             "<transform name=\"to_world\"><lookat origin=\"0, 2, 0\" target=\"0, 0, 0\" up=\"0, 0, 1\"/>"
                             "</transform></emitter>",
                             4);
    /* uv = 1/2 + (x, z) / (2 y tan 40): color0 where x and z have the same
     * sign, i.e. in the image's top-left and bottom-right quadrants. */
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            if (abs(2 * i + 1 - N) < 4 || abs(2 * j + 1 - N) < 4 || hypot(i - N / 2.0, j - N / 2.0) > 18)
                continue; /* the seams, and beyond the beam's full width */
            double got = px[(j * N + i) * 3];
            if ((i < N / 2) == (j < N / 2))
                cr_assert_gt(got, 0.01, "pixel (%d, %d) lit", i, j);
            else
                cr_assert_eq(got, 0.0f, "pixel (%d, %d) dark", i, j);
        }
    free(px);
}

Test(render_spot_projector, projector_texels_and_constant_irradiance)
{
    render_fixture f;
    render_fixture_open(&f);
    char tex[256], err[256];
    snprintf(tex, sizeof tex, "%s/proj.exr", f.dir);
    /* Top row red, green; bottom row blue, white. */
    const float texels[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    const char *names[3] = {"R", "G", "B"};
    cr_assert_eq(exr_write_float(tex, 2, 2, 3, names, texels, NULL, err, sizeof err), 0, "%s", err);
    char emitter[1024];
    snprintf(emitter, sizeof emitter,
             "<emitter type=\"projector\"><float name=\"fov\" value=\"40\"/><float name=\"scale\" value=\"0.5\"/>"
             "<texture type=\"bitmap\" name=\"irradiance\"><string name=\"filename\" value=\"%s\"/>"
             "<string name=\"filter_type\" value=\"nearest\"/></texture>"
             "<transform name=\"to_world\"><lookat origin=\"0, 2, 0\" target=\"0, 0, 0\" up=\"0, 0, 1\"/></transform>"
             "</emitter>",
             tex);
    float *px = render_plane(emitter, 4);
    /* rho scale E / z^2 = 0.8 x 0.5 x E / 4 inside the frustum (half width
     * 2 tan 20 = 0.728), the texel of (u, v) = 1/2 - (x, z) / (2 z tan 20). */
    const double half = 2.0 * tan(20.0 * M_PI / 180.0);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double x0, z0, x1, z1;
            plane_point(i, j, &x0, &z0);
            plane_point(i + 1, j + 1, &x1, &z1);
            double xlo = fmin(x0, x1), xhi = fmax(x0, x1), zlo = fmin(z0, z1), zhi = fmax(z0, z1);
            const float *p = px + (j * N + i) * 3;
            if (xlo > half || xhi < -half || zlo > half || zhi < -half) {
                cr_assert(p[0] == 0 && p[1] == 0 && p[2] == 0, "pixel (%d, %d) outside the frustum", i, j);
                continue;
            }
            if (xhi > half || xlo < -half || zhi > half || zlo < -half || (xlo < -1e-9 && xhi > 1e-9) ||
                (zlo < -1e-9 && zhi > 1e-9))
                continue; /* pixels across an edge */
            const float *t = texels + 3 * ((zlo + zhi > 0 ? 0 : 2) + (xlo + xhi > 0 ? 0 : 1));
            for (int c = 0; c < 3; c++)
                cr_assert_float_eq(p[c], 0.1 * t[c], 1e-5, "pixel (%d, %d) channel %d: %g, want %g", i, j, c, p[c],
                                   0.1 * t[c]);
        }
    free(px);
    render_fixture_close(&f);
}
