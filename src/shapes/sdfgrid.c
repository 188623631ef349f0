/* Mitsuba's `sdfgrid`: a signed distance field sampled on a regular grid
 * over the object-space unit cube [0,1]^3, read from a one-channel .vol
 * file (`filename`), trilinearly interpolated; the surface is its zero
 * level set, the outside where the distance is positive.
 *
 * Grid: nx x ny x nz values at the points (i / (nx-1), j / (ny-1),
 * k / (nz-1)), x fastest (Mitsuba's convention: the values sit on the
 * voxels' corners, so (nx-1)(ny-1)(nz-1) voxels fill the cube). Grid
 * coordinates g = p * (n-1) put the voxel (i, j, k) at [i, i+1] x ...
 *
 * Intersection, exact up to rounding: the trilinear interpolant of a voxel
 * along a ray is a cubic in t; its first root in the voxel's t-interval is
 * isolated by the cubic's critical points (celadon/polynomial.h). Voxels
 * whose eight corners share one strict sign hold no surface (the
 * interpolant is a convex combination of the corners) and are skipped.
 * The others are grouped in bricks of BRICK^3 voxels, one Embree user
 * primitive each (boxed by its surface voxels); inside a brick a 3D DDA
 * walks the ray's voxels front to back, so the first root found is the
 * brick's nearest.
 *
 * Normals: the geometric normal is the gradient of the voxel's trilinear
 * interpolant at the hit. The shading normal is that same gradient with
 * `normals` = "analytic", and with "smooth" (Mitsuba's default) the normals
 * of the eight voxels around the nearest grid point, each the gradient
 * across that voxel, blended trilinearly between the voxels' centres
 * (Hansson-Söderlund, Evans and Akenine-Möller, "Ray Tracing of Signed
 * Distance Function Grids", JCGT 11(3), 2022), continuous across voxels.
 * No texture coordinates (uv = 0, dp/du = dp/dv = 0) and no area emitter,
 * as in Mitsuba. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/polynomial.h"
#include "shapes/shape_impl.h"
#include "volumes/volumes.h"

enum { BRICK = 8 }; /* voxels along each side of a brick */

typedef struct {
    int lo[3], hi[3]; /* the brick's surface voxels' box, in voxels: [lo, hi) */
} sdf_brick;

typedef struct {
    float *values;           /* the grid's values, x fastest */
    int n[3];                /* grid points along each axis, >= 2 */
    int res[3];              /* voxels along each axis, n - 1 */
    unsigned char *surface;  /* per voxel: its corners are not all > 0 nor all < 0 */
    sdf_brick *bricks;       /* the bricks that hold a surface voxel: the primitives */
    unsigned n_bricks;
    bool smooth;             /* smooth shading normals */
} sdfgrid_data;

static size_t point_index(const sdfgrid_data *d, int i, int j, int k)
{
    return ((size_t)k * (size_t)d->n[1] + (size_t)j) * (size_t)d->n[0] + (size_t)i;
}

static size_t voxel_index(const sdfgrid_data *d, const int v[3])
{
    return ((size_t)v[2] * (size_t)d->res[1] + (size_t)v[1]) * (size_t)d->res[0] + (size_t)v[0];
}

/* The voxel v's interpolant as f(x,y,z) = k0 + k1 x + k2 y + k3 z + k4 xy +
 * k5 xz + k6 yz + k7 xyz in its local coordinates [0,1]^3. */
static void voxel_coeffs(const sdfgrid_data *d, const int v[3], double k[8])
{
    double s[8]; /* s[a + 2b + 4c]: the corner (a, b, c) */
    for (int c = 0; c < 8; c++)
        s[c] = d->values[point_index(d, v[0] + (c & 1), v[1] + (c >> 1 & 1), v[2] + (c >> 2))];
    k[0] = s[0];
    k[1] = s[1] - s[0];
    k[2] = s[2] - s[0];
    k[3] = s[4] - s[0];
    k[4] = s[3] - s[1] - s[2] + s[0];
    k[5] = s[5] - s[1] - s[4] + s[0];
    k[6] = s[6] - s[2] - s[4] + s[0];
    k[7] = s[7] - s[3] - s[5] - s[6] + s[1] + s[2] + s[4] - s[0];
}

