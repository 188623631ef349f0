/* The BSDFs that wrap others or let light through: null, mask and
 * blendbsdf, against their definitions evaluated here: null passes
 * everything straight on; mask is opacity times its nested BSDF and a null
 * lobe taken with probability 1 - opacity (a textured opacity follows its
 * texture), with a shadow-ray transmittance of 1 - opacity; blendbsdf is
 * the mixture of its two and picks the second with probability weight. A
 * furnace render: a half-transparent white sphere in a white environment
 * is white, and its coverage (alpha) is its opacity. */
#include <criterion/criterion.h>

#include "support/plugin_xml.h"
#include "test_bsdf_support.h"
#include "test_render_util.h"

Test(bsdf_wrappers, null_passes_everything_straight_through)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const bsdf_t *b = plugin_xml_bsdf(&fx, "<bsdf type='null'/>", err, sizeof err);
    cr_assert_not_null(b, "%s", err);
    for (int th = 0; th <= 180; th += 30) {
        bsdf_query q = query_at(th, 40.0, TRANSPORT_RADIANCE);
        bsdf_sample_rec s;
        cr_assert(bsdf_sample(b, &q, 0.3, v2(0.2, 0.9), &s));
        cr_assert(s.wo.x == -q.wi.x && s.wo.y == -q.wi.y && s.wo.z == -q.wi.z);
        cr_assert_eq(s.weight.g, 1.0);
        cr_assert(s.sampled_type & BSDF_NULL);
        cr_assert_eq(bsdf_straight_transmittance(b, &q).r, 1.0);
        cr_assert(rgb_is_black(bsdf_eval(b, &q, v3(0, 0, 1))));
    }
    plugin_xml_close(&fx);
}

Test(bsdf_wrappers, mask_is_opacity_times_its_bsdf_and_a_null_lobe)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const bsdf_t *diffuse = plugin_xml_bsdf(&fx, "<bsdf type='diffuse'><rgb name='reflectance' value='0.6'/></bsdf>",
                                            err, sizeof err);
    const bsdf_t *mask = plugin_xml_bsdf(&fx, "<bsdf type='mask'><float name='opacity' value='0.3'/>"
                                              "<bsdf type='diffuse'><rgb name='reflectance' value='0.6'/></bsdf></bsdf>",
                                         err, sizeof err);
    cr_assert(diffuse && mask, "%s", err);
    bsdf_query q = query_at(35.0, 20.0, TRANSPORT_RADIANCE);
    vec3 wo = v3_norm(v3(0.3, -0.2, 0.9));
    cr_assert_float_eq(bsdf_eval(mask, &q, wo).r, 0.3 * bsdf_eval(diffuse, &q, wo).r, 1e-15);
    cr_assert_float_eq(bsdf_pdf(mask, &q, wo), 0.3 * bsdf_pdf(diffuse, &q, wo), 1e-15);
    cr_assert_float_eq(bsdf_straight_transmittance(mask, &q).r, 0.7, 1e-15);
    /* The null lobe's frequency: binomial, 1 - opacity. */
    rng_t rng;
    rng_seed(&rng, 5, 1);
    const int n = 100000;
    int straight = 0;
    for (int k = 0; k < n; k++) {
        bsdf_sample_rec s;
        cr_assert(bsdf_sample(mask, &q, rng_next_double(&rng), v2(rng_next_double(&rng), rng_next_double(&rng)), &s));
        if (s.sampled_type & BSDF_NULL) {
            straight++;
            cr_assert_eq(s.weight.r, 1.0);
            cr_assert_float_eq(s.pdf, 0.7, 1e-15);
        } else {
            cr_assert_float_eq(s.weight.r, 0.6, 1e-12, "the nested weight, unchanged");
        }
    }
    cr_assert_float_eq(straight / (double)n, 0.7, 5.0 * sqrt(0.21 / n), "null lobe frequency %g", straight / (double)n);
    /* A textured opacity: the checkerboard's value in each cell, read as a
     * scalar (Mitsuba's eval_1: color0 where the sides differ). */
    const bsdf_t *tex = plugin_xml_bsdf(&fx, "<bsdf type='mask'><texture type='checkerboard' name='opacity'>"
                                             "<float name='color0' value='0.9'/><float name='color1' value='0.2'/></texture>"
                                             "<bsdf type='diffuse'><rgb name='reflectance' value='0.6'/></bsdf></bsdf>",
                                        err, sizeof err);
    cr_assert_not_null(tex, "%s", err);
    bsdf_query in0 = q, in1 = q;
    in0.uv = v2(0.25, 0.25), in1.uv = v2(0.75, 0.25);
    cr_assert_float_eq(bsdf_straight_transmittance(tex, &in0).r, 0.8, 1e-12);
    cr_assert_float_eq(bsdf_straight_transmittance(tex, &in1).r, 0.1, 1e-12);
    cr_assert_float_eq(bsdf_eval(tex, &in1, wo).r, 0.9 * bsdf_eval(diffuse, &q, wo).r, 1e-15);
    plugin_xml_close(&fx);
}

