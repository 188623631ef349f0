/* Affine transforms against hand-computed matrices and algebraic identities. */
#include <criterion/criterion.h>

#include "celadon/transform.h"

static void assert_vec(vec3 a, vec3 b, double tol)
{
    cr_assert(fabs(a.x - b.x) <= tol && fabs(a.y - b.y) <= tol && fabs(a.z - b.z) <= tol,
              "(%.15g %.15g %.15g) != (%.15g %.15g %.15g)", a.x, a.y, a.z, b.x, b.y, b.z);
}

static void assert_identity(const double m[4][4], double tol)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            cr_assert_float_eq(m[i][j], i == j ? 1.0 : 0.0, tol, "[%d][%d] = %g", i, j, m[i][j]);
}

static void assert_inverse_pair(const transform4 *t)
{
    double p[4][4] = {{0}};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++)
                p[i][j] += t->m[i][k] * t->inv[k][j];
    assert_identity(p, 1e-12);
}

Test(transform, rotate_is_counter_clockwise_in_degrees)
{
    transform4 r = transform_rotate(v3(0, 0, 1), 90);
    assert_vec(transform_point(&r, v3(1, 0, 0)), v3(0, 1, 0), 1e-15);
    assert_vec(transform_point(&r, v3(0, 1, 0)), v3(-1, 0, 0), 1e-15);
    transform4 ry = transform_rotate(v3(0, 2, 0), 90); /* axis need not be unit */
    assert_vec(transform_point(&ry, v3(0, 0, 1)), v3(1, 0, 0), 1e-15);
    /* 120 degrees about (1,1,1) cycles the axes x -> y -> z. */
    transform4 d = transform_rotate(v3(1, 1, 1), 120);
    assert_vec(transform_vector(&d, v3(1, 0, 0)), v3(0, 1, 0), 1e-15);
    assert_vec(transform_vector(&d, v3(0, 1, 0)), v3(0, 0, 1), 1e-15);
    assert_inverse_pair(&d);
}

Test(transform, compose_applies_right_operand_first)
{
    transform4 t = transform_translate(v3(1, 0, 0));
    transform4 r = transform_rotate(v3(0, 0, 1), 90);
    transform4 rt = transform_compose(&r, &t); /* translate, then rotate */
    assert_vec(transform_point(&rt, v3(0, 0, 0)), v3(0, 1, 0), 1e-15);
    transform4 tr = transform_compose(&t, &r); /* rotate, then translate */
    assert_vec(transform_point(&tr, v3(0, 0, 0)), v3(1, 0, 0), 1e-15);
    /* Hand-written matrix of rotate∘translate. */
    const double want[16] = {0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 1};
    transform4 w;
    cr_assert_eq(transform_from_rows(want, &w), 0);
    cr_assert_leq(transform_max_diff(&rt, &w), 1e-15);
    assert_inverse_pair(&rt);
}

Test(transform, scale_translate_vectors_and_normals)
{
    transform4 s = transform_scale(v3(2, 3, 4));
    transform4 t = transform_translate(v3(5, 6, 7));
    transform4 m = transform_compose(&t, &s);
    assert_vec(transform_point(&m, v3(1, 1, 1)), v3(7, 9, 11), 1e-15);
    assert_vec(transform_vector(&m, v3(1, 1, 1)), v3(2, 3, 4), 1e-15); /* no translation */
    /* A normal stays perpendicular to every transformed tangent of its plane. */
    vec3 n = v3(1, 1, 1), t1 = v3(1, -1, 0), t2 = v3(0, 1, -1);
    vec3 nn = transform_normal(&m, n);
    cr_assert_float_eq(v3_dot(nn, transform_vector(&m, t1)), 0, 1e-14);
    cr_assert_float_eq(v3_dot(nn, transform_vector(&m, t2)), 0, 1e-14);
    transform4 mi = transform_inverse(&m);
    assert_vec(transform_point(&mi, v3(7, 9, 11)), v3(1, 1, 1), 1e-14);
    assert_inverse_pair(&m);
}

Test(transform, lookat_follows_mitsuba_axes)
{
    transform4 l;
    cr_assert_eq(transform_lookat(v3(0, 0, 0), v3(5, 0, 0), v3(0, 0, 1), &l), 0);
    /* local +z = view direction, +y = up, +x = left = up x dir */
    assert_vec(transform_vector(&l, v3(0, 0, 1)), v3(1, 0, 0), 1e-15);
    assert_vec(transform_vector(&l, v3(0, 1, 0)), v3(0, 0, 1), 1e-15);
    assert_vec(transform_vector(&l, v3(1, 0, 0)), v3(0, 1, 0), 1e-15);
    /* Non-orthogonal up is orthogonalised; origin is the translation. */
    cr_assert_eq(transform_lookat(v3(1, 2, 3), v3(1, 2, 10), v3(0, 1, 0.5), &l), 0);
    assert_vec(transform_point(&l, v3(0, 0, 0)), v3(1, 2, 3), 1e-15);
    assert_vec(transform_vector(&l, v3(0, 1, 0)), v3(0, 1, 0), 1e-15);
    assert_vec(transform_vector(&l, v3(1, 0, 0)), v3(1, 0, 0), 1e-15);
    assert_inverse_pair(&l);
    cr_assert_eq(transform_lookat(v3(0, 0, 0), v3(0, 3, 0), v3(0, 1, 0), &l), -1, "up parallel to view");
    cr_assert_eq(transform_lookat(v3(1, 1, 1), v3(1, 1, 1), v3(0, 1, 0), &l), -1, "origin == target");
}

Test(transform, from_rows_checks_affine_and_invertible)
{
    const double ok[16] = {0, 2, 0, 1, -3, 0, 0, 2, 0, 0, 0.5, 3, 0, 0, 0, 1};
    transform4 t;
    cr_assert_eq(transform_from_rows(ok, &t), 0);
    assert_vec(transform_point(&t, v3(1, 1, 1)), v3(3, -1, 3.5), 1e-15);
    assert_inverse_pair(&t);
    const double projective[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    cr_assert_eq(transform_from_rows(projective, &t), -1);
    const double singular[16] = {1, 2, 3, 0, 2, 4, 6, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    cr_assert_eq(transform_from_rows(singular, &t), -1);
}