static double voxel_value(const double k[8], vec3 q)
{
    return k[0] + k[1] * q.x + k[2] * q.y + k[3] * q.z + k[4] * q.x * q.y + k[5] * q.x * q.z + k[6] * q.y * q.z +
           k[7] * q.x * q.y * q.z;
}

/* The gradient of the voxel's interpolant at local q, per unit of object space. */
static vec3 voxel_gradient(const sdfgrid_data *d, const double k[8], vec3 q)
{
    return v3((k[1] + k[4] * q.y + k[5] * q.z + k[7] * q.y * q.z) * d->res[0],
              (k[2] + k[4] * q.x + k[6] * q.z + k[7] * q.x * q.z) * d->res[1],
              (k[3] + k[5] * q.x + k[6] * q.y + k[7] * q.x * q.y) * d->res[2]);
}

/* The first root in (tmin, tmax) of voxel v's interpolant along the grid
 * ray g + t dg, between the voxel's entry ta and exit tb (ta < tb): 1 and
 * *t, or 0. The cubic is written about the entry point, inside the voxel,
 * so its coefficients stay of the size of the values. */
static int voxel_root(const sdfgrid_data *d, const int v[3], vec3 g, vec3 dg, double ta, double tb, double tmin,
                      double tmax, double *t)
{
    double k[8];
    voxel_coeffs(d, v, k);
    vec3 o = v3(g.x + dg.x * ta - v[0], g.y + dg.y * ta - v[1], g.z + dg.z * ta - v[2]), e = dg;
    double c[4];
    c[0] = voxel_value(k, o);
    c[1] = e.x * (k[1] + k[4] * o.y + k[5] * o.z + k[7] * o.y * o.z) +
           e.y * (k[2] + k[4] * o.x + k[6] * o.z + k[7] * o.x * o.z) +
           e.z * (k[3] + k[5] * o.x + k[6] * o.y + k[7] * o.x * o.y);
    c[2] = k[4] * e.x * e.y + k[5] * e.x * e.z + k[6] * e.y * e.z +
           k[7] * (e.x * e.y * o.z + e.x * o.y * e.z + o.x * e.y * e.z);
    c[3] = k[7] * e.x * e.y * e.z;
    double s;
    if (!poly_cubic_first_root(c, 0.0, tb - ta, tmin - ta, &s) || !(ta + s < tmax))
        return 0;
    *t = ta + s;
    return 1;
}

/* The t-interval of the grid ray inside the box [lo, hi] of grid
 * coordinates: 0 when it misses. */
static int box_span(const int lo[3], const int hi[3], vec3 g, vec3 dg, double *t0, double *t1)
{
    const double o[3] = {g.x, g.y, g.z}, dir[3] = {dg.x, dg.y, dg.z};
    *t0 = -INFINITY, *t1 = INFINITY;
    for (int a = 0; a < 3; a++) {
        if (dir[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a])
                return 0;
            continue;
        }
        double ta = (lo[a] - o[a]) / dir[a], tb = (hi[a] - o[a]) / dir[a];
        *t0 = fmax(*t0, fmin(ta, tb));
        *t1 = fmin(*t1, fmax(ta, tb));
    }
    return *t0 <= *t1;
}

/* Walks the voxels of box b along the grid ray from its entry, front to
 * back (Amanatides and Woo's DDA), and solves in each surface voxel: the
 * first root in (tmin, tmax), its voxel in v. Each voxel's interval starts
 * where the previous one ended, so the intervals cover the ray's span in
 * the box without a gap, whatever the rounding of the crossings. */
