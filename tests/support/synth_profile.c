/* Analytic vessel profiles: see synth_profile.h. */
#include "synth_profile.h"

#include <math.h>
#include <stddef.h>

static const double PI = 3.14159265358979323846;

/* Logistic step from 0 (x << 0) to 1 (x >> 0). */
static double step(double x) { return 0.5 * (1 + tanh(0.5 * x)); }

/* From a (t well below c) to b (t well above c) over a width ~4w around c. */
static double blend(double t, double a, double b, double c, double w) { return a + (b - a) * step((t - c) / w); }

static double maebyeong(double t)
{
    /* A bell centred on the shoulder, long below (the taper to the foot),
     * short above (the shoulder rounding in), plus a slight flare at the foot;
     * then the short neck and the everted lip. */
    double width = blend(t, 0.40, 0.17, 0.74, 0.05);
    double x = (t - 0.74) / width;
    double body = 0.150 + 0.152 * exp(-x * x) + 0.02 * exp(-(t / 0.035) * (t / 0.035));
    double mouth = blend(t, 0.058, 0.120, 0.972, 0.008);
    return blend(t, body, mouth, 0.905, 0.011);
}

static double ewer(double t)
{
    /* A flattened bell (x² + 1.5 x⁴) for the round body, wider below its
     * middle so the foot stands; a thin neck that flares into the mouth. */
    double width = blend(t, 0.36, 0.28, 0.36, 0.06);
    double x = (t - 0.36) / width;
    double body = 0.25 * exp(-(x * x + 1.5 * x * x * x * x)) + 0.018 * exp(-(t / 0.03) * (t / 0.03));
    return 0.045 + body + blend(t, 0.0, 0.045, 0.95, 0.02);
}

static double lidded_jar(double t)
{
    /* Pieces joined by steep steps: body, neck, the lid's flange overhanging
     * the neck, its dome, the knob's stem, and the knob (a half sine up to its
     * flat top). */
    double body = 0.135 + 0.195 * exp(-((t - 0.47) / 0.33) * ((t - 0.47) / 0.33));
    double dome = 0.045 + 0.145 * cos(0.5 * PI * fmax(-1.2, fmin(1.2, (t - 0.765) / 0.165)));
    double knob = 0.03 + 0.035 * sin(PI * fmax(0.0, fmin(1.0, (t - 0.935) / 0.075)));
    double r = blend(t, body, 0.165, 0.705, 0.006); /* neck */
    r = blend(t, r, 0.190, 0.735, 0.003);           /* flange */
    r = blend(t, r, dome, 0.765, 0.004);
    r = blend(t, r, 0.028, 0.925, 0.004);           /* stem */
    return blend(t, r, knob, 0.950, 0.006);
}

static double footed_bowl(double t)
{
    double foot = 0.34 - 0.04 * t;
    double wall = 0.22 + 0.70 * (1 - exp(-(t - 0.05) / 0.30));
    return blend(t, foot, wall, 0.12, 0.008);
}

double synth_profile_radius(synth_profile profile, double t)
{
    switch (profile) {
    case SYNTH_PROFILE_VASE:
        return 0.17 + 0.09 * sin(2 * PI * (0.85 * t + 0.08));
    case SYNTH_PROFILE_BOWL:
        return 0.50 + 0.70 * t - 0.25 * t * t;
    case SYNTH_PROFILE_BOTTLE:
        return 0.08 + 0.17 * 0.5 * (1 - tanh((t - 0.6) / 0.07));
    case SYNTH_PROFILE_JAR:
        return 0.32 + 0.04 * sin(PI * t) - 0.02 * t;
    case SYNTH_PROFILE_MAEBYEONG:
        return maebyeong(t);
    case SYNTH_PROFILE_EWER:
        return ewer(t);
    case SYNTH_PROFILE_LIDDED_JAR:
        return lidded_jar(t);
    case SYNTH_PROFILE_FOOTED_BOWL:
        return footed_bowl(t);
    case SYNTH_PROFILE_CYLINDER:
    default:
        return 0.5;
    }
}

double synth_profile_max_radius(synth_profile profile)
{
    double m = 0;
    for (int k = 0; k <= 400; k++)
        m = fmax(m, synth_profile_radius(profile, k / 400.0));
    return m;
}

const char *synth_profile_name(synth_profile profile)
{
    static const char *const names[SYNTH_PROFILE_COUNT] = {"vase", "bowl",       "bottle",      "jar",     "maebyeong",
                                                           "ewer", "lidded_jar", "footed_bowl", "cylinder"};
    return (unsigned)profile < SYNTH_PROFILE_COUNT ? names[profile] : NULL;
}
