/* Triangle meshes through the Embree scene: hits on a cube and a quad against
 * the slab method and planar barycentrics the test computes itself, under
 * rigid, non-uniform and mirroring transforms; nearest-of-two; occlusion;
 * rejected input; the float bounds of a double ray interval. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/accel_internal.h"
#include "celadon/accel.h"
#include "test_accel_support.h"

/* The cube [-0.5, 0.5]^3 as 6 faces of 4 own vertices (normal = face normal,
 * uv = the face's (a, b) coordinates from its first corner), counter-clockwise
 * from outside. Face f: normal n, tangents a x b = n. */
static const vec3 face_n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const vec3 face_a[6] = {{0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}};
static const vec3 face_b[6] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}};

static vec3 face_origin(int f) { return v3_sub(v3_scale(face_n[f], 0.5), v3_scale(v3_add(face_a[f], face_b[f]), 0.5)); }

static mesh_t cube_mesh(void)
{
    mesh_t m = {.n_verts = 24, .n_tris = 12};
    m.pos = calloc(3 * 24 + 1, sizeof(float));
    m.nrm = calloc(3 * 24, sizeof(float));
    m.uv = calloc(2 * 24, sizeof(float));
    m.tri = calloc(3 * 12, sizeof(uint32_t));
    const double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    for (int f = 0; f < 6; f++) {
        for (int k = 0; k < 4; k++) {
            int i = 4 * f + k;
            vec3 p = v3_add(face_origin(f), v3_add(v3_scale(face_a[f], cu[k]), v3_scale(face_b[f], cv[k])));
            m.pos[3 * i] = (float)p.x, m.pos[3 * i + 1] = (float)p.y, m.pos[3 * i + 2] = (float)p.z;
            m.nrm[3 * i] = (float)face_n[f].x, m.nrm[3 * i + 1] = (float)face_n[f].y, m.nrm[3 * i + 2] = (float)face_n[f].z;
            m.uv[2 * i] = (float)cu[k], m.uv[2 * i + 1] = (float)cv[k];
        }
        const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++)
            m.tri[6 * f + k] = 4 * (uint32_t)f + t[k];
    }
    return m;
}

static void free_mesh(mesh_t *m)
{
    free(m->pos), free(m->nrm), free(m->uv), free(m->tri);
}

/* Slab method: entry t and the face entered, or 0 on a miss. */
static int cube_slab(ray3 r, double *t, int *face)
{
    double o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
    double t0 = 0, t1 = INFINITY;
    int f0 = -1;
    for (int k = 0; k < 3; k++) {
        double ta = (-0.5 - o[k]) / d[k], tb = (0.5 - o[k]) / d[k];
        int fa = 2 * k + 1, fb = 2 * k;
        if (ta > tb) {
            double s = ta; ta = tb; tb = s;
            int g = fa; fa = fb; fb = g;
        }
        if (ta > t0)
            t0 = ta, f0 = fa;
        t1 = fmin(t1, tb);
    }
    if (f0 < 0 || t0 > t1)
        return 0;
    *t = t0;
    *face = f0;
    return 1;
}