static int brick_root(const sdfgrid_data *d, const sdf_brick *b, vec3 g, vec3 dg, double tmin, double tmax, double *t,
                      int v[3])
{
    double t0, t1;
    if (!box_span(b->lo, b->hi, g, dg, &t0, &t1))
        return 0;
    double cur = fmax(t0, tmin), end = fmin(t1, tmax);
    if (!(cur <= end))
        return 0;
    const double o[3] = {g.x, g.y, g.z}, dir[3] = {dg.x, dg.y, dg.z};
    int step[3], steps = 0;
    for (int a = 0; a < 3; a++) {
        double i = floor(o[a] + dir[a] * cur); /* in the box up to rounding */
        v[a] = i < b->lo[a] ? b->lo[a] : i >= b->hi[a] ? b->hi[a] - 1 : (int)i;
        step[a] = dir[a] > 0.0 ? 1 : dir[a] < 0.0 ? -1 : 0;
        steps += b->hi[a] - b->lo[a];
    }
    for (int it = 0; it <= steps; it++) {
        double exit[3];
        int next = 0;
        for (int a = 0; a < 3; a++) {
            exit[a] = step[a] == 0 ? INFINITY : (v[a] + (step[a] > 0) - o[a]) / dir[a];
            if (exit[a] < exit[next])
                next = a;
        }
        double out = fmin(exit[next], end);
        if (out > cur && d->surface[voxel_index(d, v)] && voxel_root(d, v, g, dg, cur, out, tmin, tmax, t))
            return 1;
        if (out >= end)
            return 0;
        cur = fmax(cur, out);
        v[next] += step[next];
        if (v[next] < b->lo[next] || v[next] >= b->hi[next])
            return 0;
    }
    return 0;
}

static void sdf_brick_bounds(const void *data, unsigned prim, vec3 *lo, vec3 *hi)
{
    const sdfgrid_data *d = data;
    const sdf_brick *b = &d->bricks[prim];
    *lo = v3((double)b->lo[0] / d->res[0], (double)b->lo[1] / d->res[1], (double)b->lo[2] / d->res[2]);
    *hi = v3((double)b->hi[0] / d->res[0], (double)b->hi[1] / d->res[1], (double)b->hi[2] / d->res[2]);
}

static int sdf_brick_intersect(const void *data, unsigned prim, const ray3 *r, double tmin, double tmax,
                               accel_user_hit *h)
{
    const sdfgrid_data *d = data;
    vec3 g = v3(r->o.x * d->res[0], r->o.y * d->res[1], r->o.z * d->res[2]);
    vec3 dg = v3(r->d.x * d->res[0], r->d.y * d->res[1], r->d.z * d->res[2]);
    double t;
    int v[3];
    if (!brick_root(d, &d->bricks[prim], g, dg, tmin, tmax, &t, v))
        return 0;
    double k[8];
    voxel_coeffs(d, v, k);
    vec3 q = v3(fmin(1.0, fmax(0.0, g.x + dg.x * t - v[0])), fmin(1.0, fmax(0.0, g.y + dg.y * t - v[1])),
                fmin(1.0, fmax(0.0, g.z + dg.z * t - v[2])));
    vec3 n = v3_norm(voxel_gradient(d, k, q));
    /* a zero gradient (a voxel where the distance is zero throughout) has
     * no normal: face the ray */
    h->n = v3_len(n) > 0.0 ? n : v3_norm(v3_neg(r->d));
    h->t = t;
    h->p = v3_add(r->o, v3_scale(r->d, t));
    h->uv = v2(0.0, 0.0);
    h->param[0] = h->param[1] = 0.0;
    return 1;
}

static const accel_user_ops sdf_accel_ops = {sdf_brick_bounds, sdf_brick_intersect};

static unsigned sdfgrid_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    const sdfgrid_data *d = data;
    return accel_add_user(acc, &sdf_accel_ops, d, d->n_bricks, to_world, err, errlen);
}

/* The interpolant of the whole grid at object point p, clamped to the cube
 * (Mitsuba's clamped texture lookup). */
static double grid_value(const sdfgrid_data *d, vec3 p)
{
    const double c[3] = {p.x, p.y, p.z};
    int v[3];
    double q[3];
    for (int a = 0; a < 3; a++) {
        double x = fmin(1.0, fmax(0.0, c[a])) * d->res[a];
        v[a] = (int)fmin(floor(x), d->res[a] - 1);
        q[a] = x - v[a];
    }
    double k[8];
    voxel_coeffs(d, v, k);
    return voxel_value(k, v3(q[0], q[1], q[2]));
}

/* The normal of voxel v at p for the smooth normals: along each axis the
 * difference of the grid's interpolant across v's extent on that axis, at
 * p's other two coordinates (Mitsuba's voxel_grad), normalised. */
