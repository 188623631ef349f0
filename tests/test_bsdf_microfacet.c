/* Microfacet distributions: normalisation, the Smith projected-area identity,
 * and visible-normal sampling against its density (chi-square). */
#include <criterion/criterion.h>
#include <math.h>

#include "bsdfs/microfacet.h"
#include "test_bsdf_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Integral over the upper hemisphere of g(m) in (cos theta, phi) with a
 * cos-theta grid refined towards the pole, where rough peaks live. */
static double hemisphere_integral(double (*g)(const microfacet *, vec3, vec3), const microfacet *d, vec3 v)
{
    const int nz = 800, np = 160;
    double sum = 0.0;
    for (int i = 0; i < nz; i++) {
        /* z = 1 - t^2 with t uniform concentrates nodes near z = 1; dz = 2 t dt. */
        double t = (i + 0.5) / nz, z = 1.0 - t * t, r = sqrt(fmax(0.0, 1.0 - z * z));
        for (int j = 0; j < np; j++) {
            double phi = 2.0 * M_PI * (j + 0.5) / np;
            sum += g(d, v3(r * cos(phi), r * sin(phi), z), v) * 2.0 * t;
        }
    }
    return sum * (1.0 / nz) * (2.0 * M_PI / np);
}

static double projected_d(const microfacet *d, vec3 m, vec3 v)
{
    (void)v;
    return microfacet_D(d, m) * m.z;
}

static double visible_projected_area(const microfacet *d, vec3 m, vec3 v)
{
    return microfacet_D(d, m) * fmax(0.0, v3_dot(v, m)) * microfacet_G1(d, v, m);
}

static const microfacet cases[] = {
    {MICROFACET_BECKMANN, 0.3, 0.3, 1},
    {MICROFACET_BECKMANN, 0.15, 0.6, 1},
    {MICROFACET_GGX, 0.3, 0.3, 1},
    {MICROFACET_GGX, 0.6, 0.2, 1},
};

Test(microfacet, projected_area_is_one)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double a = hemisphere_integral(projected_d, &cases[i], v3(0, 0, 1));
        cr_assert_float_eq(a, 1.0, 2e-3, "case %zu: %g", i, a);
    }
}

/* Smith's G1 is defined so that the visible projected microfacet area equals
 * the projected macro-surface area: int D(m) <v,m>+ G1(v,m) dm = cos theta_v. */
Test(microfacet, smith_masking_preserves_projected_area)
{
    const double thetas[] = {0.0, 40.0, 70.0, 85.0};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (int k = 0; k < 4; k++) {
            double th = thetas[k] * M_PI / 180.0;
            vec3 v = v3(sin(th) * cos(0.7), sin(th) * sin(0.7), cos(th));
            double a = hemisphere_integral(visible_projected_area, &cases[i], v);
            cr_assert_float_eq(a, v.z, 3e-3, "case %zu theta %g: %g vs %g", i, thetas[k], a, v.z);
        }
}

typedef struct {
    const microfacet *d;
    vec3 wi;
} normal_ctx;

static int normal_sample(void *ctx, rng_t *rng, vec3 *w)
{
    const normal_ctx *c = ctx;
    double pdf;
    *w = microfacet_sample(c->d, c->wi, v2(rng_next_double(rng), rng_next_double(rng)), &pdf);
    return pdf > 0.0;
}

static double normal_pdf(void *ctx, vec3 m)
{
    const normal_ctx *c = ctx;
    return microfacet_pdf(c->d, c->wi, m);
}

Test(microfacet, normal_sampling_matches_pdf)
{
    const double thetas[] = {0.0, 45.0, 85.0};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (int vis = 0; vis < 2; vis++)
            for (int k = 0; k < 3; k++) {
                if (!vis && k > 0)
                    continue; /* D cos sampling does not depend on wi */
                microfacet d = cases[i];
                d.sample_visible = vis;
                double th = thetas[k] * M_PI / 180.0;
                normal_ctx c = {&d, v3(sin(th) * cos(1.0), sin(th) * sin(1.0), cos(th))};
                sphere_sampler s = {normal_sample, normal_pdf, &c};
                char msg[256];
                double p = chi2_sphere(&s, 16, 32, 50000, 1000 + 10 * i + k, msg, sizeof msg);
                cr_assert_gt(p, chi2_threshold(), "case %zu visible %d theta %g: %s", i, vis, thetas[k], msg);
            }
}
