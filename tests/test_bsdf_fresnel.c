/* Fresnel equations against closed forms and physical identities. */
#include <criterion/criterion.h>
#include <math.h>

#include "bsdfs/fresnel.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

Test(fresnel, normal_incidence_dielectric)
{
    const double etas[] = {1.000277, 1.333, 1.5046, 2.419};
    for (int i = 0; i < 4; i++) {
        double n = etas[i], r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
        cr_assert_float_eq(fresnel_dielectric(1.0, n, NULL, NULL, NULL), r0, 1e-14);
        /* Same from the inside (reciprocity at normal incidence). */
        cr_assert_float_eq(fresnel_dielectric(-1.0, n, NULL, NULL, NULL), r0, 1e-14);
    }
    cr_assert_eq(fresnel_dielectric(0.3, 1.0, NULL, NULL, NULL), 0.0);
}

/* R + T = 1 where T is computed independently from the transmission amplitude
 * coefficients t_s = 2 n1 c1 / (n1 c1 + n2 c2), t_p = 2 n1 c1 / (n2 c1 + n1 c2)
 * and the flux factor (n2 c2) / (n1 c1). */
Test(fresnel, energy_conservation_and_snell)
{
    const double n1s[] = {1.0, 1.5}, n2s[] = {1.5, 1.0};
    for (int k = 0; k < 2; k++) {
        double n1 = n1s[k], n2 = n2s[k], eta = n2 > n1 ? n2 / n1 : n1 / n2;
        for (int i = 1; i < 90; i++) {
            double th = i * M_PI / 180.0, c1 = cos(th), s1 = sin(th);
            double s2 = n1 / n2 * s1;
            double cos_i = n2 > n1 ? c1 : -c1; /* inside means negative cosine */
            double cos_t, eta_it, eta_ti;
            double r = fresnel_dielectric(cos_i, eta, &cos_t, &eta_it, &eta_ti);
            cr_assert_float_eq(eta_it, n2 / n1, 1e-14);
            cr_assert_float_eq(eta_ti * eta_it, 1.0, 1e-14);
            if (s2 >= 1.0) {
                cr_assert_eq(r, 1.0, "total internal reflection at %d deg", i);
                cr_assert_eq(cos_t, 0.0);
                continue;
            }
            double c2 = sqrt(1.0 - s2 * s2);
            cr_assert_float_eq(fabs(cos_t), c2, 1e-13);
            cr_assert(cos_t * cos_i < 0.0, "cos_t points to the other side");
            double ts = 2 * n1 * c1 / (n1 * c1 + n2 * c2), tp = 2 * n1 * c1 / (n2 * c1 + n1 * c2);
            double t = (n2 * c2) / (n1 * c1) * 0.5 * (ts * ts + tp * tp);
            cr_assert_float_eq(r + t, 1.0, 1e-12, "n1 %g n2 %g theta %d: R %g T %g", n1, n2, i, r, t);
        }
    }
}

Test(fresnel, brewster_angle_kills_p_polarisation)
{
    double n = 1.5, th = atan(n), c = cos(th);
    double r = fresnel_dielectric(c, n, NULL, NULL, NULL);
    double ct = sqrt(1.0 - sin(th) * sin(th) / (n * n));
    double rs = (c - n * ct) / (c + n * ct);
    cr_assert_float_eq(r, 0.5 * rs * rs, 1e-14);
}

Test(fresnel, conductor_reduces_to_closed_forms)
{
    /* Normal incidence: ((n-1)^2 + k^2) / ((n+1)^2 + k^2). */
    double n = 0.2, k = 3.9;
    cr_assert_float_eq(fresnel_conductor(1.0, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-14);
    /* k = 0 is a dielectric seen from outside. */
    for (int i = 0; i <= 90; i += 5) {
        double c = cos(i * M_PI / 180.0);
        cr_assert_float_eq(fresnel_conductor(c, 1.5, 0.0), fresnel_dielectric(c, 1.5, NULL, NULL, NULL), 1e-12,
                           "%d deg", i);
    }
    /* Grazing incidence reflects everything; eta 0, k 1 ("none") always does. */
    cr_assert_float_eq(fresnel_conductor(0.0, n, k), 1.0, 1e-12);
    for (int i = 0; i <= 90; i += 10)
        cr_assert_float_eq(fresnel_conductor(cos(i * M_PI / 180.0), 0.0, 1.0), 1.0, 1e-12);
}

Test(fresnel, diffuse_reflectance_identities)
{
    /* Light leaving a medium: 1 - Fdr_int = (1 - Fdr_ext) / eta^2 (reciprocity
     * of the smooth interface), which also checks the TIR part of the quadrature. */
    const double etas[] = {1.33, 1.49, 1.5046, 2.0};
    for (int i = 0; i < 4; i++) {
        double e = etas[i];
        double ext = fresnel_diffuse_reflectance(e), in = fresnel_diffuse_reflectance(1.0 / e);
        cr_assert_float_eq(1.0 - in, (1.0 - ext) / (e * e), 2e-6, "eta %g: ext %g int %g", e, ext, in);
    }
    /* Known value for eta = 1.5: about 0.0918 (e.g. Egan & Hilgeman's fit, d'Eon & Irving 2011). */
    cr_assert_float_eq(fresnel_diffuse_reflectance(1.5), 0.0918, 5e-4);
    cr_assert_float_eq(fresnel_diffuse_reflectance(1.0), 0.0, 1e-15);
}
