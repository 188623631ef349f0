/* Mitsuba's `hair` BSDF: the near-field hair fibre of Chiang, Bitterli,
 * Tappan and Burley 2016 ("A Practical and Controllable Hair and Fur Model
 * for Production Path Tracing"), as pbrt-v3 and Mitsuba 3 implement it.
 * Light entering the fibre leaves it after p internal segments: R (p = 0),
 * TT (1), TRT (2) and the residual of all longer paths (p = 3). Each lobe
 * is  Mp(theta_i, theta_o) Ap Np(dphi):  Mp the longitudinal spread (d'Eon
 * et al. 2011: the marginal of a von Mises-Fisher lobe around the cone of
 * mirror directions), Ap the Fresnel and Beer-Lambert attenuation along the
 * path inside a cylinder, Np a logistic in the azimuth trimmed to [-pi, pi]
 * around the perfectly specular exit angle; the residual is uniform in the
 * azimuth. With sigma_a = 0 the lobes' attenuations sum to 1 and
 * integral of eval over the sphere is 1 (pbrt's convention: eval is f |cos|
 * with no further cosine, the fibre scatters into every direction).
 *
 * The frame is Mitsuba's (BSDF_ANISOTROPIC: x along dp/du): on the curve
 * shapes dp/du runs around the fibre, so y is the fibre's tangent, z the
 * normal, and x-z the fibre's cross-section. theta is the angle of a
 * direction to that cross-section (sin theta = w.y), phi its angle in it
 * (atan2(w.z, w.x)), and the offset h across the fibre at which the light
 * arrives is sin gamma_i, gamma_i the angle of wi to the normal in the
 * cross-section. On any other shape the same frame is used, as Mitsuba
 * does (its documentation warns that the result is then not meaningful). */
#include <gsl/gsl_sf_bessel.h>
#include <math.h>

#include "bsdfs/bsdf_impl.h"
#include "bsdfs/fresnel.h"

enum { HAIR_P_MAX = 3 }; /* R, TT, TRT, then the residual */

/* d'Eon et al.'s absorption of the two melanins per unit hair radius. */
static const rgb eumelanin_sigma_a = {0.419, 0.697, 1.37};
static const rgb pheomelanin_sigma_a = {0.187, 0.4, 1.05};

typedef struct {
    double eta;                    /* int_ior / ext_ior */
    bsdf_spectrum sigma_a;         /* per unit radius, scale applied */
    double scale;                  /* applied to a textured sigma_a */
    double v[HAIR_P_MAX + 1];      /* longitudinal variances per lobe */
    double s;                      /* the azimuthal logistic's scale */
    double sin2k[3], cos2k[3];     /* sin, cos of the scale tilt alpha times 1, 2, 4 */
} hair_data;

/* The incident direction's parametrisation in the fibre's frame. */
typedef struct {
    double sin_theta, cos_theta, phi, gamma, h;
} hair_dir;

static hair_dir hair_param(vec3 w)
{
    hair_dir d;
    d.sin_theta = fmax(-1.0, fmin(1.0, w.y));
    d.cos_theta = sqrt(fmax(0.0, 1.0 - d.sin_theta * d.sin_theta));
    d.phi = atan2(w.z, w.x);
    double proj = sqrt(w.x * w.x + w.z * w.z);
    double g = proj > 0.0 ? acos(fmax(-1.0, fmin(1.0, w.z / proj))) : 0.0;
    d.gamma = w.x < 0.0 ? g : -g;
    d.h = sin(d.gamma);
    return d;
}

/* Mp: the density in theta_o (with weight cos theta_o, over 2 pi of azimuth)
 * of light arriving at theta_i, for the variance v = 1 / kappa:
 *   kappa / (2 sinh kappa) exp(-kappa sin_i sin_o) I0(kappa cos_i cos_o) / (2 pi),
 * written with the exponentially scaled I0 so that it neither overflows for
 * smooth fibres (kappa in the hundreds) nor loses digits for rough ones. */
