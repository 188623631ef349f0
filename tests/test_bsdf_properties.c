/* Properties every BSDF must have, checked over the case list of
 * test_bsdf_support.c: bounded albedo, sample/eval/pdf consistency, sampling
 * that follows the claimed density (chi-square), and reciprocity where the
 * model is reciprocal. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "celadon/sampling.h"
#include "support/test_build.h"
#include "test_bsdf_support.h"

static const double front_thetas[] = {0.0, 30.0, 60.0, 85.0};

/* Incident directions of a case: front ones, plus mirrored ones when the
 * case scatters light arriving on the back. Returns their number. */
static int incident_thetas(const bsdf_case *c, double *out)
{
    int n = 0;
    for (int i = 0; i < 4; i++) {
        out[n++] = front_thetas[i];
        if (c->two_sided_incidence)
            out[n++] = 180.0 - front_thetas[i];
    }
    return n;
}


Test(bsdf_props, albedo_at_most_one_and_sample_matches_eval_pdf, .timeout = 60)
{
    bsdf_case cases[BSDF_CASES_MAX];
    int nc = bsdf_cases_make(cases);
    for (int ci = 0; ci < nc; ci++) {
        double thetas[8];
        int nt = incident_thetas(&cases[ci], thetas);
        for (int ti = 0; ti < nt; ti++)
            for (int mode = 0; mode < 2; mode++) {
                bsdf_query q = query_at(thetas[ti], 23.0, mode ? TRANSPORT_IMPORTANCE : TRANSPORT_RADIANCE);
                rng_t rng;
                rng_seed(&rng, 1234 + ci, ti);
                const int n = 10000;
                rgb sum = rgb_gray(0.0), sum2 = rgb_gray(0.0);
                for (int k = 0; k < n; k++) {
                    bsdf_sample_rec s;
                    double u1 = rng_next_double(&rng);
                    vec2 u2 = v2(rng_next_double(&rng), rng_next_double(&rng));
                    if (!bsdf_sample(cases[ci].bsdf, &q, u1, u2, &s))
                        continue;
                    cr_assert(isfinite(s.weight.r + s.weight.g + s.weight.b) && s.weight.r >= 0 && s.weight.g >= 0 &&
                                  s.weight.b >= 0,
                              "%s: bad weight", cases[ci].name);
                    cr_assert_float_eq(v3_len(s.wo), 1.0, 1e-9, "%s: wo not unit", cases[ci].name);
                    cr_assert_gt(s.pdf, 0.0);
                    sum = rgb_add(sum, s.weight);
                    sum2 = rgb_add(sum2, rgb_mul(s.weight, s.weight));
                    if (s.sampled_type & BSDF_DELTA) {
                        cr_assert(s.sampled_type & bsdf_flags(cases[ci].bsdf));
                        continue;
                    }
                    if (k >= 2000)
                        continue;
                    /* weight == eval / pdf and the sampler's pdf == bsdf_pdf. */
                    double pdf = bsdf_pdf(cases[ci].bsdf, &q, s.wo);
                    rgb f = bsdf_eval(cases[ci].bsdf, &q, s.wo);
                    cr_assert_float_eq(pdf, s.pdf, 1e-9 * s.pdf, "%s theta %g: pdf %g vs sampled %g", cases[ci].name,
                                       thetas[ti], pdf, s.pdf);
                    rgb w = rgb_scale(f, 1.0 / pdf);
                    cr_assert(fabs(w.r - s.weight.r) <= 1e-9 * (1 + w.r) && fabs(w.g - s.weight.g) <= 1e-9 * (1 + w.g) &&
                                  fabs(w.b - s.weight.b) <= 1e-9 * (1 + w.b),
                              "%s theta %g: weight differs from eval/pdf", cases[ci].name, thetas[ti]);
                }
                /* Mean weight = directional albedo; allow 4 standard errors. In
                 * radiance mode refraction into a denser medium is scaled by
                 * 1/eta^2 < 1 and out of it by eta^2, so only importance mode
                 * (flux) is bounded by one when light leaves the dense side. */
                rgb mean = rgb_scale(sum, 1.0 / n);
                rgb var = rgb_sub(rgb_scale(sum2, 1.0 / n), rgb_mul(mean, mean));
                double se = sqrt(fmax(0.0, rgb_max(var)) / n);
                int bounded = cases[ci].energy_bounded && (mode == 1 || thetas[ti] < 90.0);
                if (bounded)
                    cr_assert_leq(rgb_max(mean), 1.0 + 4.0 * se + 1e-9, "%s theta %g mode %d: albedo %g (se %g)",
                                  cases[ci].name, thetas[ti], mode, rgb_max(mean), se);
            }
    }
    bsdf_cases_free();
}

