/* The synth-dev photographs' exact geometry (../shared/data/synth-dev, its
 * README), for the perspective tests and benchmark: the camera (elevation,
 * roll, focal length) from camera.json and the exact profile r(z) from
 * profile.csv; and the error of a reconstructed profile against it. */
#ifndef CELADON_TESTS_SYNTHDEV_TRUTH_H
#define CELADON_TESTS_SYNTHDEV_TRUTH_H

#include <stddef.h>

#include "celadon/bspline.h"

/* The eight cases, in INDEX.tsv order. */
extern const char *const SYNTHDEV_CASES[];
enum { SYNTHDEV_NCASES = 8 };

typedef struct {
    double elevation_deg, roll_deg, focal_px, height; /* height in the profile's unit (cm) */
    int n;
    double *z, *r; /* profile.csv, increasing z */
} synthdev_truth;

/* The data folder: $CELADON_SHARED/data/synth-dev, else
 * ../shared/data/synth-dev. Returns 1 when it exists. */
int synthdev_dir(char *out, size_t len);

/* Reads one case's camera.json and profile.csv. Returns 0, or -1 with a
 * reason in err. */
int synthdev_truth_load(const char *dir, const char *name, synthdev_truth *t, char *err, size_t errlen);
void synthdev_truth_free(synthdev_truth *t);

/* The distance of a profile curve (r, h), base (h = 0) to rim (its last
 * point's h), scaled so its rim is at the true height, from the true
 * profile (the polyline of profile.csv), at points evenly spaced in the
 * curve's parameter whose height lies within lo..hi (fractions of the
 * height): the mean and the largest, as fractions of the height. */
void synthdev_profile_error(const synthdev_truth *t, const bspline_t *curve, double lo, double hi, double *mean,
                            double *max);

#endif