static double hair_mp(double sin_i, double cos_i, double sin_o, double cos_o, double v)
{
    double kappa = 1.0 / v, c = kappa * cos_i * cos_o, s = kappa * sin_i * sin_o;
    double norm = kappa / -expm1(-2.0 * kappa); /* kappa e^kappa / (2 sinh kappa) */
    return norm * exp(c - s - kappa) * gsl_sf_bessel_I0_scaled(c) / (2.0 * M_PI);
}

static double logistic(double x, double s)
{
    x = fabs(x);
    double e = exp(-x / s);
    return e / (s * (1.0 + e) * (1.0 + e));
}

static double logistic_cdf(double x, double s) { return 1.0 / (1.0 + exp(-x / s)); }

/* Np: the logistic of scale s trimmed to [-pi, pi], at the azimuth dphi
 * measured from lobe p's specular exit angle. */
static double hair_np(double dphi, int p, double s, double gamma_i, double gamma_t)
{
    double x = dphi - (2.0 * p * gamma_t - 2.0 * gamma_i + p * M_PI);
    x = remainder(x, 2.0 * M_PI); /* into [-pi, pi] */
    return logistic(x, s) / (logistic_cdf(M_PI, s) - logistic_cdf(-M_PI, s));
}

static double trimmed_logistic_sample(double u, double s)
{
    double k = logistic_cdf(M_PI, s) - logistic_cdf(-M_PI, s);
    double x = -s * log(1.0 / (u * k + logistic_cdf(-M_PI, s)) - 1.0);
    return fmax(-M_PI, fmin(M_PI, x));
}

/* The longitudinal angle of lobe p's cone, tilted by the cuticle scales:
 * R by -2 alpha, TT by alpha, TRT by 4 alpha, the residual not at all. */
static void hair_tilt(const hair_data *d, const hair_dir *wi, int p, double *sin_ip, double *cos_ip)
{
    double st = wi->sin_theta, ct = wi->cos_theta;
    switch (p) {
    case 0: *sin_ip = st * d->cos2k[1] - ct * d->sin2k[1], *cos_ip = ct * d->cos2k[1] + st * d->sin2k[1]; break;
    case 1: *sin_ip = st * d->cos2k[0] + ct * d->sin2k[0], *cos_ip = ct * d->cos2k[0] - st * d->sin2k[0]; break;
    case 2: *sin_ip = st * d->cos2k[2] + ct * d->sin2k[2], *cos_ip = ct * d->cos2k[2] - st * d->sin2k[2]; break;
    default: *sin_ip = st, *cos_ip = ct; break;
    }
    *cos_ip = fabs(*cos_ip);
}

/* What the lobes of an incident direction share: the refracted angles and
 * the attenuations Ap, and the lobe-choice probabilities (Ap's luminance). */
typedef struct {
    hair_dir wi;
    double gamma_t;
    rgb a[HAIR_P_MAX + 1];
    double a_pdf[HAIR_P_MAX + 1];
} hair_lobes;

/* x / (1 - x): the sum x + x^2 + ...; 0 at x = 1, where grazing light is all
 * reflected and no path enters (the term it multiplies is then 0). */
static double series(double x) { return x < 1.0 ? x / (1.0 - x) : 0.0; }