/* Runs the chi-square test on every case whose name starts with prefix. */
static void chi2_cases(const char *prefix)
{
    bsdf_case cases[BSDF_CASES_MAX];
    int nc = bsdf_cases_make(cases), tested = 0;
    const double thetas[] = {10.0, 55.0, 80.0, 130.0};
    for (int ci = 0; ci < nc; ci++) {
        if (strncmp(cases[ci].name, prefix, strlen(prefix)) != 0 || !(bsdf_flags(cases[ci].bsdf) & BSDF_SMOOTH))
            continue;
        /* the sanitized build: every other angle, alternating by case */
        int step = test_build_case_step(2);
        for (int ti = step > 1 ? ci % 2 : 0; ti < 4; ti += step) {
            if (thetas[ti] > 90.0 && !cases[ci].two_sided_incidence)
                continue;
            bsdf_density_ctx ctx = {cases[ci].bsdf, query_at(thetas[ti], 40.0, TRANSPORT_RADIANCE)};
            sphere_sampler s = bsdf_sphere_sampler(&ctx);
            char msg[256];
            double p = chi2_sphere(&s, 16, 32, 100000, 1000 + 13 * ci + ti, msg, sizeof msg);
            cr_assert_gt(p, chi2_threshold(), "%s, theta %g: %s", cases[ci].name, thetas[ti], msg);
            tested++;
        }
    }
    cr_assert_gt(tested, 0);
    bsdf_cases_free();
}

Test(bsdf_chi2, diffuse_and_twosided, .timeout = 60) { chi2_cases("diffuse"); chi2_cases("twosided"); }
Test(bsdf_chi2, roughconductor, .timeout = 60) { chi2_cases("roughconductor"); }
Test(bsdf_chi2, roughdielectric, .timeout = 60) { chi2_cases("roughdielectric"); }
Test(bsdf_chi2, plastic, .timeout = 60) { chi2_cases("plastic"); }
Test(bsdf_chi2, roughplastic, .timeout = 60) { chi2_cases("roughplastic"); }
Test(bsdf_chi2, principled, .timeout = 60) { chi2_cases("principled"); }
Test(bsdf_chi2, mask_blendbsdf_normalmap, .timeout = 60)
{
    chi2_cases("mask");
    chi2_cases("blendbsdf");
    chi2_cases("normalmap");
}

/* f(wi, wo) = f(wo, wi) with f = eval / |cos theta_o|. */
Test(bsdf_props, reciprocity)
{
    bsdf_case cases[BSDF_CASES_MAX];
    int nc = bsdf_cases_make(cases);
    rng_t rng;
    rng_seed(&rng, 31, 4);
    for (int ci = 0; ci < nc; ci++) {
        if (!cases[ci].reciprocal)
            continue;
        int nonzero = 0;
        for (int k = 0; k < 400; k++) {
            vec3 a = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
            vec3 b = warp_square_to_cosine_hemisphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
            if (cases[ci].two_sided_incidence && k % 2) {
                a.z = -a.z;
                b.z = -b.z;
            }
            bsdf_query qa = {.wi = a, .uv = v2(0.3, 0.6), .mode = TRANSPORT_RADIANCE};
            bsdf_query qb = {.wi = b, .uv = v2(0.3, 0.6), .mode = TRANSPORT_RADIANCE};
            rgb fab = rgb_scale(bsdf_eval(cases[ci].bsdf, &qa, b), 1.0 / fabs(b.z));
            rgb fba = rgb_scale(bsdf_eval(cases[ci].bsdf, &qb, a), 1.0 / fabs(a.z));
            double tol = 1e-9 * (1.0 + rgb_max(fab));
            cr_assert(fabs(fab.r - fba.r) <= tol && fabs(fab.g - fba.g) <= tol && fabs(fab.b - fba.b) <= tol,
                      "%s: f(a,b) %g != f(b,a) %g", cases[ci].name, fab.r, fba.r);
            nonzero += rgb_max(fab) > 0.0;
        }
        if (bsdf_flags(cases[ci].bsdf) & BSDF_SMOOTH)
            cr_assert_gt(nonzero, 100, "%s: evaluates to zero", cases[ci].name);
    }
    bsdf_cases_free();
}