Test(bsdf_wrappers, blendbsdf_is_the_mixture)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const bsdf_t *a = plugin_xml_bsdf(&fx, "<bsdf type='diffuse'><rgb name='reflectance' value='0.2'/></bsdf>",
                                      err, sizeof err);
    const bsdf_t *c = plugin_xml_bsdf(&fx, "<bsdf type='roughconductor'><float name='alpha' value='0.2'/></bsdf>",
                                      err, sizeof err);
    const bsdf_t *blend = plugin_xml_bsdf(&fx, "<bsdf type='blendbsdf'><float name='weight' value='0.25'/>"
                                                "<bsdf type='diffuse'><rgb name='reflectance' value='0.2'/></bsdf>"
                                                "<bsdf type='roughconductor'><float name='alpha' value='0.2'/></bsdf></bsdf>",
                                          err, sizeof err);
    cr_assert(a && c && blend, "%s", err);
    bsdf_query q = query_at(40.0, 10.0, TRANSPORT_RADIANCE);
    rng_t rng;
    rng_seed(&rng, 6, 1);
    int second = 0;
    const int n = 20000;
    for (int k = 0; k < n; k++) {
        vec3 wo = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        double want = 0.75 * bsdf_eval(a, &q, wo).r + 0.25 * bsdf_eval(c, &q, wo).r;
        cr_assert_float_eq(bsdf_eval(blend, &q, wo).r, want, 1e-12 * (1 + want));
        double want_pdf = 0.75 * bsdf_pdf(a, &q, wo) + 0.25 * bsdf_pdf(c, &q, wo);
        cr_assert_float_eq(bsdf_pdf(blend, &q, wo), want_pdf, 1e-12 * (1 + want_pdf));
        /* Which BSDF sampled: the second, the conductor (glossy), with
         * probability weight; its weight is the mixture's eval / pdf. */
        bsdf_sample_rec sr;
        if (!bsdf_sample(blend, &q, rng_next_double(&rng), v2(rng_next_double(&rng), rng_next_double(&rng)), &sr))
            continue;
        second += sr.sampled_type == BSDF_GLOSSY_REFLECTION;
        double pdf = bsdf_pdf(blend, &q, sr.wo);
        cr_assert_float_eq(sr.pdf, pdf, 1e-12 * pdf);
        cr_assert_float_eq(sr.weight.r, bsdf_eval(blend, &q, sr.wo).r / pdf, 1e-12 * (1 + sr.weight.r));
    }
    /* A few conductor samples fail below the horizon: at most 0.25. */
    cr_assert_float_eq(second / (double)n, 0.25, 5.0 * sqrt(0.25 * 0.75 / n) + 0.01, "%g", second / (double)n);
    plugin_xml_close(&fx);
}

/* A sphere of mask(0.5, white two-sided diffuse) seen head-on. In a white
 * furnace every interaction keeps the energy (the null lobe passes all of
 * it, the diffuse reflects all): the image is 1. Without the environment,
 * a camera ray is covered unless both walls it meets are absent: alpha
 * 1 - 0.5^2 = 0.75 at the disc's centre (with the environment, Mitsuba
 * counts every sample as covered). */
static float *masked_sphere(const char *environment)
{
    render_fixture f;
    render_fixture_open(&f);
    char xml[2048], path[256];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"40\"/>"
             "<integer name=\"rr_depth\" value=\"40\"/></integrator>"
             "<sensor type=\"orthographic\"><transform name=\"to_world\"><translate z=\"-5\"/></transform>"
             "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"256\"/></sampler>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"
             "<string name=\"pixel_format\" value=\"rgba\"/><rfilter type=\"box\"/></film></sensor>"
             "<shape type=\"sphere\"><float name=\"radius\" value=\"0.9\"/><bsdf type=\"mask\">"
             "<float name=\"opacity\" value=\"0.5\"/><bsdf type=\"twosided\"><bsdf type=\"diffuse\">"
             "<rgb name=\"reflectance\" value=\"1\"/></bsdf></bsdf></bsdf></shape>%s</scene>",
             environment);
    render_write_file(&f, "scene.xml", xml, path, sizeof path);
    int w, h, nch;
    float *px = render_to_pixels(path, 0, 4, 2, 0, &w, &h, &nch);
    cr_assert(w == 8 && h == 8 && nch == 4);
    render_fixture_close(&f);
    return px;
}

Test(bsdf_wrappers, masked_sphere_furnace_and_coverage, .timeout = 60)
{
    float *px = masked_sphere("<emitter type=\"constant\"/>");
    double mean = 0.0;
    for (int i = 0; i < 64; i++) {
        for (int c = 0; c < 3; c++)
            cr_assert_float_eq(px[i * 4 + c], 1.0, 0.1, "furnace pixel %d: %g", i, px[i * 4 + c]);
        mean += px[i * 4] / 64;
        cr_assert_eq(px[i * 4 + 3], 1.0f, "a visible environment covers everything");
    }
    /* 256 samples give each pixel a standard error near 0.02: the mean of
     * 64, 0.0025. */
    cr_assert_float_eq(mean, 1.0, 0.01, "furnace mean %g", mean);
    free(px);
    px = masked_sphere("");
    double alpha = 0.0;
    for (int y = 3; y < 5; y++)
        for (int x = 3; x < 5; x++)
            alpha += px[(y * 8 + x) * 4 + 3] / 4;
    cr_assert_float_eq(alpha, 0.75, 0.06, "alpha at the centre %g", alpha);
    cr_assert_eq(px[3], 0.0f, "the corner sees nothing");
    free(px);
}