static hair_lobes hair_lobes_at(const hair_data *d, const bsdf_query *q)
{
    hair_lobes l;
    l.wi = hair_param(q->wi);
    double st = l.wi.sin_theta, ct = l.wi.cos_theta;
    /* the refracted direction: longitudinally by Snell's law, azimuthally by
     * Bravais' index for the projection into the cross-section */
    double sin_theta_t = st / d->eta, cos_theta_t = sqrt(fmax(0.0, 1.0 - sin_theta_t * sin_theta_t));
    double eta_p = sqrt(fmax(0.0, d->eta * d->eta - st * st)) / ct;
    double sin_gamma_t = fmax(-1.0, fmin(1.0, l.wi.h / eta_p));
    double cos_gamma_t = sqrt(fmax(0.0, 1.0 - sin_gamma_t * sin_gamma_t));
    l.gamma_t = asin(sin_gamma_t);
    /* one crossing of the fibre is 2 cos gamma_t / cos theta_t radii long */
    rgb sa = rgb_scale(spectrum_eval(&d->sigma_a, bsdf_at(q)), d->scale);
    double len = 2.0 * cos_gamma_t / cos_theta_t;
    rgb tr = rgb_make(exp(-sa.r * len), exp(-sa.g * len), exp(-sa.b * len));
    double cos_gamma_i = sqrt(fmax(0.0, 1.0 - l.wi.h * l.wi.h));
    double f = fresnel_dielectric(ct * cos_gamma_i, d->eta, NULL, NULL, NULL);
    l.a[0] = rgb_gray(f);
    l.a[1] = rgb_scale(tr, (1.0 - f) * (1.0 - f));
    for (int p = 2; p < HAIR_P_MAX; p++)
        l.a[p] = rgb_scale(rgb_mul(l.a[p - 1], tr), f);
    rgb tf = rgb_scale(tr, f); /* the geometric series of the longer paths */
    l.a[HAIR_P_MAX] = rgb_mul(l.a[HAIR_P_MAX - 1], rgb_make(series(tf.r), series(tf.g), series(tf.b)));
    double sum = 0.0;
    for (int p = 0; p <= HAIR_P_MAX; p++)
        sum += l.a_pdf[p] = rgb_luminance(l.a[p]);
    for (int p = 0; p <= HAIR_P_MAX; p++)
        l.a_pdf[p] = sum > 0.0 ? l.a_pdf[p] / sum : (p == 0);
    return l;
}

/* The lobes at wo: value (with weights a) or density (with weights a_pdf). */
static void hair_sum(const hair_data *d, const hair_lobes *l, vec3 wo, rgb *value, double *pdf)
{
    hair_dir o = hair_param(wo);
    double dphi = o.phi - l->wi.phi;
    rgb f = rgb_gray(0.0);
    double dens = 0.0;
    for (int p = 0; p <= HAIR_P_MAX; p++) {
        double sin_ip, cos_ip;
        hair_tilt(d, &l->wi, p, &sin_ip, &cos_ip);
        double m = hair_mp(sin_ip, cos_ip, o.sin_theta, o.cos_theta, d->v[p]);
        double n = p < HAIR_P_MAX ? 2.0 * M_PI * hair_np(dphi, p, d->s, l->wi.gamma, l->gamma_t) : 1.0;
        f = rgb_add(f, rgb_scale(l->a[p], m * n));
        dens += l->a_pdf[p] * m * n;
    }
    if (value)
        *value = isfinite(f.r + f.g + f.b) ? f : rgb_gray(0.0);
    if (pdf)
        *pdf = isfinite(dens) ? dens : 0.0;
}

static rgb hair_eval(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    hair_lobes l = hair_lobes_at(b->data, q);
    rgb f;
    hair_sum(b->data, &l, wo, &f, NULL);
    return f;
}

static double hair_pdf(const bsdf_t *b, const bsdf_query *q, vec3 wo)
{
    hair_lobes l = hair_lobes_at(b->data, q);
    double pdf;
    hair_sum(b->data, &l, wo, NULL, &pdf);
    return pdf;
}

/* u1 picks the lobe by a_pdf and, rescaled, the azimuth; u2 the direction
 * on the lobe's longitudinal cone (Mp exactly). */