static vec3 voxel_normal_at(const sdfgrid_data *d, const int v[3], vec3 p)
{
    double grad[3];
    for (int a = 0; a < 3; a++) {
        double c0[3] = {p.x, p.y, p.z}, c1[3] = {p.x, p.y, p.z};
        c0[a] = (double)v[a] / d->res[a];
        c1[a] = (double)(v[a] + 1) / d->res[a];
        grad[a] = (grid_value(d, v3(c1[0], c1[1], c1[2])) - grid_value(d, v3(c0[0], c0[1], c0[2]))) * d->res[a];
    }
    return v3_norm(v3(grad[0], grad[1], grad[2]));
}

/* The smooth shading normal at object point p: the eight voxels around the
 * grid point nearest to p, their normals weighted trilinearly by p's
 * position between their centres. A voxel outside the grid counts with
 * weight 0, and along an axis where the voxels of one side are all
 * outside, the other side takes the whole weight. */
static vec3 smooth_normal(const sdfgrid_data *d, vec3 p)
{
    const double c[3] = {p.x, p.y, p.z};
    int base[3];
    double w[3];
    bool side_out[3][2] = {{false}};
    for (int a = 0; a < 3; a++) {
        double x = c[a] * d->res[a], r = round(x);
        base[a] = (int)r - 1;
        w[a] = x - r + 0.5; /* weight of the upper voxel along a */
        side_out[a][0] = base[a] < 0 || base[a] >= d->res[a];
        side_out[a][1] = base[a] + 1 < 0 || base[a] + 1 >= d->res[a];
        if (side_out[a][0])
            w[a] = 1.0;
        if (side_out[a][1])
            w[a] = 0.0;
    }
    vec3 n = v3(0.0, 0.0, 0.0);
    for (int corner = 0; corner < 8; corner++) {
        const int s[3] = {corner & 1, corner >> 1 & 1, corner >> 2};
        if (side_out[0][s[0]] || side_out[1][s[1]] || side_out[2][s[2]])
            continue;
        const int v[3] = {base[0] + s[0], base[1] + s[1], base[2] + s[2]};
        double weight = 1.0;
        for (int a = 0; a < 3; a++)
            weight *= s[a] ? w[a] : 1.0 - w[a];
        n = v3_add(n, v3_scale(voxel_normal_at(d, v, p), weight));
    }
    return v3_norm(n);
}

static vec3 sdfgrid_shading_normal(const void *data, const shape_local_hit *h)
{
    const sdfgrid_data *d = data;
    vec3 n = d->smooth ? smooth_normal(d, h->p) : h->n;
    return v3_len(n) > 0.0 ? n : h->n;
}

/* No uv parametrisation, as in Mitsuba: zero derivatives. */
static void sdfgrid_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    (void)data, (void)h;
    *dpdu = *dpdv = v3(0.0, 0.0, 0.0);
}

static void sdfgrid_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    (void)data;
    *lo = v3(0.0, 0.0, 0.0), *hi = v3(1.0, 1.0, 1.0);
}

static void sdfgrid_destroy(void *data)
{
    sdfgrid_data *d = data;
    if (!d)
        return;
    free(d->values);
    free(d->surface);
    free(d->bricks);
    free(d);
}

/* An SDF grid never emits (sdfgrid_create refuses an area emitter), so it
 * is never sampled by area. */
static const shape_analytic_ops sdfgrid_ops = {
    .add = sdfgrid_add,
    .local_hit = shape_analytic_local_hit,
    .destroy = sdfgrid_destroy,
    .tangents = sdfgrid_tangents,
    .bounds = sdfgrid_bounds,
    .shading_normal = sdfgrid_shading_normal,
};

/* Marks the surface voxels and boxes each brick's: 0, or -1 when memory
 * runs out. */
