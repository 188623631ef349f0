/* Analytic vessel profiles for the synthetic photographs: closed-form, smooth
 * radius functions r(t) in units of the vessel's height H, t = h/H in [0, 1]
 * from the base (t = 0) to the rim (t = 1). Every profile has r > 0 on
 * [0, 1], so both ends are flat discs (the base and the rim, or a lid's knob
 * top). Sharp features (a lid's overhang, a foot ring) are logistic steps a
 * few thousandths of H wide: smooth, but steep at the scale of a pixel. */
#ifndef CELADON_TESTS_SYNTH_PROFILE_H
#define CELADON_TESTS_SYNTH_PROFILE_H

/* The first four are synth_vessel's shapes, in its order (synth_shape). */
typedef enum {
    SYNTH_PROFILE_VASE,        /* belly, narrow neck, flared mouth */
    SYNTH_PROFILE_BOWL,        /* wide and flaring, wider than tall, flat foot */
    SYNTH_PROFILE_BOTTLE,      /* round body, narrow neck (a tanh step) */
    SYNTH_PROFILE_JAR,         /* nearly a cylinder */
    SYNTH_PROFILE_MAEBYEONG,   /* plum vase: narrow foot, broad high shoulder, short neck, small everted mouth */
    SYNTH_PROFILE_EWER,        /* pear-shaped bottle: rounded body and shoulder under a long narrow neck */
    SYNTH_PROFILE_LIDDED_JAR,  /* ovoid jar, short neck, overhanging domed lid with a knob (all one surface) */
    SYNTH_PROFILE_FOOTED_BOWL, /* rounded bowl on a narrower foot ring */
    SYNTH_PROFILE_CYLINDER,    /* r = 0.5: a test solid and the stand of a scene */
    SYNTH_PROFILE_COUNT
} synth_profile;

/* r(t) in units of H. Outside [0, 1] the same formula is evaluated (callers
 * that need the solid clamp t). */
double synth_profile_radius(synth_profile profile, double t);

/* The largest r over 401 equally spaced t in [0, 1], units of H (a lower
 * bound of the true maximum: callers that need a bound add a margin). */
double synth_profile_max_radius(synth_profile profile);

/* A short lowercase name ("maebyeong"); NULL out of range. */
const char *synth_profile_name(synth_profile profile);

#endif
