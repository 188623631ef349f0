/* The `sdfgrid` shape against independent truth. Grids are sampled from
 * analytic distance fields (a plane, a sphere) and traced through a scene;
 * the reference is the grid's trilinear interpolant written here as nested
 * linear interpolation (the shape writes it as a polynomial per voxel),
 * searched for its first sign change along each ray by dense steps and
 * bisection. A plane's distance is linear, so the grid reproduces it
 * exactly; a sphere's is reproduced within the trilinear interpolation
 * error. Bad grid files are refused in one line. */
#include <math.h>

#include "celadon/rng.h"
#include "celadon/scene.h"
#include "support/cli_run.h"
#include "support/vol_file.h"
#include "test_render_util.h"

typedef double (*distance_fn)(vec3 p);

/* n^3 values of f at the points (i, j, k) / (n - 1), x fastest (malloc'd). */
static float *sample_grid(int n, distance_fn f)
{
    float *g = malloc(sizeof *g * (size_t)n * n * n);
    cr_assert_not_null(g);
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                g[((size_t)k * n + j) * n + i] = (float)f(v3((double)i / (n - 1), (double)j / (n - 1), (double)k / (n - 1)));
    return g;
}

/* The voxel of p (clamped into the grid) and p's place in it. */
static void locate(int n, vec3 p, int v[3], double q[3])
{
    const double c[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; a++) {
        double x = fmin(1.0, fmax(0.0, c[a])) * (n - 1);
        v[a] = (int)fmin(floor(x), n - 2);
        q[a] = x - v[a];
    }
}

static double at(const float *g, int n, int i, int j, int k) { return g[((size_t)k * n + j) * n + i]; }
static double lerp(double a, double b, double t) { return a + (b - a) * t; }

/* The trilinear interpolant at p: along x, then y, then z. */
static double ref_value(const float *g, int n, vec3 p)
{
    int v[3];
    double q[3];
    locate(n, p, v, q);
    double y0[2], z[2];
    for (int c = 0; c < 2; c++) {
        for (int b = 0; b < 2; b++)
            y0[b] = lerp(at(g, n, v[0], v[1] + b, v[2] + c), at(g, n, v[0] + 1, v[1] + b, v[2] + c), q[0]);
        z[c] = lerp(y0[0], y0[1], q[1]);
    }
    return lerp(z[0], z[1], q[2]);
}

/* Its gradient in p's voxel, per unit of the cube: along each axis the
 * difference of the two opposite faces' bilinear interpolants at p. */
static vec3 ref_gradient(const float *g, int n, vec3 p)
{
    int v[3];
    double q[3], d[3];
    locate(n, p, v, q);
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        double face[2];
        for (int s = 0; s < 2; s++) {
            double corner[2][2];
            for (int u = 0; u < 2; u++)
                for (int w = 0; w < 2; w++) {
                    int idx[3];
                    idx[a] = v[a] + s, idx[b] = v[b] + u, idx[c] = v[c] + w;
                    corner[u][w] = at(g, n, idx[0], idx[1], idx[2]);
                }
            face[s] = lerp(lerp(corner[0][0], corner[1][0], q[b]), lerp(corner[0][1], corner[1][1], q[b]), q[c]);
        }
        d[a] = (face[1] - face[0]) * (n - 1);
    }
    return v3(d[0], d[1], d[2]);
}

/* The first sign change of the interpolant along the cube-space ray o + t d
 * inside the cube, by steps of dt and 80 bisections: its t, or INFINITY. */
static double ref_first_root(const float *g, int n, vec3 o, vec3 d, double dt)
{
    const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    double t0 = 0.0, t1 = INFINITY;
    for (int a = 0; a < 3; a++) {
        if (dd[a] == 0.0) {
            if (oo[a] < 0.0 || oo[a] > 1.0)
                return INFINITY;
            continue;
        }
        double ta = -oo[a] / dd[a], tb = (1.0 - oo[a]) / dd[a];
        t0 = fmax(t0, fmin(ta, tb)), t1 = fmin(t1, fmax(ta, tb));
    }
    if (!(t0 < t1))
        return INFINITY;
    double a = t0, fa = ref_value(g, n, v3_add(o, v3_scale(d, a)));
    for (double b = fmin(t0 + dt, t1);; b = fmin(b + dt, t1)) {
        double fb = ref_value(g, n, v3_add(o, v3_scale(d, b)));
        if (fa == 0.0)
            return a;
        if ((fa < 0.0) != (fb < 0.0)) {
            for (int it = 0; it < 80; it++) {
                double m = 0.5 * (a + b), fm = ref_value(g, n, v3_add(o, v3_scale(d, m)));
                if ((fm < 0.0) == (fa < 0.0))
                    a = m, fa = fm;
                else
                    b = m;
            }
            return 0.5 * (a + b);
        }
        if (b >= t1)
            return INFINITY;
        a = b, fa = fb;
    }
}