static int find_surface(sdfgrid_data *d)
{
    size_t voxels = (size_t)d->res[0] * (size_t)d->res[1] * (size_t)d->res[2];
    int nb[3];
    for (int a = 0; a < 3; a++)
        nb[a] = (d->res[a] + BRICK - 1) / BRICK;
    size_t max_bricks = (size_t)nb[0] * (size_t)nb[1] * (size_t)nb[2];
    if (!(d->surface = calloc(voxels, 1)) || !(d->bricks = malloc(max_bricks * sizeof *d->bricks)))
        return -1;
    for (int bz = 0; bz < nb[2]; bz++)
        for (int by = 0; by < nb[1]; by++)
            for (int bx = 0; bx < nb[0]; bx++) {
                const int first[3] = {bx * BRICK, by * BRICK, bz * BRICK};
                sdf_brick b = {{INT_MAX, INT_MAX, INT_MAX}, {0, 0, 0}};
                int v[3];
                for (v[2] = first[2]; v[2] < first[2] + BRICK && v[2] < d->res[2]; v[2]++)
                    for (v[1] = first[1]; v[1] < first[1] + BRICK && v[1] < d->res[1]; v[1]++)
                        for (v[0] = first[0]; v[0] < first[0] + BRICK && v[0] < d->res[0]; v[0]++) {
                            float lo = INFINITY, hi = -INFINITY;
                            for (int c = 0; c < 8; c++) {
                                float s = d->values[point_index(d, v[0] + (c & 1), v[1] + (c >> 1 & 1), v[2] + (c >> 2))];
                                lo = fminf(lo, s), hi = fmaxf(hi, s);
                            }
                            if (!(lo <= 0.0f && hi >= 0.0f))
                                continue;
                            d->surface[voxel_index(d, v)] = 1;
                            for (int a = 0; a < 3; a++)
                                b.lo[a] = v[a] < b.lo[a] ? v[a] : b.lo[a], b.hi[a] = v[a] + 1 > b.hi[a] ? v[a] + 1 : b.hi[a];
                        }
                if (b.hi[0] > 0)
                    d->bricks[d->n_bricks++] = b;
            }
    return 0;
}

static int sdfgrid_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh, char *err,
                          size_t errlen)
{
    (void)opt;
    if (scene_obj_child(o, SCENE_EMITTER))
        return scene_obj_error(o, err, errlen, "an SDF grid cannot emit light (as in Mitsuba: it has no area to sample)");
    const char *path = scene_obj_string(o, "filename", "");
    sdfgrid_data *d = calloc(1, sizeof *d);
    if (!d)
        return scene_obj_error(o, err, errlen, "out of memory");
    d->smooth = strcmp(scene_obj_string(o, "normals", "smooth"), "smooth") == 0;
    sh->is_mesh = false;
    sh->ops = &sdfgrid_ops;
    sh->data = d; /* shape_create frees it on failure */
    sh->to_world = *to_world;
    char why[256];
    vol_grid g;
    if (vol_grid_read(path, &g, why, sizeof why) != 0)
        return scene_obj_error(o, err, errlen, "%s: %s", path, why);
    d->values = g.values;
    d->n[0] = g.nx, d->n[1] = g.ny, d->n[2] = g.nz;
    if (g.channels != 1)
        return scene_obj_error(o, err, errlen, "%s: an SDF grid has 1 channel, not %d", path, g.channels);
    if (g.nx < 2 || g.ny < 2 || g.nz < 2)
        return scene_obj_error(o, err, errlen, "%s: an SDF grid needs at least 2 values along each axis, not %dx%dx%d",
                               path, g.nx, g.ny, g.nz);
    for (int a = 0; a < 3; a++)
        d->res[a] = d->n[a] - 1;
    if (find_surface(d) != 0)
        return scene_obj_error(o, err, errlen, "%s: out of memory", path);
    if (d->n_bricks == 0)
        return scene_obj_error(o, err, errlen, "%s: no voxel of the grid holds a zero of the distance (no surface)",
                               path);
    return 0;
}

static const scene_param_decl sdfgrid_params[] = {
    SHAPE_PARAMS_COMMON,
    {"filename", PARAM_STRING, PARAM_REQUIRED | PARAM_FILE, NULL},
    {"normals", PARAM_STRING, 0, "smooth|analytic"},
    SHAPE_PARAMS_END,
};

const shape_plugin shape_sdfgrid = {
    .decl = {.cls = SCENE_SHAPE, .type = "sdfgrid", .params = sdfgrid_params, .children = shape_children},
    .create = sdfgrid_create,
};
