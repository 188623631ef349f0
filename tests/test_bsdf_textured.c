/* The BSDFs driven by textures: normalmap and bumpmap against the
 * perturbed frame worked out here from the map's value or the height's
 * slope (its normal, and a diffuse BSDF's value in it times Mitsuba's
 * shadowing term 2 / (1 + sqrt(1 + a^2 tan^2 theta_o)), a^2 =
 * min(tan^2 theta_n / 8, 1)); the normal map's x axis follows dp/du; and
 * textured roughness equals the constant roughness of the texel's value. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <unistd.h>

#include "celadon/film.h"
#include "support/plugin_xml.h"
#include "test_bsdf_support.h"

/* A diffuse of albedo 0.5 in the frame of normal n, with the shadowing term. */
static double diffuse_in_frame(vec3 n, vec3 wo, bool shadowing)
{
    double c = v3_dot(wo, n);
    if (c <= 0.0 || wo.z <= 0.0)
        return 0.0;
    double g = 1.0;
    if (shadowing) {
        double tan2_n = (1 - n.z * n.z) / (n.z * n.z), tan2_o = (1 - wo.z * wo.z) / (wo.z * wo.z);
        g = 2.0 / (1.0 + sqrt(1.0 + fmin(tan2_n / 8.0, 1.0) * tan2_o));
    }
    return 0.5 / M_PI * c * g;
}

static void assert_vec(vec3 a, vec3 b, double tol, const char *what)
{
    cr_assert(fabs(a.x - b.x) <= tol && fabs(a.y - b.y) <= tol && fabs(a.z - b.z) <= tol,
              "%s: (%g, %g, %g), want (%g, %g, %g)", what, a.x, a.y, a.z, b.x, b.y, b.z);
}

Test(bsdf_textured, normalmap_flat_changes_nothing_and_tilted_follows_the_map)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const bsdf_t *plain = plugin_xml_bsdf(&fx, "<bsdf type='diffuse'/>", err, sizeof err);
    const bsdf_t *flat = plugin_xml_bsdf(&fx, "<bsdf type='normalmap'><rgb name='normalmap' value='0.5, 0.5, 1'/>"
                                              "<bsdf type='diffuse'/></bsdf>",
                                         err, sizeof err);
    /* The normal (0.6, 0, 0.8) of Mitsuba's frame, encoded (n + 1) / 2. */
    const bsdf_t *tilted = plugin_xml_bsdf(&fx, "<bsdf type='normalmap'><rgb name='normalmap' value='0.8, 0.5, 0.9'/>"
                                                "<bsdf type='diffuse'/></bsdf>",
                                           err, sizeof err);
    const bsdf_t *bare = plugin_xml_bsdf(&fx, "<bsdf type='normalmap'><rgb name='normalmap' value='0.8, 0.5, 0.9'/>"
                                              "<boolean name='use_shadowing_function' value='false'/>"
                                              "<bsdf type='diffuse'/></bsdf>",
                                         err, sizeof err);
    cr_assert(plain && flat && tilted && bare, "%s", err);
    rng_t rng;
    rng_seed(&rng, 9, 1);
    int lit = 0;
    for (int k = 0; k < 2000; k++) {
        vec3 wi = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        vec3 wo = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        bsdf_query q = {.wi = wi, .uv = v2(0.3, 0.3), .mode = TRANSPORT_RADIANCE};
        cr_assert_float_eq(bsdf_eval(flat, &q, wo).r, bsdf_eval(plain, &q, wo).r, 1e-12);
        /* Mitsuba's frame has x along dp/du, here the local +y: the normal
         * tilts toward +y. */
        q.dpdu = v3(0.0, 2.0, 0.0);
        vec3 n = v3(0.0, 0.6, 0.8);
        if (wi.z * v3_dot(wi, n) <= 0.0) /* flip_invalid_normals: wi must see it from the front */
            n = v3(0.0, -0.6, 0.8);
        assert_vec(bsdf_shading_normal(tilted, &q), n, 1e-12, "perturbed normal");
        double want = wi.z * v3_dot(wi, n) > 0.0 ? diffuse_in_frame(n, wo, true) : 0.0;
        cr_assert_float_eq(bsdf_eval(tilted, &q, wo).r, want, 1e-12, "wi (%g %g %g)", wi.x, wi.y, wi.z);
        cr_assert_float_eq(bsdf_eval(bare, &q, wo).r, diffuse_in_frame(n, wo, false), 1e-12);
        lit += want > 0.0;
    }
    cr_assert_gt(lit, 1000);
    plugin_xml_close(&fx);
}

