/* 4x4 affine transforms in double precision, carried with their inverse so
 * that normals and inverse mappings cost no inversion. Conventions follow
 * Mitsuba 3: column vectors (p' = M p), rotation angles in degrees,
 * counter-clockwise about the axis (right-handed), and `lookat` maps local +z
 * to the view direction, +y to the up direction, +x to "left". */
#ifndef CELADON_TRANSFORM_H
#define CELADON_TRANSFORM_H

#include "celadon/vecmath.h"

typedef struct {
    double m[4][4];   /* row-major: m[row][col] */
    double inv[4][4]; /* inverse of m */
} transform4;

transform4 transform_identity(void);
transform4 transform_translate(vec3 t);
/* Scale factors must be nonzero (the inverse divides by them). */
transform4 transform_scale(vec3 s);
/* Counter-clockwise rotation by angle_deg about axis (normalised here; must
 * be nonzero). */
transform4 transform_rotate(vec3 axis, double angle_deg);
/* Camera-style frame at origin looking at target: columns (left, up', dir,
 * origin) with dir = |target - origin|, left = |up x dir|, up' = dir x left.
 * Returns 0, or -1 when origin == target or up is parallel to dir. */
int transform_lookat(vec3 origin, vec3 target, vec3 up, transform4 *out);
/* From 16 row-major values. Returns 0, or -1 if the last row is not
 * (0 0 0 1) or the 3x3 part is singular (|det| <= 1e-12 · scale³). */
int transform_from_rows(const double v[16], transform4 *out);

/* a ∘ b: applies b first, then a (matrix product a·b). */
transform4 transform_compose(const transform4 *a, const transform4 *b);
transform4 transform_inverse(const transform4 *t);

vec3 transform_point(const transform4 *t, vec3 p);
vec3 transform_vector(const transform4 *t, vec3 v);
/* Normals map by the inverse transpose; the result is not renormalised. */
vec3 transform_normal(const transform4 *t, vec3 n);

/* Largest absolute elementwise difference of the forward matrices. */
double transform_max_diff(const transform4 *a, const transform4 *b);

#endif
