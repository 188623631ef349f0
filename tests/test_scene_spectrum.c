/* <spectrum> read as Mitsuba 3's RGB variants read it, against independent
 * truths: a flat reflectance is the gray of its value, flat emission is the
 * sRGB of the equal-energy white, the D65 table's white point and Planck's
 * law have the chromaticities the CIE publishes. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "celadon/scene.h"
#include "celadon/scene_xml.h"
#include "scene_xml/spectrum.h"

static void chromaticity(const double xyz[3], double *x, double *y)
{
    double s = xyz[0] + xyz[1] + xyz[2];
    *x = xyz[0] / s;
    *y = xyz[1] / s;
}

/* Planck's law against the published chromaticities of the Planckian locus
 * (4 decimals, as Wyszecki and Stiles tabulate them) and of CIE illuminant
 * A, a 2856 K black body (CIE 015:2018, 5 decimals). */
Test(spectrum, blackbody_chromaticities_are_the_planckian_locus)
{
    const struct { double kelvin, x, y; } locus[] = {
        {2856, 0.44757, 0.40745}, {5000, 0.3451, 0.3516}, {6500, 0.3135, 0.3236}, {10000, 0.2807, 0.2884}};
    for (size_t i = 0; i < sizeof locus / sizeof locus[0]; i++) {
        double xyz[3], x, y;
        spectrum_blackbody_xyz(locus[i].kelvin, CIE_MIN_NM, CIE_MAX_NM, xyz);
        chromaticity(xyz, &x, &y);
        cr_expect_float_eq(x, locus[i].x, 2e-4, "%g K: x %.5f", locus[i].kelvin, x);
        cr_expect_float_eq(y, locus[i].y, 2e-4, "%g K: y %.5f", locus[i].kelvin, y);
    }
}

Test(spectrum, d65_weighting_is_the_published_white_point)
{
    /* A flat reflectance under the D65 weighting has D65's chromaticity,
     * (0.31271, 0.32902) for the 2° observer, and luminance 1. */
    const double wl[2] = {CIE_MIN_NM, CIE_MAX_NM}, v[2] = {1, 1};
    double xyz[3], x, y;
    spectrum_list_xyz(wl, v, 2, true, xyz);
    chromaticity(xyz, &x, &y);
    cr_expect_float_eq(x, 0.31271, 1e-4, "x %.5f", x);
    cr_expect_float_eq(y, 0.32902, 1e-4, "y %.5f", y);
    cr_expect_float_eq(xyz[1], 1.0, 1e-12);
    /* without it, the equal-energy white: x = y = 1/3 (the matching
     * functions have equal integrals) */
    spectrum_list_xyz(wl, v, 2, false, xyz);
    chromaticity(xyz, &x, &y);
    cr_expect_float_eq(x, 1.0 / 3, 2e-4, "x %.5f", x);
    cr_expect_float_eq(y, 1.0 / 3, 2e-4, "y %.5f", y);
}

/* The first <bsdf>'s reflectance and the first <emitter>'s radiance of a
 * scene text, as the reader stores them. */
static void read_pair(const char *bsdf_spectrum, const char *emitter_spectrum, scene_rgb *refl, scene_rgb *rad)
{
    char xml[4096], err[512];
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><bsdf type=\"diffuse\">%s</bsdf><emitter type=\"constant\">%s</emitter></scene>",
             bsdf_spectrum, emitter_spectrum);
    scene_desc *d = scene_desc_create_from_text(xml, strlen(xml), "/tmp/x.xml", NULL, 0, scene_plugin_find, err,
                                                sizeof err);
    cr_assert_not_null(d, "%s", err);
    scene_obj *root = scene_desc_root(d);
    *refl = scene_obj_rgb(scene_obj_child(root, SCENE_BSDF), "reflectance", (scene_rgb){-1, -1, -1});
    *rad = scene_obj_rgb(scene_obj_child(root, SCENE_EMITTER), "radiance", (scene_rgb){-1, -1, -1});
    scene_desc_destroy(d);
}

