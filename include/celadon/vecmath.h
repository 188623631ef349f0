/* Small vector math: 2D and 3D double vectors, rays. Header-only, no GLM. */
#ifndef CELADON_VECMATH_H
#define CELADON_VECMATH_H

#include <math.h>

typedef struct { double x, y; } vec2;
typedef struct { double x, y, z; } vec3;

/* A ray o + t d. d need not be unit length unless a caller says so. */
typedef struct { vec3 o, d; } ray3;

static inline vec2 v2(double x, double y) { return (vec2){x, y}; }
static inline vec2 v2_add(vec2 a, vec2 b) { return (vec2){a.x + b.x, a.y + b.y}; }
static inline vec2 v2_sub(vec2 a, vec2 b) { return (vec2){a.x - b.x, a.y - b.y}; }
static inline vec2 v2_scale(vec2 a, double s) { return (vec2){a.x * s, a.y * s}; }
static inline double v2_dot(vec2 a, vec2 b) { return a.x * b.x + a.y * b.y; }
static inline double v2_cross(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }
static inline double v2_len(vec2 a) { return hypot(a.x, a.y); }
static inline vec2 v2_norm(vec2 a) { double l = v2_len(a); return l > 0 ? v2_scale(a, 1.0 / l) : a; }
static inline vec2 v2_lerp(vec2 a, vec2 b, double t) { return (vec2){a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; }

static inline vec3 v3(double x, double y, double z) { return (vec3){x, y, z}; }
static inline vec3 v3_add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline vec3 v3_sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline vec3 v3_scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
static inline vec3 v3_neg(vec3 a) { return (vec3){-a.x, -a.y, -a.z}; }
static inline double v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline double v3_len(vec3 a) { return sqrt(v3_dot(a, a)); }
static inline vec3 v3_norm(vec3 a) { double l = v3_len(a); return l > 0 ? v3_scale(a, 1.0 / l) : a; }
static inline vec3 ray3_at(ray3 r, double t) { return v3_add(r.o, v3_scale(r.d, t)); }

/* Orthonormal frame (s, t, n); builds a tangent frame around n without branches
 * that lose precision near the poles (Duff et al. 2017). */
typedef struct { vec3 s, t, n; } frame3;
static inline frame3 frame3_from_normal(vec3 n)
{
    double sign = copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double b = n.x * n.y * a;
    frame3 f;
    f.s = v3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = v3(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}
static inline vec3 frame3_to_local(frame3 f, vec3 v) { return v3(v3_dot(v, f.s), v3_dot(v, f.t), v3_dot(v, f.n)); }
static inline vec3 frame3_to_world(frame3 f, vec3 v)
{
    return v3_add(v3_add(v3_scale(f.s, v.x), v3_scale(f.t, v.y)), v3_scale(f.n, v.z));
}

#endif