static accel_t *scene_with(const mesh_t *m, const transform4 *xf)
{
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_BEST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    cr_assert_eq(accel_add_mesh(acc, m, xf, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    return acc;
}

static void vec_near(vec3 a, vec3 b, double tol, const char *what, int i)
{
    cr_assert(v3_len(v3_sub(a, b)) <= tol, "ray %d %s: (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", i, what, a.x, a.y,
              a.z, b.x, b.y, b.z);
}

/* xf = T R S with its inverse composed from the inverted factors; the cube's
 * hits must be the slab hits of the object-space ray, to double rounding. */
static void check_cube(vec3 scale, vec3 axis, double angle_deg, vec3 shift)
{
    transform4 S = transform_scale(scale), R = transform_rotate(v3_norm(axis), angle_deg),
                T = transform_translate(shift);
    transform4 RS = transform_compose(&R, &S), xf = transform_compose(&T, &RS);
    transform4 Si = transform_scale(v3(1 / scale.x, 1 / scale.y, 1 / scale.z)),
                Ri = transform_rotate(v3_norm(axis), -angle_deg), Ti = transform_translate(v3_neg(shift));
    transform4 RiTi = transform_compose(&Ri, &Ti), inv = transform_compose(&Si, &RiTi);
    mesh_t m = cube_mesh();
    accel_t *acc = scene_with(&m, &xf);
    vec3 lo, hi;
    accel_bounds(acc, &lo, &hi);
    int mirrored = scale.x * scale.y * scale.z < 0, hits = 0;
    test_rng rng = {42};
    for (int i = 0; i < 3000; i++) {
        ray3 r = test_ray_toward_box(&rng, lo, hi);
        ray3 ro = {transform_point(&inv, r.o), transform_vector(&inv, r.d)};
        double t = 0;
        int f = -1;
        int expect = cube_slab(ro, &t, &f);
        accel_hit h;
        int got = accel_intersect(acc, &r, 0, INFINITY, &h);
        cr_assert_eq(got, expect, "ray %d: hit %d, slab says %d", i, got, expect);
        cr_assert_eq(accel_occluded(acc, &r, 0, INFINITY), expect, "ray %d occlusion", i);
        if (!expect) {
            cr_assert_eq(h.geom_id, ACCEL_INVALID_ID);
            continue;
        }
        hits++;
        cr_assert_eq(h.geom_id, 0u);
        cr_assert_eq(h.kind, ACCEL_KIND_MESH);
        cr_assert_eq(h.prim / 2, (unsigned)f, "ray %d: triangle %u, slab face %d", i, h.prim, f);
        cr_assert_float_eq(h.t, t, 1e-12 * t, "ray %d: t %.17g vs %.17g", i, h.t, t);
        vec_near(h.p, ray3_at(r, t), 1e-12 * (1 + v3_len(r.o)), "point", i);
        /* Normals map by A^-T = R S^-1. */
        vec3 n = v3_norm(transform_vector(&R, v3(face_n[f].x / scale.x, face_n[f].y / scale.y, face_n[f].z / scale.z)));
        vec_near(h.ng, n, 1e-12, "geometric normal", i);
        vec_near(h.ns, n, 1e-6, "shading normal", i);
        cr_assert_lt(v3_dot(h.ng, r.d), 0.0, "ray %d: the outside is hit from outside%s", i,
                     mirrored ? " (mirrored)" : "");
        vec3 q = v3_sub(ray3_at(ro, t), face_origin(f));
        cr_assert_float_eq(h.uv.x, v3_dot(q, face_a[f]), 1e-6, "ray %d uv.x", i);
        cr_assert_float_eq(h.uv.y, v3_dot(q, face_b[f]), 1e-6, "ray %d uv.y", i);
        cr_assert_eq(accel_occluded(acc, &r, 0, 0.999 * t), 0, "ray %d: nothing before the hit", i);
        cr_assert_eq(accel_occluded(acc, &r, 0, 1.001 * t), 1, "ray %d: the hit occludes", i);
    }
    cr_assert_gt(hits, 900, "many rays aimed at the box hit the cube: %d", hits);
    accel_destroy(acc);
    free_mesh(&m);
}

Test(accel_mesh, cube_hits_are_exact)
{
    check_cube(v3(1, 1, 1), v3(0, 1, 0), 0.0, v3(0, 0, 0));
}

Test(accel_mesh, cube_rigid_transform)
{
    check_cube(v3(2.5, 2.5, 2.5), v3(1, 2, 3), 40.0, v3(10, -3, 4));
}

Test(accel_mesh, cube_nonuniform_scale_transforms_normals)
{
    check_cube(v3(3, 0.25, 1), v3(-1, 0.5, 2), 109.0, v3(-2, 0, 1));
}

Test(accel_mesh, cube_mirrored_keeps_outward_normals)
{
    check_cube(v3(-1, 1, 2), v3(0, 0, 1), 23.0, v3(0, 1, 0));
}

/* The unit quad at z = 0 split along (0,0)-(1,1); vertex normals all differ. */
static const vec3 quad_n[4] = {{0, 0, 1}, {0.5, 0, 1}, {0.3, 0.4, 1}, {-0.2, 0.6, 1}};

static mesh_t quad_mesh(double z)
{
    mesh_t m = {.n_verts = 4, .n_tris = 2};
    m.pos = calloc(3 * 4 + 1, sizeof(float));
    m.nrm = calloc(3 * 4, sizeof(float));
    m.tri = calloc(6, sizeof(uint32_t));
    const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++) {
        vec3 n = v3_norm(quad_n[i]);
        m.pos[3 * i] = xy[i][0], m.pos[3 * i + 1] = xy[i][1], m.pos[3 * i + 2] = (float)z;
        m.nrm[3 * i] = (float)n.x, m.nrm[3 * i + 1] = (float)n.y, m.nrm[3 * i + 2] = (float)n.z;
    }
    const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
    memcpy(m.tri, t, sizeof t);
    return m;
}

Test(accel_mesh, shading_normals_interpolate_barycentrically)
{
    mesh_t m = quad_mesh(0);
    accel_t *acc = scene_with(&m, NULL);
    test_rng rng = {7};
    for (int i = 0; i < 500; i++) {
        double x = 0.1 + 0.8 * test_rng_uniform(&rng), y = 0.1 + 0.8 * test_rng_uniform(&rng);
        ray3 r = {v3(x, y, 2), v3(0.1 * (test_rng_uniform(&rng) - 0.5), 0, -1)};
        accel_hit h;
        cr_assert(accel_intersect(acc, &r, 0, INFINITY, &h), "ray %d", i);
        double px = h.p.x, py = h.p.y;
        cr_assert_float_eq(h.p.z, 0.0, 1e-15);
        /* Triangle 0 = (v0, v1, v2): p = u (v1 - v0) + v (v2 - v0) -> v = y, u = x - y.
         * Triangle 1 = (v0, v2, v3): u = x, v = y - x. */
        int tri = px >= py ? 0 : 1;
        cr_assert_eq(h.prim, (unsigned)tri, "ray %d at (%g, %g)", i, px, py);
        vec3 n = tri == 0 ? v3_add(v3_add(v3_scale(v3_norm(quad_n[0]), 1 - px), v3_scale(v3_norm(quad_n[1]), px - py)),
                                   v3_scale(v3_norm(quad_n[2]), py))
                          : v3_add(v3_add(v3_scale(v3_norm(quad_n[0]), 1 - py), v3_scale(v3_norm(quad_n[2]), px)),
                                   v3_scale(v3_norm(quad_n[3]), py - px));
        vec_near(h.ns, v3_norm(n), 1e-6, "shading normal", i);
        vec_near(h.ng, v3(0, 0, 1), 1e-15, "geometric normal", i);
        /* No uvs in this mesh: the barycentrics. */
        cr_assert_float_eq(h.uv.x, tri == 0 ? px - py : px, 1e-9);
        cr_assert_float_eq(h.uv.y, tri == 0 ? py : py - px, 1e-9);
    }
    accel_destroy(acc);
    free_mesh(&m);
}

Test(accel_mesh, nearest_of_two_geometries)
{
    mesh_t cube = cube_mesh(), front = quad_mesh(0), back = quad_mesh(0);
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    transform4 tf = transform_translate(v3(-0.5, -0.5, 2)), tb = transform_translate(v3(-0.5, -0.5, -2));
    cr_assert_eq(accel_add_mesh(acc, &cube, NULL, err, sizeof err), 0u, "%s", err);
    cr_assert_eq(accel_add_mesh(acc, &front, &tf, err, sizeof err), 1u, "%s", err);
    cr_assert_eq(accel_add_mesh(acc, &back, &tb, err, sizeof err), 2u, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    accel_hit h;
    ray3 down = {v3(0.1, 0.2, 5), v3(0, 0, -1)}, up = {v3(0.1, 0.2, -5), v3(0, 0, 1)};
    cr_assert(accel_intersect(acc, &down, 0, INFINITY, &h));
    cr_assert_eq(h.geom_id, 1u);
    cr_assert_float_eq(h.t, 3.0, 1e-15);
    cr_assert(accel_intersect(acc, &down, 3.5, INFINITY, &h));
    cr_assert_eq(h.geom_id, 0u, "past the front quad: the cube");
    cr_assert_float_eq(h.t, 4.5, 1e-15);
    cr_assert(accel_intersect(acc, &up, 0, INFINITY, &h));
    cr_assert_eq(h.geom_id, 2u);
    cr_assert_float_eq(h.t, 3.0, 1e-15);
    cr_assert_eq(accel_geometry_kind(acc, 1), ACCEL_KIND_MESH);
    cr_assert_eq(accel_geometry_triangles(acc, 0), 12);
    cr_assert_null(accel_geometry_sor(acc, 0));
    accel_destroy(acc);
    free_mesh(&cube), free_mesh(&front), free_mesh(&back);
}

Test(accel_mesh, empty_scene_misses)
{
    char err[256] = "";
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    cr_assert_eq(accel_commit(acc, err, sizeof err), 0, "%s", err);
    ray3 r = {v3(0, 0, 0), v3(1, 0, 0)};
    accel_hit h;
    cr_assert_eq(accel_intersect(acc, &r, 0, INFINITY, &h), 0);
    cr_assert_eq(accel_occluded(acc, &r, 0, INFINITY), 0);
    accel_destroy(acc);
}

Test(accel_mesh, rejects_bad_meshes_and_transforms)
{
    char err[256];
    accel_t *acc = accel_create(ACCEL_BUILD_FAST, err, sizeof err);
    cr_assert_not_null(acc, "%s", err);
    mesh_t m = cube_mesh();
    transform4 flat = transform_scale(v3(1, 0, 1));
    err[0] = 0;
    cr_assert_eq(accel_add_mesh(acc, &m, &flat, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "singular"), "%s", err);
    m.tri[5] = 24;
    err[0] = 0;
    cr_assert_eq(accel_add_mesh(acc, &m, NULL, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "vertex 24"), "%s", err);
    m.tri[5] = 3;
    m.pos[7] = NAN;
    err[0] = 0;
    cr_assert_eq(accel_add_mesh(acc, &m, NULL, err, sizeof err), ACCEL_INVALID_ID);
    cr_assert(strstr(err, "not finite"), "%s", err);
    m.pos[7] = 0.5f;
    mesh_t none = {0};
    cr_assert_eq(accel_add_mesh(acc, &none, NULL, err, sizeof err), ACCEL_INVALID_ID);
    /* Failed adds leave no trace: the next one still gets id 0. */
    cr_assert_eq(accel_add_mesh(acc, &m, NULL, err, sizeof err), 0u, "%s", err);
    accel_destroy(acc);
    free_mesh(&m);
}

/* float_up(x) is the least float >= x and float_down(x) the greatest <= x
 * (libm's nextafterf as the truth), across zeros, subnormals, both signs,
 * the ends of the float range and values that are floats already. */
Test(accel_mesh, float_bounds_enclose_the_double)
{
    const double fixed[] = {0.0, -0.0, 1e-50, -1e-50, 1e-40, -1e-40, 1.0, -1.0, 0.1, -0.1, 3.0e38, -3.0e38,
                            3.5e38, -3.5e38, 1e300, -1e300, (double)FLT_MAX, -(double)FLT_MAX};
    uint64_t z = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < 20000; k++) {
        double x;
        if (k < (int)(sizeof fixed / sizeof fixed[0])) {
            x = fixed[k];
        } else {
            z = z * 6364136223846793005ull + 1442695040888963407ull;
            x = ldexp((double)(z >> 11) * 0x1p-53 - 0.5, (int)(z % 280) - 150);
        }
        float f = (float)x, up = float_up(x), down = float_down(x);
        float want_up = (double)f < x ? nextafterf(f, INFINITY) : f, want_down = (double)f > x ? nextafterf(f, -INFINITY) : f;
        cr_assert(memcmp(&up, &want_up, sizeof up) == 0 && memcmp(&down, &want_down, sizeof down) == 0,
                  "x %a: up %a (want %a), down %a (want %a)", x, (double)up, (double)want_up, (double)down,
                  (double)want_down);
        cr_assert((double)up >= x && (double)down <= x, "x %a", x);
    }
}