Test(spectrum, flat_spectra_as_mitsubas_rgb_mode_reads_them)
{
    scene_rgb refl, rad;
    read_pair("<spectrum name=\"reflectance\" value=\"0.5\"/>", "<spectrum name=\"radiance\" value=\"2\"/>", &refl,
              &rad);
    cr_expect(refl.r == 0.5 && refl.g == 0.5 && refl.b == 0.5, "a constant reflectance is its gray");
    /* flat emission: 2 · M_709 · (1, 1, 1), the sRGB of X = Y = Z = 2 */
    cr_expect_float_eq(rad.r, 2 * (3.240479 - 1.537150 - 0.498535), 1e-12);
    cr_expect_float_eq(rad.g, 2 * (-0.969256 + 1.875991 + 0.041556), 1e-12);
    cr_expect_float_eq(rad.b, 2 * (0.055648 - 0.204043 + 1.057311), 1e-12);

    read_pair("<spectrum name=\"reflectance\" value=\"360:0.3, 600:0.3 830:0.3\"/>",
              "<spectrum name=\"radiance\" value=\"360:2, 830:2\"/>", &refl, &rad);
    cr_expect_float_eq(refl.r, 0.3, 3e-4, "a flat list is the gray of its value: %g %g %g", refl.r, refl.g, refl.b);
    cr_expect_float_eq(refl.g, 0.3, 3e-4);
    cr_expect_float_eq(refl.b, 0.3, 3e-4);
    double lum = 0.212671 * rad.r + 0.715160 * rad.g + 0.072169 * rad.b;
    cr_expect_float_eq(lum, 2.0, 2e-3, "flat emission keeps its luminance: %g", lum);

    /* a reflectance is clamped to [0, 1], as Mitsuba clamps out-of-gamut colours */
    read_pair("<spectrum name=\"reflectance\" value=\"600:5, 700:5\"/>", "<rgb name=\"radiance\" value=\"1\"/>", &refl,
              &rad);
    cr_expect(refl.r == 1.0 && refl.b == 0.0, "%g %g %g", refl.r, refl.g, refl.b);
}

Test(spectrum, files_plugins_and_bad_lists)
{
    char path[] = "/tmp/celadon-spd-XXXXXX";
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    const char *spd = "# a measured spectrum\n400 0.2\n500 0.6\n\n700 0.1 # red end\n";
    cr_assert_eq(write(fd, spd, strlen(spd)), (ssize_t)strlen(spd));
    close(fd);
    char bsdf[512];
    snprintf(bsdf, sizeof bsdf, "<spectrum name=\"reflectance\" filename=\"%s\"/>", path);
    scene_rgb from_file, inline_list, rad, regular;
    read_pair(bsdf, "<spectrum name=\"radiance\" type=\"blackbody\"><float name=\"temperature\" value=\"3000\"/>"
                    "</spectrum>", &from_file, &rad);
    unlink(path);
    read_pair("<spectrum name=\"reflectance\" value=\"400:0.2, 500:0.6, 700:0.1\"/>",
              "<spectrum name=\"radiance\" type=\"uniform\"><float name=\"value\" value=\"1\"/></spectrum>",
              &inline_list, &regular);
    cr_expect(from_file.r == inline_list.r && from_file.g == inline_list.g && from_file.b == inline_list.b);
    cr_expect(rad.r > rad.g && rad.g > rad.b && rad.b > 0, "3000 K is orange: %g %g %g", rad.r, rad.g, rad.b);
    scene_rgb reg;
    read_pair("<spectrum name=\"reflectance\" type=\"regular\"><float name=\"wavelength_min\" value=\"400\"/>"
              "<float name=\"wavelength_max\" value=\"700\"/><string name=\"values\" value=\"0.2, 0.4, 0.8\"/>"
              "</spectrum>",
              "<rgb name=\"radiance\" value=\"1\"/>", &reg, &rad);
    read_pair("<spectrum name=\"reflectance\" value=\"400:0.2, 550:0.4, 700:0.8\"/>", "<rgb name=\"radiance\" value=\"1\"/>",
              &inline_list, &rad);
    cr_expect(reg.r == inline_list.r && reg.g == inline_list.g && reg.b == inline_list.b, "regular = its list");

    const char *bad[][2] = {
        {"<spectrum name=\"reflectance\" value=\"500:0.1, 400:0.2\"/>", "increasing"},
        {"<spectrum name=\"reflectance\" value=\"500:0.1 600\"/>", "bad wavelength:value pair"},
        {"<spectrum name=\"reflectance\" value=\"500:0.1\"/>", "at least two"},
        {"<spectrum name=\"reflectance\" type=\"blackbody\"/>", "needs <float name=\"temperature\">"},
        {"<spectrum name=\"reflectance\" type=\"d66\"/>", "unknown spectrum type 'd66'"},
        {"<spectrum name=\"reflectance\" filename=\"/nonexistent.spd\"/>", "spectrum file '/nonexistent.spd' not found"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char xml[1024], err[512] = "";
        snprintf(xml, sizeof xml, "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n%s\n</bsdf></scene>", bad[i][0]);
        scene_desc *d = scene_desc_create_from_text(xml, strlen(xml), "/tmp/s.xml", NULL, 0, scene_plugin_find, err,
                                                    sizeof err);
        cr_expect_null(d, "%s", bad[i][0]);
        scene_desc_destroy(d);
        cr_expect(strncmp(err, "/tmp/s.xml:3: ", 14) == 0 && strstr(err, bad[i][1]), "'%s' for %s", err, bad[i][0]);
    }
}