/* A height ramp: a 2 x 1 grey EXR [lo, lo + 1], bilinear, rises by 1
 * between the texel centres u = 1/4 and 3/4: slope 2 per unit u. */
static const bsdf_t *bump(plugin_xml *fx, const char *dir, double lo, double scale, char *err, size_t errlen)
{
    char exr[256], xml[1024];
    snprintf(exr, sizeof exr, "%s/ramp%g.exr", dir, lo);
    const float ramp[2] = {(float)lo, (float)(lo + 1.0)};
    const char *const names[] = {"Y"};
    cr_assert_eq(exr_write_float(exr, 2, 1, 1, names, ramp, NULL, err, errlen), 0, "%s", err);
    snprintf(xml, sizeof xml,
             "<bsdf type='bumpmap'><float name='scale' value='%g'/><texture type='bitmap' name='height'>"
             "<string name='filename' value='%s'/></texture><bsdf type='diffuse'/></bsdf>",
             scale, exr);
    return plugin_xml_bsdf(fx, xml, err, errlen);
}

Test(bsdf_textured, bumpmap_normal_is_the_displaced_surfaces)
{
    char dir[] = "/tmp/celadon-bump-XXXXXX", err[512];
    cr_assert_not_null(mkdtemp(dir));
    plugin_xml fx;
    plugin_xml_open(&fx);
    const bsdf_t *b = bump(&fx, dir, 0.0, 0.5, err, sizeof err), *offset = bump(&fx, dir, 3.0, 0.5, err, sizeof err);
    const bsdf_t *none = bump(&fx, dir, 1.0, 0.0, err, sizeof err);
    cr_assert(b && offset && none, "%s", err);
    /* dp/du' = (1, 0, 0.5 x 2), dp/dv' = (0, 1, 0): n' = (-1, 0, 1) / sqrt 2. */
    bsdf_query q = {.wi = v3_norm(v3(-0.3, 0.1, 0.9)), .uv = v2(0.4, 0.5), .mode = TRANSPORT_RADIANCE};
    q.dpdu = v3(1, 0, 0), q.dpdv = v3(0, 1, 0), q.ng = v3(0, 0, 1);
    vec3 n = v3(-M_SQRT1_2, 0.0, M_SQRT1_2);
    assert_vec(bsdf_shading_normal(b, &q), n, 1e-6, "bumped normal");
    assert_vec(bsdf_shading_normal(offset, &q), n, 1e-6, "an offset height bumps the same");
    assert_vec(bsdf_shading_normal(none, &q), v3(0, 0, 1), 1e-12, "scale 0: flat");
    /* Twice the surface's speed along u halves the slope in space. */
    bsdf_query fast = q;
    fast.dpdu = v3(2, 0, 0);
    assert_vec(bsdf_shading_normal(b, &fast), v3_norm(v3(-1.0, 0.0, 2.0)), 1e-6, "dp/du twice as long");
    for (int k = 0; k < 20; k++) {
        vec3 wo = v3_norm(v3(-0.8 + 0.08 * k, 0.2, 0.6));
        cr_assert_float_eq(bsdf_eval(b, &q, wo).r, diffuse_in_frame(n, wo, true), 1e-6, "wo %d", k);
    }
    plugin_xml_close(&fx);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

/* A checkerboard of alphas: each cell evaluates as the constant alpha. */
Test(bsdf_textured, textured_alpha_is_the_texels_alpha)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const char *kinds[] = {"roughconductor", "roughdielectric"};
    for (int k = 0; k < 2; k++) {
        char xml[512];
        snprintf(xml, sizeof xml,
                 "<bsdf type='%s'><string name='distribution' value='ggx'/><texture type='checkerboard' name='alpha'>"
                 "<float name='color0' value='0.15'/><float name='color1' value='0.4'/></texture></bsdf>",
                 kinds[k]);
        const bsdf_t *tex = plugin_xml_bsdf(&fx, xml, err, sizeof err);
        snprintf(xml, sizeof xml, "<bsdf type='%s'><string name='distribution' value='ggx'/>"
                                  "<float name='alpha' value='0.15'/></bsdf>", kinds[k]);
        const bsdf_t *a0 = plugin_xml_bsdf(&fx, xml, err, sizeof err);
        snprintf(xml, sizeof xml, "<bsdf type='%s'><string name='distribution' value='ggx'/>"
                                  "<float name='alpha' value='0.4'/></bsdf>", kinds[k]);
        const bsdf_t *a1 = plugin_xml_bsdf(&fx, xml, err, sizeof err);
        cr_assert(tex && a0 && a1, "%s", err);
        bsdf_query q = query_at(30.0, 15.0, TRANSPORT_RADIANCE);
        vec3 wo = v3_norm(v3(-0.4, -0.1, 0.8));
        q.uv = v2(0.75, 0.25); /* color0: read as a scalar (Mitsuba's eval_1), where the sides differ */
        double want0 = bsdf_eval(a0, &q, wo).r, want1;
        cr_assert_float_eq(bsdf_eval(tex, &q, wo).r, want0, 1e-12 * want0, "%s color0", kinds[k]);
        cr_assert_float_eq(bsdf_pdf(tex, &q, wo), bsdf_pdf(a0, &q, wo), 1e-12 * bsdf_pdf(a0, &q, wo));
        q.uv = v2(0.25, 0.25); /* color1 */
        want1 = bsdf_eval(a1, &q, wo).r;
        cr_assert_float_eq(bsdf_eval(tex, &q, wo).r, want1, 1e-12 * want1, "%s color1", kinds[k]);
        cr_assert_gt(fabs(want0 - want1), 0.01 * want0, "the two roughnesses differ");
    }
    plugin_xml_close(&fx);
}