static int hair_sample(const bsdf_t *b, const bsdf_query *q, double u1, vec2 u2, bsdf_sample_rec *out)
{
    const hair_data *d = b->data;
    hair_lobes l = hair_lobes_at(d, q);
    int p = 0;
    while (p < HAIR_P_MAX && u1 >= l.a_pdf[p])
        u1 -= l.a_pdf[p++];
    double u_phi = l.a_pdf[p] > 0.0 ? fmax(0.0, fmin(1.0, u1 / l.a_pdf[p])) : 0.5;
    double sin_ip, cos_ip;
    hair_tilt(d, &l.wi, p, &sin_ip, &cos_ip);
    /* the angle to the cone's mirror direction, of density exp(kappa cos) */
    double v = d->v[p];
    double cos_t = 1.0 + v * log(u2.x + (1.0 - u2.x) * exp(-2.0 / v));
    cos_t = fmax(-1.0, fmin(1.0, cos_t));
    double sin_t = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
    double sin_o = -cos_t * sin_ip + sin_t * cos(2.0 * M_PI * u2.y) * cos_ip;
    sin_o = fmax(-1.0, fmin(1.0, sin_o));
    double cos_o = sqrt(fmax(0.0, 1.0 - sin_o * sin_o));
    double dphi = p < HAIR_P_MAX ? 2.0 * p * l.gamma_t - 2.0 * l.wi.gamma + p * M_PI + trimmed_logistic_sample(u_phi, d->s)
                                 : 2.0 * M_PI * u_phi;
    double phi_o = l.wi.phi + dphi;
    out->wo = v3_norm(v3(cos_o * cos(phi_o), sin_o, cos_o * sin(phi_o)));
    out->eta = 1.0; /* the path crosses the whole fibre and leaves it */
    out->sampled_type = out->wo.z * q->wi.z >= 0.0 ? BSDF_GLOSSY_REFLECTION : BSDF_GLOSSY_TRANSMISSION;
    rgb f;
    double pdf;
    hair_sum(d, &l, out->wo, &f, &pdf);
    if (!(pdf > 0.0))
        return 0;
    out->pdf = pdf;
    out->weight = rgb_scale(f, 1.0 / pdf);
    return 1;
}

/* For AOVs: all the light that light arriving along the normal (h = 0,
 * theta = 0) leaves with, the sum of the lobes' attenuations. */
static rgb hair_albedo(const bsdf_t *b, texture_point at)
{
    bsdf_query q = {.wi = v3(0.0, 0.0, 1.0), .uv = at.uv, .mesh = at.mesh, .prim = at.prim, .b1 = at.b1, .b2 = at.b2};
    hair_lobes l = hair_lobes_at(b->data, &q);
    rgb sum = rgb_gray(0.0);
    for (int p = 0; p <= HAIR_P_MAX; p++)
        sum = rgb_add(sum, l.a[p]);
    return sum;
}

static const bsdf_ops hair_ops = {"hair", hair_sample, hair_eval, hair_pdf, hair_albedo, NULL, NULL};

static double pow_int(double x, int n)
{
    double r = 1.0;
    while (n-- > 0)
        r *= x;
    return r;
}

