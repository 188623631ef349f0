/* Shared machinery of the material tests: Pearson chi-square goodness-of-fit
 * of a sampler against its claimed density (after Mitsuba's ChiSquareTest),
 * and a BSDF test-case list. */
#ifndef TEST_BSDF_SUPPORT_H
#define TEST_BSDF_SUPPORT_H

#include <stddef.h>

#include "bsdfs/bsdfs.h"
#include "celadon/rng.h"

/* Significance of each chi-square test after Sidak correction for the number
 * of chi-square tests in the whole suite (alpha = 1% overall). */
double chi2_threshold(void);

/* p-value of observed counts against expected counts (same length n). Cells
 * expecting fewer than 5 are pooled; *dof receives the degrees of freedom. */
double chi2_pvalue_counts(const double *observed, const double *expected, int n, int *dof);

/* Sphere histogram test: cells uniform in (cos theta, phi), n_cos x n_phi. The
 * sampler returns 1 and a direction for a density sample, 0 for anything else
 * (a delta lobe, a failed sample): those fall into one extra cell expected to
 * hold N (1 - integral of pdf). */
typedef struct {
    int (*sample)(void *ctx, rng_t *rng, vec3 *w);
    double (*pdf)(void *ctx, vec3 w);
    void *ctx;
} sphere_sampler;

/* Returns the p-value; writes a one-line summary into msg. */
double chi2_sphere(const sphere_sampler *s, int n_cos, int n_phi, long n_samples, uint64_t seed, char *msg,
                   size_t msglen);

/* The sphere sampler of a BSDF at a query: its non-delta samples and pdf. */
typedef struct {
    const bsdf_t *b;
    bsdf_query q;
} bsdf_density_ctx;
sphere_sampler bsdf_sphere_sampler(bsdf_density_ctx *ctx);

/* A BSDF query helper: wi at polar angle theta (degrees; > 90 is the back side). */
bsdf_query query_at(double theta_deg, double phi_deg, transport_mode mode);

/* The BSDF configurations every generic property test runs over. */
typedef struct {
    const char *name;
    const bsdf_t *bsdf;
    int two_sided_incidence; /* also test wi on the back side */
    int reciprocal;          /* f(wi, wo) = f(wo, wi) for the non-delta part */
    int energy_bounded;      /* the albedo is at most 1 (not Disney's sheen and clearcoat) */
} bsdf_case;

enum { BSDF_CASES_MAX = 32 };
/* Builds the cases (asserting on failure); returns their number. They live
 * until bsdf_cases_free. */
int bsdf_cases_make(bsdf_case *cases);
void bsdf_cases_free(void);

#endif