/* ------------------------------------------------------------- scenes */

/* A scene of one sdfgrid of the grid g (n^3) with the given normals,
 * placed by the transform elements to_world. */
static scene_t *sdf_scene(render_fixture *f, const float *g, int n, const char *normals, const char *to_world)
{
    char path[300], xml[1024], err[1024];
    snprintf(path, sizeof path, "%s/g.vol", f->dir);
    vol_file_write(path, n, n, n, 1, g);
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><sensor type=\"perspective\"/><shape type=\"sdfgrid\"><string name=\"filename\" value=\"g.vol\"/>"
             "<string name=\"normals\" value=\"%s\"/><transform name=\"to_world\">%s</transform></shape></scene>",
             normals, to_world);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    scene_t *s = scene_create_from_file(path, NULL, 0, NULL, err, sizeof err);
    cr_assert_not_null(s, "%s", err);
    return s;
}

static vec3 random_unit(rng_t *r)
{
    double z = 2.0 * rng_next_double(r) - 1.0, phi = 2.0 * M_PI * rng_next_double(r), s = sqrt(1.0 - z * z);
    return v3(s * cos(phi), s * sin(phi), z);
}

/* ------------------------------------------------------------- the plane */

static const vec3 plane_n = {1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
static const double plane_c = 0.8;
static double plane_distance(vec3 p) { return v3_dot(plane_n, p) - plane_c; }

/* A plane's distance is linear: the interpolant is the plane itself, so
 * every ray meets it where the plane's equation says (to the float
 * rounding of the stored values), from either side, with the plane's
 * normal. */
Test(shape_sdfgrid, a_plane_distance_grid_is_the_exact_plane)
{
    render_fixture f;
    render_fixture_open(&f);
    float *g = sample_grid(9, plane_distance);
    scene_t *s = sdf_scene(&f, g, 9, "analytic", "");
    rng_t r;
    rng_seed(&r, 12, 0);
    int hits = 0;
    for (int k = 0; k < 400; k++) {
        /* a point of the plane well inside the cube, and a ray to it */
        vec3 q = v3(0.2 + 0.6 * rng_next_double(&r), 0.2 + 0.6 * rng_next_double(&r), 0.0);
        q.z = (plane_c - plane_n.x * q.x - plane_n.y * q.y) / plane_n.z;
        if (q.z < 0.1 || q.z > 0.9)
            continue;
        vec3 d = random_unit(&r);
        if (fabs(v3_dot(d, plane_n)) < 0.2)
            continue;
        double dist = 0.05 + 2.0 * rng_next_double(&r);
        ray3 ray = {v3_sub(q, v3_scale(d, dist)), d};
        scene_hit h;
        cr_assert(scene_first_hit(s, &ray, 0.0, INFINITY, &h), "ray %d missed the plane", k);
        cr_expect(fabs(h.t - dist) <= 1e-6 * dist, "ray %d: t = %.12g, the plane is at %.12g", k, h.t, dist);
        cr_expect(v3_len(v3_sub(h.n, plane_n)) < 1e-6, "ray %d: normal (%g, %g, %g)", k, h.n.x, h.n.y, h.n.z);
        hits++;
    }
    cr_assert_gt(hits, 100);
    scene_destroy(s);
    free(g);
    render_fixture_close(&f);
}

/* ------------------------------------------------------------ the sphere */

/* The sphere of radius 0.3 about the cube's centre, on a 17^3 grid (voxels
 * of h = 1/16), placed in the world by scale 2, translate -1: the world
 * sphere of radius 0.6 about the origin, and world = 2 cube - 1. */
enum { SPHERE_N = 17 };
static const double sphere_r = 0.3;
static double sphere_distance(vec3 p) { return v3_len(v3_sub(p, v3(0.5, 0.5, 0.5))) - sphere_r; }
static const char *sphere_place = "<scale value=\"2\"/><translate value=\"-1, -1, -1\"/>";

static vec3 to_cube(vec3 w) { return v3_scale(v3_add(w, v3(1.0, 1.0, 1.0)), 0.5); }

/* The bound of trilinear interpolation, (h^2 / 8) times the sum of the
 * second derivatives' largest sizes: each is at most 1 / rho for |p - c|
 * at distance rho from c, and within a voxel of the surface rho >= r -
 * sqrt(3) h. */
static double sphere_interpolation_bound(void)
{
    double h = 1.0 / (SPHERE_N - 1);
    return h * h / 8.0 * 3.0 / (sphere_r - sqrt(3.0) * h);
}

/* The sphere's grid and a scene of it with the given normals. */
typedef struct {
    render_fixture f;
    float *g;
    scene_t *s;
} sphere_fixture;

static void sphere_open(sphere_fixture *x, const char *normals)
{
    render_fixture_open(&x->f);
    x->g = sample_grid(SPHERE_N, sphere_distance);
    x->s = sdf_scene(&x->f, x->g, SPHERE_N, normals, sphere_place);
}

static void sphere_close(sphere_fixture *x)
{
    scene_destroy(x->s);
    free(x->g);
    render_fixture_close(&x->f);
}

/* A ray from a random point 3 away towards a random point of the ball of
 * radius 0.4 (inside the sphere's 0.6 by far more than the interpolation
 * error): it hits. */
static ray3 ray_into_sphere(rng_t *r)
{
    vec3 o = v3_scale(random_unit(r), 3.0), target = v3_scale(random_unit(r), 0.4 * cbrt(rng_next_double(r)));
    return (ray3){o, v3_norm(v3_sub(target, o))};
}

/* Every ray's hit agrees with the dense-step root of the interpolant to
 * 1e-6 relative (the cubic's root isolation and the voxel walk miss
 * nothing and find the first crossing), lies on the true sphere within the
 * interpolation error, and has the interpolant's gradient as its normal. */
Test(shape_sdfgrid, a_sphere_grid_hits_the_first_root_of_its_interpolant)
{
    sphere_fixture x;
    sphere_open(&x, "analytic");
    const float *g = x.g;
    rng_t r;
    rng_seed(&r, 7, 0);
    double worst_t = 0.0, worst_surface = 0.0, worst_n = 0.0;
    for (int k = 0; k < 300; k++) {
        ray3 ray = ray_into_sphere(&r);
        scene_hit h;
        cr_assert(scene_first_hit(x.s, &ray, 0.0, INFINITY, &h), "ray %d missed", k);
        /* the same ray in the cube's coordinates: t is kept */
        vec3 o = to_cube(ray.o), d = v3_scale(ray.d, 0.5);
        double t_ref = ref_first_root(g, SPHERE_N, o, d, 1e-3);
        cr_assert(isfinite(t_ref), "ray %d: the reference finds no root", k);
        worst_t = fmax(worst_t, fabs(h.t - t_ref) / t_ref);
        vec3 p = v3_add(o, v3_scale(d, h.t));
        worst_surface = fmax(worst_surface, fabs(sphere_distance(p)));
        vec3 n_ref = v3_norm(ref_gradient(g, SPHERE_N, p)); /* a uniform scale keeps directions */
        worst_n = fmax(worst_n, v3_len(v3_sub(h.n, n_ref)));
    }
    cr_expect_lt(worst_t, 1e-6, "t differs from the reference root by %g relative", worst_t);
    cr_expect_lt(worst_surface, sphere_interpolation_bound(), "a hit lies %g from the sphere (bound %g)", worst_surface,
                 sphere_interpolation_bound());
    cr_expect_lt(worst_n, 1e-9, "a normal differs from the interpolant's gradient by %g", worst_n);
    sphere_close(&x);
}

/* Rays that pass the sphere farther than the interpolation error, or leave
 * the cube, meet nothing; a ray along the grid's planes (x = y = 1/2 in the
 * cube: every voxel crossing a face and an edge at once) meets the top of
 * the sphere, where the interpolant is exact along that line. */
Test(shape_sdfgrid, rays_that_miss_miss_and_a_ray_along_grid_planes_hits)
{
    sphere_fixture x;
    sphere_open(&x, "analytic");
    rng_t r;
    rng_seed(&r, 9, 0);
    double clear = 2.0 * (0.3 + sphere_interpolation_bound()) + 0.01; /* world */
    for (int k = 0; k < 300; k++) {
        vec3 o = v3_scale(random_unit(&r), 3.0), side = v3_norm(v3_cross(o, random_unit(&r)));
        /* passing the centre at `clear` to 1.5 (the cube's corners are at sqrt(3)) */
        vec3 target = v3_scale(side, clear + (1.5 - clear) * rng_next_double(&r));
        ray3 ray = {o, v3_norm(v3_sub(target, o))};
        scene_hit h;
        cr_expect(!scene_first_hit(x.s, &ray, 0.0, INFINITY, &h), "ray %d passing at %g hit at t = %g", k,
                  v3_len(target), h.t);
        ray3 away = {o, v3_norm(o)};
        cr_expect(!scene_first_hit(x.s, &away, 0.0, INFINITY, &h), "ray %d leaving the cube hit", k);
    }
    ray3 down = {v3(0.0, 0.0, 3.0), v3(0.0, 0.0, -1.0)};
    scene_hit h;
    cr_assert(scene_first_hit(x.s, &down, 0.0, INFINITY, &h));
    cr_expect(fabs(h.t - 2.4) < 1e-6, "the top of the sphere at t = %.12g, not 2.4", h.t);
    /* and from inside, the way out: the bottom of the sphere */
    ray3 out = {v3(0.0, 0.0, 0.0), v3(0.0, 0.0, -1.0)};
    cr_assert(scene_first_hit(x.s, &out, 0.0, INFINITY, &h));
    cr_expect(fabs(h.t - 0.6) < 1e-6, "the bottom of the sphere from inside at t = %.12g, not 0.6", h.t);
    sphere_close(&x);
}

/* The largest change of the normal between neighbouring rays of a fine
 * scan across the sphere (steps of 1/500 voxel), and the largest angle to
 * the true sphere's normal. */
static void normal_scan(scene_t *s, double *jump, double *off)
{
    *jump = *off = 0.0;
    vec3 prev = v3(0.0, 0.0, 0.0);
    for (int k = 0; k <= 4000; k++) {
        double x = -0.4 + 0.8 * k / 4000.0;
        ray3 ray = {v3(x, 0.13, 3.0), v3(0.0, 0.0, -1.0)};
        scene_hit h;
        cr_assert(scene_first_hit(s, &ray, 0.0, INFINITY, &h));
        vec3 p = v3_add(ray.o, v3_scale(ray.d, h.t));
        *off = fmax(*off, acos(fmin(1.0, v3_dot(h.n, v3_norm(p)))));
        if (k > 0)
            *jump = fmax(*jump, v3_len(v3_sub(h.n, prev)));
        prev = h.n;
    }
}

/* Smooth normals (Mitsuba's default) follow the sphere and are continuous
 * across voxels; the analytic ones (the interpolant's gradient) jump at
 * voxel faces, where the trilinear interpolant has a kink. */
Test(shape_sdfgrid, smooth_normals_are_continuous_where_the_gradient_jumps)
{
    double jump[2], off[2];
    const char *modes[2] = {"analytic", "smooth"};
    for (int m = 0; m < 2; m++) {
        sphere_fixture x;
        sphere_open(&x, modes[m]);
        normal_scan(x.s, &jump[m], &off[m]);
        sphere_close(&x);
    }
    /* a step of 1/500 voxel turns a continuous normal of curvature 1/0.6 by
     * about 2e-4 / 0.6 */
    cr_expect_lt(jump[1], 2e-3, "smooth normals jump by %g between neighbouring rays", jump[1]);
    cr_expect_gt(jump[0], 10.0 * jump[1], "analytic normals jump by only %g (smooth: %g)", jump[0], jump[1]);
    /* the gradient of an interpolant is good to O(h |Hessian|): h / (r -
     * sqrt(3) h) = 0.33 here (measured 0.135); blending the voxels' normals
     * cancels most of that (measured 0.007) */
    cr_expect_lt(off[0], 0.33, "analytic normals stray %g rad from the sphere's", off[0]);
    cr_expect_lt(off[1], 0.02, "smooth normals stray %g rad from the sphere's", off[1]);
}

/* -------------------------------------------------------------- bad files */

/* Renders a scene of an sdfgrid of the file g.vol (bytes, len) plus the
 * shape's extra elements; its exit status and stderr in err. */
static int render_grid_file(render_fixture *f, const void *bytes, size_t len, const char *extra, char *err,
                            size_t errlen)
{
    char path[300], xml[1024], out[300];
    snprintf(path, sizeof path, "%s/g.vol", f->dir);
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(bytes, 1, len, fp), len);
    fclose(fp);
    snprintf(xml, sizeof xml,
             "<scene version=\"3.0.0\"><sensor type=\"perspective\"/><shape type=\"sdfgrid\"><string name=\"filename\" value=\"g.vol\"/>%s</shape>"
             "</scene>",
             extra);
    render_write_file(f, "scene.xml", xml, path, sizeof path);
    snprintf(out, sizeof out, "%s/out.exr", f->dir);
    const char *args[] = {"render", path, "-o", out, "--res", "8x6", "--spp", "1", NULL};
    cli_result r = cli_run(f->dir, args);
    snprintf(err, errlen, "%s", r.err);
    int status = r.status;
    cli_result_free(&r);
    cr_expect(access(out, F_OK) != 0, "a refused scene left %s", out);
    return status;
}

