/* Mitsuba's `rectangle`: [-1,1]^2 in the z = 0 plane, normal +z,
 * uv = ((x+1)/2, (y+1)/2), as a mesh of two triangles. While to_world keeps
 * it a rectangle (its edges orthogonal), it is sampled from a point
 * uniformly in the solid angle it subtends: spherical rectangles
 * (sampling.h). */
#include "shapes/shape_impl.h"

/* The world rectangle (solid_angle_frame): corner (-1,-1) and the edges to
 * (1,-1) and (-1,1). */
static double rectangle_solid_angle(const shape_t *sh, vec3 ref, spherical_rect *r)
{
    const vec3 *f = sh->solid_angle_frame;
    double s = spherical_rect_init(r, ref, f[0], f[1], f[2]);
    return s >= SHAPE_MIN_SOLID_ANGLE ? s : 0.0;
}

static double rectangle_sa_pdf(const shape_t *sh, vec3 ref)
{
    spherical_rect r;
    double s = rectangle_solid_angle(sh, ref, &r);
    return s > 0.0 ? 1.0 / s : 0.0;
}

/* The sampled point as a hit of the mesh: at rectangle coordinates (a, b)
 * it lies in triangle 0 (corners 0, 1, 2) when a >= b, else in triangle 1
 * (corners 0, 2, 3), shape_mesh_square_face's order. */
static double rectangle_sa_sample(const shape_t *sh, vec3 ref, vec2 u, surface_hit *hit)
{
    spherical_rect r;
    double s = rectangle_solid_angle(sh, ref, &r);
    if (!(s > 0.0))
        return 0.0;
    vec3 eu = sh->solid_angle_frame[1], ev = sh->solid_angle_frame[2];
    vec3 d = v3_sub(spherical_rect_sample(&r, u), sh->solid_angle_frame[0]);
    double a = fmin(1.0, fmax(0.0, v3_dot(d, eu) / v3_dot(eu, eu)));
    double b = fmin(1.0, fmax(0.0, v3_dot(d, ev) / v3_dot(ev, ev)));
    if (a >= b)
        shape_mesh_finish(sh, 0, a - b, b, 0.0, hit);
    else
        shape_mesh_finish(sh, 1, a, b - a, 0.0, hit);
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
