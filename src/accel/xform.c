/* Affine object-to-world transforms (3x4, row-major, double). */
#include "accel/accel_internal.h"

accel_xform accel_xform_identity(void)
{
    return (accel_xform){{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
}

accel_xform accel_xform_translate(vec3 t)
{
    return (accel_xform){{{1, 0, 0, t.x}, {0, 1, 0, t.y}, {0, 0, 1, t.z}}};
}

accel_xform accel_xform_scale(vec3 s)
{
    return (accel_xform){{{s.x, 0, 0, 0}, {0, s.y, 0, 0}, {0, 0, s.z, 0}}};
}

/* Rodrigues: R = cos a I + sin a [k]x + (1 - cos a) k k^T. */
accel_xform accel_xform_rotate(vec3 k, double angle)
{
    double c = cos(angle), s = sin(angle), C = 1.0 - c;
    return (accel_xform){{{c + k.x * k.x * C, k.x * k.y * C - k.z * s, k.x * k.z * C + k.y * s, 0},
                          {k.y * k.x * C + k.z * s, c + k.y * k.y * C, k.y * k.z * C - k.x * s, 0},
                          {k.z * k.x * C - k.y * s, k.z * k.y * C + k.x * s, c + k.z * k.z * C, 0}}};
}

accel_xform accel_xform_compose(const accel_xform *a, const accel_xform *b)
{
    accel_xform r;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double v = j == 3 ? a->m[i][3] : 0.0;
            for (int k = 0; k < 3; k++)
                v += a->m[i][k] * b->m[k][j];
            r.m[i][j] = v;
        }
    }
    return r;
}

vec3 accel_xform_point(const accel_xform *x, vec3 p)
{
    return v3(x->m[0][0] * p.x + x->m[0][1] * p.y + x->m[0][2] * p.z + x->m[0][3],
              x->m[1][0] * p.x + x->m[1][1] * p.y + x->m[1][2] * p.z + x->m[1][3],
              x->m[2][0] * p.x + x->m[2][1] * p.y + x->m[2][2] * p.z + x->m[2][3]);
}

vec3 accel_xform_vector(const accel_xform *x, vec3 v)
{
    return v3(x->m[0][0] * v.x + x->m[0][1] * v.y + x->m[0][2] * v.z,
              x->m[1][0] * v.x + x->m[1][1] * v.y + x->m[1][2] * v.z,
              x->m[2][0] * v.x + x->m[2][1] * v.y + x->m[2][2] * v.z);
}

/* Inverse by the adjugate; fails when the linear part is singular (or not
 * finite) relative to its own scale. */
int xform_invert(const accel_xform *x, accel_xform *inv)
{
    const double(*m)[4] = x->m;
    double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    double scale = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            scale = fmax(scale, fabs(m[i][j]));
    if (!isfinite(det) || !isfinite(scale) || fabs(det) <= 1e-12 * scale * scale * scale)
        return -1;
    double id = 1.0 / det;
    double a[3][3] = {
        {c00 * id, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * id, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * id},
        {c01 * id, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * id, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * id},
        {c02 * id, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * id, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * id},
    };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            inv->m[i][j] = a[i][j];
        inv->m[i][3] = -(a[i][0] * m[0][3] + a[i][1] * m[1][3] + a[i][2] * m[2][3]);
    }
    return 0;
}

/* Normals map by the inverse transpose: n' = A^-T n, renormalised. */
vec3 xform_normal(const accel_xform *inv, vec3 n)
{
    return v3_norm(v3(inv->m[0][0] * n.x + inv->m[1][0] * n.y + inv->m[2][0] * n.z,
                      inv->m[0][1] * n.x + inv->m[1][1] * n.y + inv->m[2][1] * n.z,
                      inv->m[0][2] * n.x + inv->m[1][2] * n.y + inv->m[2][2] * n.z));
}
