/* Spectra to RGB (spectrum.h): the integrals over the CIE range, Planck's
 * law, and the XYZ to Rec. 709 matrix. */
#include <math.h>
#include <string.h>

#include "scene_xml/spectrum.h"

/* The integrals are sums over SPECTRUM_STEPS evenly spaced wavelengths from
 * CIE_MIN_NM to CIE_MAX_NM, as Mitsuba 3 computes them; the normalisation
 * uses the same sum, so a flat spectrum comes out exactly flat. */
enum { SPECTRUM_STEPS = 1000 };

/* Table value i of column col at wavelength w, linearly interpolated. */
static double table_at(const double *tab, int stride, double w)
{
    double t = (w - CIE_MIN_NM) / 5.0;
    int i = (int)t;
    if (i < 0 || t < 0)
        return tab[0];
    if (i >= CIE_SAMPLES - 1)
        return tab[(CIE_SAMPLES - 1) * stride];
    double f = t - i;
    return (1 - f) * tab[i * stride] + f * tab[(i + 1) * stride];
}

static double step_nm(int i) { return CIE_MIN_NM + i * (CIE_MAX_NM - CIE_MIN_NM) / (SPECTRUM_STEPS - 1); }

static double ybar_at(double w) { return table_at(&cie1931_xyz[0][1], 3, w); }

/* Σ ȳ over the steps, and Σ ȳ·D65 / Σ ȳ (the luminance of the table's D65). */
static void norms(double *ysum, double *d65_luminance)
{
    double y = 0, yd = 0;
    for (int i = 0; i < SPECTRUM_STEPS; i++) {
        double w = step_nm(i);
        y += ybar_at(w);
        yd += ybar_at(w) * table_at(cie_d65, 1, w);
    }
    *ysum = y;
    *d65_luminance = yd / y;
}

typedef double (*spectrum_fn)(double nm, const void *ctx);

/* Σ f(w) x̄ȳz̄(w) [D65(w)] over the steps inside [wmin, wmax], normalised. */
static void integrate(spectrum_fn f, const void *ctx, double wmin, double wmax, bool d65, double xyz[3])
{
    double ysum, d65_lum;
    norms(&ysum, &d65_lum);
    xyz[0] = xyz[1] = xyz[2] = 0;
    for (int i = 0; i < SPECTRUM_STEPS; i++) {
        double w = step_nm(i);
        if (w < wmin || w > wmax)
            continue;
        double v = f(w, ctx) * (d65 ? table_at(cie_d65, 1, w) / d65_lum : 1.0);
        for (int k = 0; k < 3; k++)
            xyz[k] += v * table_at(&cie1931_xyz[0][k], 3, w);
    }
    for (int k = 0; k < 3; k++)
        xyz[k] /= ysum;
}

typedef struct {
    const double *wl, *v;
    int n;
} spectrum_list;

static double list_at(double w, const void *ctx)
{
    const spectrum_list *s = ctx;
    int i = 0;
    while (i < s->n - 2 && s->wl[i + 1] <= w)
        i++;
    if (s->n == 1)
        return s->v[0];
    double t = (w - s->wl[i]) / (s->wl[i + 1] - s->wl[i]);
    return (1 - t) * s->v[i] + t * s->v[i + 1];
}

void spectrum_list_xyz(const double *wl, const double *v, int n, bool d65, double xyz[3])
{
    spectrum_list s = {wl, v, n};
    integrate(list_at, &s, wl[0], wl[n - 1], d65, xyz);
}

static double planck(double nm, const void *ctx)
{
    const double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23; /* SI, exact since 2019 */
    double kelvin = *(const double *)ctx, lambda = nm * 1e-9;
    /* W m^-2 sr^-1 per metre of wavelength, times 1e-9: per nanometre. */
    return 1e-9 * 2 * h * c * c / (pow(lambda, 5) * expm1(h * c / (k * lambda * kelvin)));
}

void spectrum_blackbody_xyz(double kelvin, double wmin, double wmax, double xyz[3])
{
    integrate(planck, &kelvin, wmin, wmax, false, xyz);
}

scene_rgb spectrum_xyz_to_rgb(const double xyz[3])
{
    /* ITU-R BT.709 primaries and D65 white (the matrix Mitsuba and
     * color.h's rgb_luminance use). */
    const double m[3][3] = {{3.240479, -1.537150, -0.498535},
                            {-0.969256, 1.875991, 0.041556},
                            {0.055648, -0.204043, 1.057311}};
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[i][0] * xyz[0] + m[i][1] * xyz[1] + m[i][2] * xyz[2];
    return (scene_rgb){r[0], r[1], r[2]};
}

spectrum_use spectrum_use_of(scene_class cls, const char *name)
{
    static const char *unbounded[] = {"eta", "k", "int_ior", "ext_ior", "sigma_t", "sigma_a"};
    if (cls == SCENE_EMITTER)
        return SPECTRUM_EMITTED;
    for (size_t i = 0; i < sizeof unbounded / sizeof unbounded[0]; i++)
        if (strcmp(name, unbounded[i]) == 0)
            return SPECTRUM_UNBOUNDED;
    return SPECTRUM_BOUNDED;
}

scene_rgb spectrum_clamp(scene_rgb c, spectrum_use use)
{
    double hi = use == SPECTRUM_BOUNDED ? 1.0 : INFINITY;
    return (scene_rgb){fmin(fmax(c.r, 0.0), hi), fmin(fmax(c.g, 0.0), hi), fmin(fmax(c.b, 0.0), hi)};
}

scene_rgb spectrum_list_rgb(const double *wl, const double *v, int n, spectrum_use use)
{
    double xyz[3];
    spectrum_list_xyz(wl, v, n, use != SPECTRUM_EMITTED, xyz);
    return spectrum_clamp(spectrum_xyz_to_rgb(xyz), use);
}

scene_rgb spectrum_constant_rgb(double value, spectrum_use use)
{
    if (use != SPECTRUM_EMITTED)
        return (scene_rgb){value, value, value};
    /* Flat emission: the sRGB of the equal-energy white X = Y = Z. */
    const double one[3] = {value, value, value};
    return spectrum_xyz_to_rgb(one);
}
