/* Fresnel equations (Born & Wolf; Hecht, Optics ch. 4), unpolarised averages. */
#include "bsdfs/fresnel.h"

#include <stddef.h>

double fresnel_dielectric(double cos_i, double eta, double *cos_t, double *eta_it, double *eta_ti)
{
    double n = cos_i >= 0.0 ? eta : 1.0 / eta; /* n_t / n_i */
    double ci = fabs(cos_i);
    double sin2_t = (1.0 - ci * ci) / (n * n);
    if (eta_it)
        *eta_it = n;
    if (eta_ti)
        *eta_ti = 1.0 / n;
    if (sin2_t >= 1.0) { /* total internal reflection */
        if (cos_t)
            *cos_t = 0.0;
        return 1.0;
    }
    double ct = sqrt(1.0 - sin2_t);
    if (cos_t)
        *cos_t = cos_i >= 0.0 ? -ct : ct;
    if (n == 1.0)
        return 0.0;
    double rs = (ci - n * ct) / (ci + n * ct);
    double rp = (n * ci - ct) / (n * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

/* With a + ib = sqrt((eta + ik)^2 - sin^2), Rs and Rp in closed form. */
double fresnel_conductor(double cos_i, double eta, double k)
{
    double c = fmin(fabs(cos_i), 1.0);
    double c2 = c * c, s2 = 1.0 - c2;
    double t0 = eta * eta - k * k - s2;
    double a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k); /* a^2 + b^2 */
    double a = sqrt(fmax(0.0, 0.5 * (a2b2 + t0)));
    double t1 = a2b2 + c2, t2 = 2.0 * a * c;
    double rs = (t1 - t2) / (t1 + t2);
    double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    double rp = t3 + t4 > 0.0 ? rs * (t3 - t4) / (t3 + t4) : rs;
    return 0.5 * (rs + rp);
}

rgb fresnel_conductor_rgb(double cos_i, rgb eta, rgb k)
{
    return rgb_make(fresnel_conductor(cos_i, eta.r, k.r), fresnel_conductor(cos_i, eta.g, k.g),
                    fresnel_conductor(cos_i, eta.b, k.b));
}

double fresnel_diffuse_reflectance(double eta)
{
    /* 2 int_0^1 F(mu) mu dmu by composite Simpson. For eta < 1, F = 1 below the
     * critical cosine mu_c = sqrt(1 - eta^2) (exact part), and above it F has a
     * square-root kink at mu_c; substituting mu = mu_c + (1 - mu_c) s^2 makes
     * the integrand smooth in s. */
    double mu_c = eta < 1.0 ? sqrt(1.0 - eta * eta) : 0.0;
    const int n = 256; /* even */
    double h = 1.0 / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double s = i * h, mu = mu_c + (1.0 - mu_c) * s * s;
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * fresnel_dielectric(mu, eta, NULL, NULL, NULL) * mu * 2.0 * (1.0 - mu_c) * s;
    }
    return mu_c * mu_c + 2.0 * sum * h / 3.0;
}