static bsdf_t *hair_create(scene_obj *o, bsdf_set *set, char *err, size_t errlen)
{
    hair_data d = {0};
    double beta_m = scene_obj_float(o, "longitudinal_roughness", 0.3);
    double beta_n = scene_obj_float(o, "azimuthal_roughness", 0.3);
    double alpha = scene_obj_float(o, "scale_tilt", 2.0) * M_PI / 180.0;
    double int_ior, ext_ior;
    if (bsdf_ior_pair_param(o, "amber", &int_ior, &ext_ior, err, errlen) != 0)
        return NULL;
    if (!(beta_m >= 0.0 && beta_m <= 1.0))
        return bsdf_refuse(o, err, errlen, "longitudinal_roughness must be in [0, 1], not %g", beta_m), NULL;
    if (!(beta_n >= 0.0 && beta_n <= 1.0))
        return bsdf_refuse(o, err, errlen, "azimuthal_roughness must be in [0, 1], not %g", beta_n), NULL;
    if (!(int_ior > 0.0 && ext_ior > 0.0) || int_ior == ext_ior)
        return bsdf_refuse(o, err, errlen, "int_ior and ext_ior must be positive and differ"), NULL;
    d.eta = int_ior / ext_ior;
    d.scale = scene_obj_float(o, "scale", 1.0);
    if (scene_obj_has(o, "sigma_a")) {
        if (scene_obj_has(o, "pheomelanin")) /* eumelanin is the declaration's exclusive pair */
            return bsdf_refuse(o, err, errlen, "give the pigments or sigma_a, not both"), NULL;
        if (bsdf_spectrum_param(set, o, "sigma_a", 0.0, &d.sigma_a, err, errlen) != 0)
            return NULL;
        rgb c = d.sigma_a.value;
        if (!d.sigma_a.texture && !(c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0))
            return bsdf_refuse(o, err, errlen, "sigma_a must not be negative"), NULL;
    } else { /* the pigments, Mitsuba's brown by default; scale is for sigma_a only */
        double eu = scene_obj_float(o, "eumelanin", 1.3), pheo = scene_obj_float(o, "pheomelanin", 0.2);
        d.sigma_a.value = rgb_add(rgb_scale(eumelanin_sigma_a, eu), rgb_scale(pheomelanin_sigma_a, pheo));
        d.scale = 1.0;
    }
    if (!(d.scale >= 0.0) || !isfinite(d.scale))
        return bsdf_refuse(o, err, errlen, "scale must not be negative"), NULL;
    /* Chiang et al.'s fits of the lobes' widths to the roughnesses */
    d.v[0] = pow(0.726 * beta_m + 0.812 * beta_m * beta_m + 3.7 * pow_int(beta_m, 20), 2.0);
    d.v[1] = 0.25 * d.v[0];
    d.v[2] = d.v[3] = 4.0 * d.v[0];
    d.s = sqrt(M_PI / 8.0) * (0.265 * beta_n + 1.194 * beta_n * beta_n + 5.372 * pow_int(beta_n, 22));
    if (!(d.v[1] > 0.0) || !(d.s > 0.0))
        return bsdf_refuse(o, err, errlen, "a roughness of 0 gives a delta lobe, which the hair model cannot sample"),
               NULL;
    d.sin2k[0] = sin(alpha), d.cos2k[0] = sqrt(fmax(0.0, 1.0 - d.sin2k[0] * d.sin2k[0]));
    for (int i = 1; i < 3; i++) {
        d.sin2k[i] = 2.0 * d.cos2k[i - 1] * d.sin2k[i - 1];
        d.cos2k[i] = d.cos2k[i - 1] * d.cos2k[i - 1] - d.sin2k[i - 1] * d.sin2k[i - 1];
    }
    unsigned flags = BSDF_GLOSSY_REFLECTION | BSDF_GLOSSY_TRANSMISSION | BSDF_FRONT_SIDE | BSDF_ANISOTROPIC;
    return bsdf_alloc(o, &hair_ops, flags, &d, sizeof d, err, errlen);
}

static const scene_param_decl hair_params[] = {
    {"eumelanin", PARAM_FLOAT, 0, NULL},
    {"pheomelanin", PARAM_FLOAT, 0, NULL},
    {"sigma_a", PARAM_COLOR | PARAM_TEXTURE, 0, NULL},
    {"scale", PARAM_FLOAT, 0, NULL},
    BSDF_PARAMS_IOR,
    {"longitudinal_roughness", PARAM_FLOAT, 0, NULL},
    {"azimuthal_roughness", PARAM_FLOAT, 0, NULL},
    {"scale_tilt", PARAM_FLOAT, 0, NULL},
    BSDF_PARAMS_END,
};

const bsdf_plugin bsdf_hair = {
    .decl = {.cls = SCENE_BSDF, .type = "hair", .params = hair_params, .exclusive = {"sigma_a", "eumelanin"}},
    .create = hair_create,
};