Test(shape_sdfgrid, bad_grid_files_are_refused_in_one_line)
{
    render_fixture f;
    render_fixture_open(&f);
    enum { N = 4 };
    float grid[N * N * N * 3];
    for (int i = 0; i < N * N * N * 3; i++)
        grid[i] = (float)(i % 7) - 3.0f;
    unsigned char buf[48 + sizeof grid];
    struct {
        const char *what, *expect;
        int nx, channels;
        float poison;   /* a value put in the middle, or 0 */
        int cut;        /* bytes cut off the end */
        float constant; /* all values this when nonzero */
    } cases[] = {
        {"three channels", "1 channel, not 3", N, 3, 0, 0, 0},
        {"one point across", "at least 2 values along each axis", 1, 1, 0, 0, 0},
        {"a NaN", "must be finite", N, 1, NAN, 0, 0},
        {"a short file", "bytes of values", N, 1, 0, 5, 0},
        {"no surface", "no surface", N, 1, 0, 0, 2.0f},
    };
    char err[4096];
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        float values[N * N * N * 3];
        memcpy(values, grid, sizeof values);
        if (cases[k].poison != 0 || isnan(cases[k].poison))
            values[N * N + 1] = cases[k].poison;
        for (int i = 0; cases[k].constant != 0 && i < N * N * N; i++)
            values[i] = cases[k].constant;
        size_t len = vol_file_bytes(buf, cases[k].nx, N, N, cases[k].channels, values) - (size_t)cases[k].cut;
        int status = render_grid_file(&f, buf, len, "", err, sizeof err);
        cr_expect_eq(status, 2, "%s: exit %d (%s)", cases[k].what, status, err);
        cr_expect_eq(cli_count_lines(err), 1, "%s: not one line: %s", cases[k].what, err);
        cr_expect(strstr(err, "g.vol") && strstr(err, cases[k].expect), "%s: %s", cases[k].what, err);
    }
    int status = render_grid_file(&f, "not a grid at all, just some text that is long enough to be read", 64, "", err,
                                  sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1 && strstr(err, "not a Mitsuba .vol file"), "%d: %s", status, err);
    size_t len = vol_file_bytes(buf, N, N, N, 1, grid);
    status = render_grid_file(&f, buf, len, "<emitter type=\"area\"/>", err, sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1 && strstr(err, "cannot emit"), "%d: %s", status, err);
    status = render_grid_file(&f, buf, len, "<string name=\"normals\" value=\"flat\"/>", err, sizeof err);
    cr_expect(status == 2 && cli_count_lines(err) == 1 && strstr(err, "normals"), "%d: %s", status, err);
    render_fixture_close(&f);
}
