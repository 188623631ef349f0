#include "celadon/transform.h"

#include <string.h>

static void mat_identity(double m[4][4])
{
    memset(m, 0, sizeof(double[4][4]));
    for (int i = 0; i < 4; i++)
        m[i][i] = 1.0;
}

static void mat_mul(const double a[4][4], const double b[4][4], double out[4][4])
{
    double r[4][4];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += a[i][k] * b[k][j];
            r[i][j] = s;
        }
    memcpy(out, r, sizeof r);
}

/* Inverse of an affine matrix (last row 0 0 0 1): invert the 3x3 block by
 * cofactors, then the translation is -A^-1 t. Returns -1 if singular. */
static int affine_inverse(const double m[4][4], double inv[4][4])
{
    double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    double scale = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            scale = fmax(scale, fabs(m[i][j]));
    if (!(fabs(det) > 1e-12 * scale * scale * scale))
        return -1;
    double r = 1.0 / det;
    double a[3][3] = {
        {c00 * r, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * r, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * r},
        {c01 * r, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * r, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * r},
        {c02 * r, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * r, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * r},
    };
    mat_identity(inv);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            inv[i][j] = a[i][j];
        inv[i][3] = -(a[i][0] * m[0][3] + a[i][1] * m[1][3] + a[i][2] * m[2][3]);
    }
    return 0;
}

transform4 transform_identity(void)
{
    transform4 t;
    mat_identity(t.m);
    mat_identity(t.inv);
    return t;
}

transform4 transform_translate(vec3 v)
{
    transform4 t = transform_identity();
    t.m[0][3] = v.x, t.m[1][3] = v.y, t.m[2][3] = v.z;
    t.inv[0][3] = -v.x, t.inv[1][3] = -v.y, t.inv[2][3] = -v.z;
    return t;
}

transform4 transform_scale(vec3 s)
{
    transform4 t = transform_identity();
    t.m[0][0] = s.x, t.m[1][1] = s.y, t.m[2][2] = s.z;
    t.inv[0][0] = 1.0 / s.x, t.inv[1][1] = 1.0 / s.y, t.inv[2][2] = 1.0 / s.z;
    return t;
}

/* Rodrigues: R = cos·I + sin·[a]x + (1 - cos)·a aᵀ; R⁻¹ = Rᵀ. */
transform4 transform_rotate(vec3 axis, double angle_deg)
{
    vec3 a = v3_norm(axis);
    double rad = angle_deg * (M_PI / 180.0);
    double s = sin(rad), c = cos(rad), k = 1.0 - c;
    transform4 t = transform_identity();
    double r[3][3] = {
        {c + k * a.x * a.x, k * a.x * a.y - s * a.z, k * a.x * a.z + s * a.y},
        {k * a.y * a.x + s * a.z, c + k * a.y * a.y, k * a.y * a.z - s * a.x},
        {k * a.z * a.x - s * a.y, k * a.z * a.y + s * a.x, c + k * a.z * a.z},
    };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            t.m[i][j] = r[i][j];
            t.inv[j][i] = r[i][j];
        }
    return t;
}

int transform_lookat(vec3 origin, vec3 target, vec3 up, transform4 *out)
{
    vec3 dir = v3_sub(target, origin);
    if (!(v3_len(dir) > 0))
        return -1;
    dir = v3_norm(dir);
    vec3 left = v3_cross(up, dir);
    double ll = v3_len(left);
    if (!(ll > 1e-9 * v3_len(up)))
        return -1;
    left = v3_scale(left, 1.0 / ll);
    vec3 new_up = v3_cross(dir, left);
    const vec3 cols[4] = {left, new_up, dir, origin};
    double v[16] = {0};
    for (int j = 0; j < 4; j++) {
        v[0 * 4 + j] = cols[j].x;
        v[1 * 4 + j] = cols[j].y;
        v[2 * 4 + j] = cols[j].z;
    }
    v[15] = 1.0;
    return transform_from_rows(v, out);
}

int transform_from_rows(const double v[16], transform4 *out)
{
    if (v[12] != 0.0 || v[13] != 0.0 || v[14] != 0.0 || v[15] != 1.0)
        return -1;
    transform4 t;
    for (int i = 0; i < 16; i++)
        t.m[i / 4][i % 4] = v[i];
    if (affine_inverse(t.m, t.inv) != 0)
        return -1;
    *out = t;
    return 0;
}

transform4 transform_compose(const transform4 *a, const transform4 *b)
{
    transform4 t;
    mat_mul(a->m, b->m, t.m);
    mat_mul(b->inv, a->inv, t.inv);
    return t;
}

transform4 transform_inverse(const transform4 *t)
{
    transform4 r;
    memcpy(r.m, t->inv, sizeof r.m);
    memcpy(r.inv, t->m, sizeof r.inv);
    return r;
}

vec3 transform_point(const transform4 *t, vec3 p)
{
    const double(*m)[4] = t->m;
    return v3(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
              m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
              m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}

vec3 transform_vector(const transform4 *t, vec3 v)
{
    const double(*m)[4] = t->m;
    return v3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
              m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
              m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

vec3 transform_normal(const transform4 *t, vec3 n)
{
    const double(*w)[4] = t->inv;
    return v3(w[0][0] * n.x + w[1][0] * n.y + w[2][0] * n.z,
              w[0][1] * n.x + w[1][1] * n.y + w[2][1] * n.z,
              w[0][2] * n.x + w[1][2] * n.y + w[2][2] * n.z);
}

double transform_max_diff(const transform4 *a, const transform4 *b)
{
    double d = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            d = fmax(d, fabs(a->m[i][j] - b->m[i][j]));
    return d;
}