/* Refraction is not symmetric, but adjoint: the importance-mode BSDF equals the
 * radiance-mode BSDF with the directions swapped (Veach 1997, ch. 5). */
Test(bsdf_props, roughdielectric_adjoint)
{
    bsdf_case cases[BSDF_CASES_MAX];
    int nc = bsdf_cases_make(cases), checked = 0;
    rng_t rng;
    rng_seed(&rng, 32, 4);
    for (int ci = 0; ci < nc; ci++) {
        if (strncmp(cases[ci].name, "roughdielectric", 15) != 0)
            continue;
        for (int k = 0; k < 400; k++) {
            /* Pairs (a, b) with b sampled from a, so most are transmissions with f > 0. */
            vec3 a = warp_square_to_uniform_sphere(v2(rng_next_double(&rng), rng_next_double(&rng)));
            bsdf_query qa = {.wi = a, .uv = v2(0, 0), .mode = TRANSPORT_IMPORTANCE};
            bsdf_sample_rec s;
            if (!bsdf_sample(cases[ci].bsdf, &qa, 0.999, v2(rng_next_double(&rng), rng_next_double(&rng)), &s))
                continue;
            vec3 b = s.wo;
            bsdf_query qb = {.wi = b, .uv = v2(0, 0), .mode = TRANSPORT_RADIANCE};
            double f_imp = bsdf_eval(cases[ci].bsdf, &qa, b).r / fabs(b.z);
            double f_rad = bsdf_eval(cases[ci].bsdf, &qb, a).r / fabs(a.z);
            cr_assert_float_eq(f_imp, f_rad, 1e-9 * (1.0 + f_imp), "%s: %g vs %g", cases[ci].name, f_imp, f_rad);
            checked += f_imp > 0.0 && a.z * b.z < 0.0;
        }
    }
    cr_assert_gt(checked, 100);
    bsdf_cases_free();
}

/* One-sided models are black from the back, as in Mitsuba. */
Test(bsdf_props, one_sided_models_are_black_from_behind)
{
    bsdf_case cases[BSDF_CASES_MAX];
    int nc = bsdf_cases_make(cases);
    for (int ci = 0; ci < nc; ci++) {
        unsigned fl = bsdf_flags(cases[ci].bsdf);
        if (fl & BSDF_BACK_SIDE)
            continue;
        bsdf_query q = query_at(120.0, 10.0, TRANSPORT_RADIANCE);
        bsdf_sample_rec s;
        cr_assert_eq(bsdf_sample(cases[ci].bsdf, &q, 0.5, v2(0.3, 0.3), &s), 0, "%s", cases[ci].name);
        cr_assert(rgb_is_black(bsdf_eval(cases[ci].bsdf, &q, v3(0, 0, -1))), "%s", cases[ci].name);
        cr_assert(rgb_is_black(bsdf_eval(cases[ci].bsdf, &q, v3(0, 0, 1))), "%s", cases[ci].name);
        cr_assert_eq(bsdf_pdf(cases[ci].bsdf, &q, v3(0, 0, -1)), 0.0, "%s", cases[ci].name);
    }
    bsdf_cases_free();
}
