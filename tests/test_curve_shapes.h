/* Known curves shared by the curve, mesh and profile tests. */
#ifndef CELADON_TEST_CURVE_SHAPES_H
#define CELADON_TEST_CURVE_SHAPES_H

#include <criterion/criterion.h>

#include "celadon/bspline.h"

/* A vase profile in pixels: clamped cubic, r > 0 everywhere, h strictly
 * increasing (all control points climb), one double interior knot. */
static inline bspline_t test_vase_curve(void)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 8), 0);
    const double U[] = {0, 0, 0, 0, 0.1, 0.35, 0.35, 0.7, 1, 1, 1, 1};
    const vec2 P[] = {{30, 0}, {45, 10}, {60, 40}, {20, 70}, {15, 90}, {25, 110}, {35, 130}, {33, 140}};
    for (int i = 0; i < 12; i++)
        c.knots[i] = U[i];
    for (int i = 0; i < 8; i++)
        c.ctrl[i] = P[i];
    cr_assert_null(bspline_validate(&c));
    return c;
}

/* A bowl that starts on the axis: r(0) = 0 with a horizontal tangent there. */
static inline bspline_t test_bowl_curve(void)
{
    bspline_t c;
    cr_assert_eq(bspline_init(&c, 3, 5), 0);
    const double U[] = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
    const vec2 P[] = {{0, 0}, {40, 0}, {80, 20}, {95, 60}, {100, 90}};
    for (int i = 0; i < 9; i++)
        c.knots[i] = U[i];
    for (int i = 0; i < 5; i++)
        c.ctrl[i] = P[i];
    cr_assert_null(bspline_validate(&c));
    return c;
}

#endif