/* alpha_u is the roughness along dp/du (Mitsuba's shading frame): with
 * dp/du along the local y axis, alpha_u 0.05 and alpha_v 0.3 evaluate as
 * the swapped alphas in the local frame. */
Test(bsdf_textured, anisotropy_follows_dp_du)
{
    plugin_xml fx;
    plugin_xml_open(&fx);
    char err[512];
    const bsdf_t *a = plugin_xml_bsdf(&fx, "<bsdf type='roughconductor'><float name='alpha_u' value='0.05'/>"
                                           "<float name='alpha_v' value='0.3'/></bsdf>",
                                      err, sizeof err);
    const bsdf_t *swapped = plugin_xml_bsdf(&fx, "<bsdf type='roughconductor'><float name='alpha_u' value='0.3'/>"
                                                 "<float name='alpha_v' value='0.05'/></bsdf>",
                                            err, sizeof err);
    cr_assert(a && swapped, "%s", err);
    cr_assert(bsdf_flags(a) & BSDF_ANISOTROPIC);
    rng_t rng;
    rng_seed(&rng, 12, 1);
    for (int k = 0; k < 500; k++) {
        vec3 wi = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        vec3 wo = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
        bsdf_query q = {.wi = wi, .uv = v2(0.5, 0.5), .mode = TRANSPORT_RADIANCE}, along_y = q;
        along_y.dpdu = v3(0.0, 3.0, 0.0);
        double want = bsdf_eval(swapped, &q, wo).r;
        cr_assert_float_eq(bsdf_eval(a, &along_y, wo).r, want, 1e-12 * (1 + want));
        cr_assert_float_eq(bsdf_pdf(a, &along_y, wo), bsdf_pdf(swapped, &q, wo), 1e-9 * (1 + want));
        /* Sampling turns back: the sampled direction's density is the turned pdf. */
        bsdf_sample_rec s;
        if (bsdf_sample(a, &along_y, 0.5, v2(rng_next_double(&rng), rng_next_double(&rng)), &s))
            cr_assert_float_eq(s.pdf, bsdf_pdf(swapped, &q, s.wo), 1e-9 * s.pdf);
    }
    plugin_xml_close(&fx);
}
