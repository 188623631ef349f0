/* The curve shapes (`linearcurve`, `bsplinecurve`, traced by Embree's round
 * curves) against the exact `cylinder`: a straight tube of constant radius,
 * seen from the side away from its ends, has the cylinder's depth at every
 * pixel, for a linear curve and for a B-spline whose control points lie
 * evenly on a line (its centre is then that line); and curve files that are
 * not curves are refused naming the file. */
#include <math.h>

#include "test_render_util.h"

static const char *tube_xml =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>\n"
    "  <sensor type=\"orthographic\">\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"24\"/></film>\n"
    "  </sensor>\n"
    "  <emitter type=\"constant\"/>\n"
    "  %s\n"
    "</scene>\n";

/* The depth channel of the tube scene with shape, 24 x 24 (malloc'd). */
static float *tube_depth(render_fixture *f, const char *shape)
{
    char xml[4096], path[256];
    snprintf(xml, sizeof xml, tube_xml, shape);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 5, 1, RENDER_AOV_DEPTH, &w, &h, &nch);
    cr_assert(w == 24 && h == 24 && nch >= 4);
    float *d = malloc(sizeof *d * 24 * 24);
    cr_assert_not_null(d);
    for (int i = 0; i < 24 * 24; i++)
        d[i] = px[i * nch + 3];
    free(px);
    return d;
}

Test(render_curves, straight_curves_have_the_depth_of_the_exact_cylinder)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    render_write_file(&f, "line.txt", "-3 0 0 0.5\n0 0 0 0.5\n3 0 0 0.5\n", path, sizeof path);
    render_write_file(&f, "spline.txt", "-6 0 0 0.5\n-3 0 0 0.5\n0 0 0 0.5\n3 0 0 0.5\n6 0 0 0.5\n", path, sizeof path);
    float *cyl = tube_depth(&f, "<shape type=\"cylinder\"><point name=\"p0\" value=\"-3, 0, 0\"/>"
                                "<point name=\"p1\" value=\"3, 0, 0\"/><float name=\"radius\" value=\"0.5\"/></shape>");
    const char *curves[2] = {"<shape type=\"linearcurve\"><string name=\"filename\" value=\"line.txt\"/></shape>",
                             "<shape type=\"bsplinecurve\"><string name=\"filename\" value=\"spline.txt\"/></shape>"};
    int covered = 0;
    for (int i = 0; i < 24 * 24; i++)
        covered += cyl[i] > 0.0f;
    cr_assert(covered > 24 * 24 / 5 && covered < 24 * 24 * 3 / 4, "the tube covers %d pixels", covered);
    for (int k = 0; k < 2; k++) {
        float *d = tube_depth(&f, curves[k]);
        double worst = 0.0;
        for (int i = 0; i < 24 * 24; i++) {
            /* silhouette pixels average hits and misses: the same rays, so
             * the same mix, unless a ray grazes within Embree's float error */
            worst = fmax(worst, fabs(d[i] - cyl[i]));
        }
        cr_expect_lt(worst, 1e-3, "%s: depth differs from the cylinder's by %g", curves[k], worst);
        free(d);
    }
    free(cyl);
    render_fixture_close(&f);
}

Test(render_curves, files_that_are_not_curves_are_refused)
{
    render_fixture f;
    render_fixture_open(&f);
    const char *bad[3][2] = {{"1 2 3\n4 5 6 0.1\n", "line 1 is not four finite numbers"},
                             {"0 0 0 0.1\n1 0 0 0.1\n2 0 0 0.1\n", "fewer than 4 control points"},
                             {"\n\n", "no curve in the file"}};
    for (int k = 0; k < 3; k++) {
        char path[256], xml[1024], err[1024];
        render_write_file(&f, "c.txt", bad[k][0], path, sizeof path);
        snprintf(xml, sizeof xml, tube_xml, "<shape type=\"bsplinecurve\"><string name=\"filename\" value=\"c.txt\"/></shape>");
        render_write_file(&f, "scene.xml", xml, path, sizeof path);
        scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
        cr_expect_null(s);
        cr_expect(strstr(err, "scene.xml:9:") && strstr(err, "c.txt") && strstr(err, bad[k][1]), "%s", err);
        scene_destroy(s);
    }
    render_fixture_close(&f);
}

/* The `hair` BSDF on curves, in a white furnace: a fibre that absorbs
 * nothing under a uniform white sky gives back exactly 1 along every path
 * that leaves it after one scattering (max_depth 2), since its lobes'
 * weights then sum to 1 and each light path through the fibre is one
 * event: a direction into the fibre must pass out of its far side, not hit
 * its inside (curves are seen from outside only, as in Mitsuba). Brown
 * hair, in the same place, is darker than the sky. */
Test(render_curves, white_hair_in_a_furnace_stays_white)
{
    render_fixture f;
    render_fixture_open(&f);
    char path[256];
    render_write_file(&f, "line.txt", "-3 0 0 0.5\n0 0 0 0.5\n3 0 0 0.5\n", path, sizeof path);
    render_write_file(&f, "spline.txt", "-6 0 0 0.5\n-3 0 0.3 0.5\n0 0 0 0.5\n3 0 -0.3 0.5\n6 0 0 0.5\n", path,
                      sizeof path);
    const char *shapes[2] = {"linearcurve\"><string name=\"filename\" value=\"line.txt\"/>",
                             "bsplinecurve\"><string name=\"filename\" value=\"spline.txt\"/>"};
    const char *bsdfs[2] = {"<bsdf type=\"hair\"><rgb name=\"sigma_a\" value=\"0\"/></bsdf>",
                            "<bsdf type=\"hair\"/>"};
    for (int k = 0; k < 2; k++)
        for (int b = 0; b < 2; b++) {
            char shape[512], xml[4096];
            snprintf(shape, sizeof shape, "<shape type=\"%s%s</shape>", shapes[k], bsdfs[b]);
            snprintf(xml, sizeof xml, tube_xml, shape);
            render_write_file(&f, "scene.xml", xml, path, sizeof path);
            int w, h, nch, covered = 0;
            float *px = render_to_pixels(path, 0, 5, 1, RENDER_AOV_DEPTH, &w, &h, &nch);
            double worst = 0.0, mean = 0.0;
            for (int i = 0; i < w * h; i++)
                if (px[i * nch + 3] > 0.0f) { /* the fibre */
                    covered++;
                    worst = fmax(worst, fabs(px[i * nch] - 1.0));
                    mean += px[i * nch];
                }
            free(px);
            cr_assert_gt(covered, w * h / 5, "%s", shape);
            mean /= covered;
            if (b == 0)
                cr_expect_lt(worst, 1e-5, "%s: a white fibre in a furnace is off by %g", shape, worst);
            else
                cr_expect_lt(mean, 0.8, "%s: brown hair's mean %g", shape, mean);
        }
    render_fixture_close(&f);
}
