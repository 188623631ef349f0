/* The test vessels. Each is a control polygon plus interior knots; the
 * clamped knot vector is built from them. Shapes are chosen to exercise the
 * intersector: wide and flat, narrow necks, wide shoulders over a narrow base,
 * the axis being touched, a near-cylinder (ill-conditioned culling), a sharp
 * C0 corner with an inflection right after it, and a dense reconstructed-like
 * curve whose lip overhangs (h not monotone). */
#include "sor_profiles.h"

#include <stdio.h>
#include <stdlib.h>

typedef struct {
    const char *name;
    int n_ctrl;
    const vec2 *ctrl;
    const double *interior; /* n_ctrl - 4 interior knots, non-decreasing in (0,1) */
} profile_def;

static const vec2 bowl_p[] = {{0.35, 0.0}, {0.55, 0.0}, {0.8, 0.1}, {1.0, 0.35}, {1.08, 0.6}};
static const double bowl_k[] = {0.5};

static const vec2 bottle_p[] = {{0.4, 0.0}, {0.52, 0.0}, {0.56, 0.35}, {0.52, 0.85}, {0.16, 1.0},
                                {0.1, 1.3}, {0.1, 1.6}, {0.14, 1.72}};
static const double bottle_k[] = {0.2, 0.4, 0.6, 0.8};

/* Maebyeong: small foot, broad high shoulder, short narrow neck, flared mouth. */
static const vec2 plum_p[] = {{0.24, 0.0}, {0.28, 0.08}, {0.36, 0.55}, {0.78, 1.05}, {0.62, 1.36},
                              {0.14, 1.44}, {0.11, 1.54}, {0.18, 1.62}};
static const double plum_k[] = {0.15, 0.4, 0.7, 0.85};

/* Egg-shaped gourd closed at both ends: r = 0 at the base and at the top. */
static const vec2 gourd_p[] = {{0.0, 0.0}, {0.45, 0.0}, {0.62, 0.45}, {0.2, 0.72}, {0.34, 1.05},
                               {0.12, 1.3}, {0.0, 1.3}};
static const double gourd_k[] = {0.25, 0.5, 0.75};

static const vec2 cylinder_p[] = {{0.5, 0.0}, {0.5, 0.3}, {0.5004, 0.6}, {0.4998, 0.9}, {0.5, 1.2}};
static const double cylinder_k[] = {0.5};

/* A triple knot at 0.3 makes the control point (0.62, 0.12) a C0 corner of the
 * curve; right after it the wall bends in and out again (an inflection). */
static const vec2 corner_p[] = {{0.3, 0.0}, {0.5, 0.0}, {0.6, 0.04}, {0.62, 0.12}, {0.5, 0.22},
                                {0.42, 0.4}, {0.7, 0.7}, {0.66, 1.0}};
static const double corner_k[] = {0.3, 0.3, 0.3, 0.65};

/* Like a fit to a photo's contour: 20 control points, uneven knots, small
 * ripples, and a lip rolled inward so that it overhangs (its top is above
 * h(1): h decreases at the rim). */
static const vec2 recon_p[] = {{0.31, 0.0},  {0.36, 0.0},  {0.4, 0.02},  {0.43, 0.09}, {0.47, 0.2},
                               {0.53, 0.33}, {0.6, 0.47},  {0.64, 0.6},  {0.645, 0.72}, {0.62, 0.84},
                               {0.56, 0.95}, {0.45, 1.05}, {0.33, 1.13}, {0.25, 1.2},  {0.22, 1.28},
                               {0.225, 1.36}, {0.24, 1.42}, {0.3, 1.48}, {0.3, 1.53}, {0.26, 1.52}};
static const double recon_k[] = {0.04, 0.09, 0.15, 0.22, 0.3, 0.36, 0.43, 0.5,
                                 0.56, 0.62, 0.68, 0.74, 0.8, 0.85, 0.9, 0.95};

#define DEF(name, p, k) {name, (int)(sizeof p / sizeof p[0]), p, k}
static const profile_def defs[] = {
    DEF("bowl", bowl_p, bowl_k),
    DEF("bottle", bottle_p, bottle_k),
    DEF("plum", plum_p, plum_k),
    DEF("gourd", gourd_p, gourd_k),
    DEF("cylinder", cylinder_p, cylinder_k),
    DEF("corner", corner_p, corner_k),
    DEF("recon", recon_p, recon_k),
};
#undef DEF

int sor_test_profile_count(void) { return (int)(sizeof defs / sizeof defs[0]); }

const char *sor_test_profile_name(int i) { return i >= 0 && i < sor_test_profile_count() ? defs[i].name : NULL; }

void sor_test_profile(int i, bspline_t *out)
{
    const profile_def *d = &defs[i];
    if (bspline_init(out, 3, d->n_ctrl) != 0)
        abort();
    int nk = bspline_n_knots(out);
    for (int j = 0; j < 4; j++) {
        out->knots[j] = 0.0;
        out->knots[nk - 1 - j] = 1.0;
    }
    for (int j = 0; j < d->n_ctrl - 4; j++)
        out->knots[4 + j] = d->interior[j];
    for (int j = 0; j < d->n_ctrl; j++)
        out->ctrl[j] = d->ctrl[j];
}

sor_t *sor_test_create(int i, unsigned caps)
{
    bspline_t c;
    sor_test_profile(i, &c);
    char err[160];
    sor_t *s = sor_create(&c, 1.0, caps, err, sizeof err);
    bspline_free(&c);
    if (!s) {
        fprintf(stderr, "sor_test_create(%s): %s\n", sor_test_profile_name(i), err);
        abort();
    }
    return s;
}
