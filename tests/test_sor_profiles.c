/* The test profiles themselves must satisfy the SOR contract. */
#include <criterion/criterion.h>

#include "support/sor_profiles.h"

Test(sor_profiles, valid_clamped_cubics_with_r_nonnegative)
{
    cr_assert_geq(sor_test_profile_count(), 7);
    for (int i = 0; i < sor_test_profile_count(); i++) {
        bspline_t c;
        sor_test_profile(i, &c);
        cr_assert_not_null(sor_test_profile_name(i));
        cr_assert_null(bspline_validate(&c), "%s", sor_test_profile_name(i));
        cr_assert_eq(c.degree, 3);
        cr_assert_eq(bspline_eval(&c, 0.0).y, 0.0, "%s: h(0) = 0", sor_test_profile_name(i));
        cr_assert_gt(bspline_eval(&c, 1.0).y, 0.0, "%s: h(1) > 0", sor_test_profile_name(i));
        for (int k = 0; k <= 1000; k++)
            cr_assert_geq(bspline_eval(&c, k / 1000.0).x, 0.0, "%s: r >= 0", sor_test_profile_name(i));
        bspline_free(&c);
    }
    cr_assert_null(sor_test_profile_name(sor_test_profile_count()));
}
