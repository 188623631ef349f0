/* Mitsuba's `rectangle`: [-1,1]^2 in the z = 0 plane, normal +z,
 * uv = ((x+1)/2, (y+1)/2), as a mesh of two triangles. While to_world keeps
 * it a rectangle (its edges orthogonal), it is sampled from a point
 * uniformly in the solid angle it subtends (spherical rectangles,
 * sampling.h), or uniformly in area where that is nearly as uniform in
 * solid angle and cheaper (area_is_as_good). */
#include "shapes/shape_impl.h"

/* Area sampling's density in solid angle, d^2 / (A cos) = d^3 / (A h) at
 * distance d from ref (h: ref's height over the plane), varies over the
 * rectangle by at most (d_max / d_min)^3. Where that is at most
 * AREA_RATIO_MAX the rectangle is sampled by area, uniformly in its own
 * coordinates, for a fraction of the spherical rectangle's cost (no
 * transcendental): the second moment of a constant integrand grows by at
 * most (R - 1)^2 / 4R, an eighth at R = 2. Measured at 16 spp (seed-pair
 * RMSE, docs/BENCHMARKS.md): cornell-sor's noise +0.05%, studio's +0.4%,
 * for 4-7% fewer instructions per sample. */
#define AREA_RATIO_MAX 2.0

/* x clamped to [0, 1], NaN to 0 (as fmin(1, fmax(0, x)), without their
 * calls into libm) */
static double clamp01(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; }

static bool area_is_as_good(const shape_t *sh, vec3 ref)
{
    const vec3 *f = sh->solid_angle_frame;
    vec3 d = v3_sub(ref, f[0]);
    double uu = v3_dot(f[1], f[1]), vv = v3_dot(f[2], f[2]);
    double s = v3_dot(d, f[1]) / uu, t = v3_dot(d, f[2]) / vv; /* ref's projection, in edge units */
    double hn = v3_dot(d, v3_cross(f[1], f[2])), h2 = hn * hn / (uu * vv);
    /* The nearest point (ref's projection clamped onto the rectangle) and
     * the farthest corner. */
    double ns = s - clamp01(s), nt = t - clamp01(t);
    double fs = s - (s < 0.5 ? 1.0 : 0.0), ft = t - (t < 0.5 ? 1.0 : 0.0);
    double near2 = h2 + uu * ns * ns + vv * nt * nt, far2 = h2 + uu * fs * fs + vv * ft * ft;
    double q = far2 / near2; /* (d_max / d_min)^2 */
    return near2 > 0.0 && q * q * q <= AREA_RATIO_MAX * AREA_RATIO_MAX;
}

/* The world rectangle (solid_angle_frame): corner (-1,-1) and the edges to
 * (1,-1) and (-1,1). 0 where the solid angle is too small for the
 * spherical formulas (area sampling then). */
static double rectangle_solid_angle(const shape_t *sh, vec3 ref, spherical_rect *r)
{
    const vec3 *f = sh->solid_angle_frame;
    double s = spherical_rect_init(r, ref, f[0], f[1], f[2]);
    return s >= SHAPE_MIN_SOLID_ANGLE ? s : 0.0;
}

/* The point of the mesh at rectangle coordinates (a, b) in [0,1]^2: in
 * triangle 0 (corners 0, 1, 2) when a >= b, else in triangle 1 (corners
 * 0, 2, 3), shape_mesh_square_face's order. */
static void rectangle_hit(const shape_t *sh, double a, double b, surface_hit *hit)
{
    if (a >= b)
        shape_mesh_point(sh, 0, a - b, b, hit);
    else
        shape_mesh_point(sh, 1, a, b - a, hit);
}

static double rectangle_sa_pdf(const shape_t *sh, vec3 ref)
{
    if (area_is_as_good(sh, ref))
        return 0.0;
    spherical_rect r;
    double s = rectangle_solid_angle(sh, ref, &r);
    return s > 0.0 ? 1.0 / s : 0.0;
}

/* By solid angle, or where area sampling is as good, uniformly in area
 * through the rectangle's own coordinates (which keeps u's 2D
 * stratification, where the mesh's sampler picks a triangle by another
 * number) with shape_pdf_from's density for it. */
static double rectangle_sa_sample(const shape_t *sh, vec3 ref, vec2 u, surface_hit *hit)
{
    if (area_is_as_good(sh, ref)) {
        rectangle_hit(sh, u.x, u.y, hit);
        vec3 d = v3_sub(hit->p, ref);
        double dist2 = v3_dot(d, d), cos_l = fabs(v3_dot(hit->ng, d));
        return dist2 > 0.0 && cos_l > 0.0 ? dist2 * sqrt(dist2) / (cos_l * sh->mesh.area) : 0.0;
    }
    spherical_rect r;
    double s = rectangle_solid_angle(sh, ref, &r);
    if (!(s > 0.0))
        return 0.0;
    vec3 eu = sh->solid_angle_frame[1], ev = sh->solid_angle_frame[2];
    vec3 d = v3_sub(spherical_rect_sample(&r, u), sh->solid_angle_frame[0]);
    rectangle_hit(sh, clamp01(v3_dot(d, eu) / v3_dot(eu, eu)), clamp01(v3_dot(d, ev) / v3_dot(ev, ev)), hit);
    return 1.0 / s;
}

static const shape_solid_angle_ops rectangle_spherical = {rectangle_sa_pdf, rectangle_sa_sample};

static int rectangle_create(scene_obj *o, const shape_options *opt, const transform4 *to_world, shape_t *sh,
                            char *err, size_t errlen)
{
    (void)opt;
    vec3 eu = transform_vector(to_world, v3(2.0, 0.0, 0.0)), ev = transform_vector(to_world, v3(0.0, 2.0, 0.0));
    if (fabs(v3_dot(eu, ev)) <= 1e-9 * v3_len(eu) * v3_len(ev)) {
        sh->solid_angle = &rectangle_spherical;
        sh->solid_angle_frame[0] = transform_point(to_world, v3(-1.0, -1.0, 0.0));
        sh->solid_angle_frame[1] = eu, sh->solid_angle_frame[2] = ev;
    }
    if (shape_mesh_alloc(&sh->mesh, 4, 2) != 0)
        return scene_obj_error(o, err, errlen, "<shape type=\"%s\">: out of memory", o->type);
    shape_mesh_square_face(&sh->mesh, 0, 0, 1, 2, 1.0);
    for (int v = 0; v < 4; v++) /* the rectangle lies in z = 0 */
        sh->mesh.pos[3 * v + 2] = 0.0f;
    return 0;
}

static const scene_param_decl rectangle_params[] = {SHAPE_PARAMS_COMMON, SHAPE_PARAMS_END};

const shape_plugin shape_rectangle = {
    .decl = {.cls = SCENE_SHAPE, .type = "rectangle", .params = rectangle_params, .children = shape_children},
    .create = rectangle_create,
};
