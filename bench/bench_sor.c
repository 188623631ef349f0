/* Ray–SOR intersection speed: the analytic intersector (direct, and as an
 * Embree user geometry), Embree on the revolved mesh at 90, 360 and 1440
 * angular segments, and the naive reference, on every test profile, for
 * incoherent rays (random origins on a sphere around the object aimed at
 * random points in its bounds) and coherent rays (a pinhole camera), on one
 * thread and on all cores. Also the geometric error of each mesh: the largest
 * distance of its hit points from the exact surface, next to the sagitta
 * estimate 4.9 r/N^2.
 *
 * Usage: bench_sor              the whole table; the last line is the ratio
 *        bench_sor --only METHOD PROFILE SECONDS
 *                               one method (direct, embree-user, naive, mesh:N,
 *                               raw:N)
 *                               on PROFILE's incoherent rays, one thread, for a
 *                               profiler */
#include <omp.h>
#include <pmmintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <embree3/rtcore.h>

#include "celadon/accel.h"
#include "celadon/curve_domains.h"
#include "core/core.h"
#include "support/sor_profiles.h"

#define HEIGHT 1.0
#define N_INCOHERENT 50000
#define CAMERA_SIDE 224          /* coherent rays: CAMERA_SIDE^2 */
#define TARGET_RINGS 300         /* curvature domains per profile, like the paper's meshes */
#define MIN_PASSES 3             /* each timing is the fastest of at least this many passes */
#define MIN_SECONDS 0.3          /* and of as many as fit in this time */
#define RECON_NAME "recon"

static const int SEGMENTS[] = {90, 360, 1440};
enum { N_SEGMENTS = 3 };

typedef enum { M_DIRECT, M_EMBREE_USER, M_MESH, M_RAW, M_NAIVE } method_kind;

typedef struct {
    method_kind kind;
    const sor_t *sor;
    accel_t *acc;
    RTCScene raw;
} method;

/* Embree at its barest, the baseline most favourable to it: the same
 * triangles in a scene of their own, rtcIntersect1 on the float ray, t only
 * (no double refinement, no normals or uv). */
static int trace_raw(RTCScene scene, const ray3 *r, double *t)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh = {.ray = {.org_x = (float)r->o.x, .org_y = (float)r->o.y, .org_z = (float)r->o.z,
                                   .dir_x = (float)r->d.x, .dir_y = (float)r->d.y, .dir_z = (float)r->d.z,
                                   .tnear = 0.0f, .tfar = INFINITY, .mask = 0xffffffffu},
                           .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
    rtcIntersect1(scene, &ctx, &rh);
    *t = rh.ray.tfar;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

static int trace(const method *m, const ray3 *r, double *t)
{
    sor_hit sh;
    accel_hit ah;
    int hit;
    switch (m->kind) {
    case M_DIRECT:
        hit = sor_intersect(m->sor, r, 0, INFINITY, &sh);
        *t = sh.t;
        return hit;
    case M_RAW:
        return trace_raw(m->raw, r, t);
    case M_NAIVE:
        hit = sor_intersect_naive(m->sor, r, 0, INFINITY, &sh);
        *t = sh.t;
        return hit;
    default:
        hit = accel_intersect(m->acc, r, 0, INFINITY, &ah);
        *t = ah.t;
        return hit;
    }
}

typedef struct {
    double rays_per_s;
    long hits;
    double tsum; /* keeps the work observable */
} timing;

static double thread_cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One thread: the fastest of at least MIN_PASSES passes over the rays (and of
 * as many as fit in MIN_SECONDS), timed by the thread's own CPU time, so other
 * processes on a shared machine can neither stretch a pass by taking the core
 * away nor, through the minimum, by disturbing some passes. All threads: rays
 * over wall time across all passes (a single pass of a few milliseconds would
 * measure the scheduler's time slice, not the tracing). */
static timing time_method(const method *m, const ray3 *rays, int n, int threads)
{
    timing tm = {0};
    double (*timer)(void) = threads == 1 ? thread_cpu_seconds : now_seconds;
    double best = INFINITY, t_start = now_seconds(), first = timer();
    int pass = 0;
    for (; pass < MIN_PASSES || now_seconds() - t_start < MIN_SECONDS; pass++) {
        long hits = 0;
        double tsum = 0, t0 = timer();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 256) reduction(+ : hits, tsum)
        for (int i = 0; i < n; i++) {
            double t;
            if (trace(m, &rays[i], &t)) {
                hits++;
                tsum += t;
            }
        }
        best = fmin(best, timer() - t0);
        tm.hits = hits;
        tm.tsum += tsum;
    }
    tm.rays_per_s = threads == 1 ? (double)n / best : (double)n * pass / (timer() - first);
    return tm;
}

/* splitmix64 */
static double uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

static void incoherent_rays(vec3 lo, vec3 hi, uint64_t seed, ray3 *rays, int n)
{
    vec3 c = v3_scale(v3_add(lo, hi), 0.5);
    double radius = 1.5 * 0.5 * v3_len(v3_sub(hi, lo));
    for (int i = 0; i < n; i++) {
        double z = 2 * uniform(&seed) - 1, phi = 2 * M_PI * uniform(&seed), s = sqrt(1 - z * z);
        vec3 o = v3_add(c, v3_scale(v3(s * cos(phi), s * sin(phi), z), radius));
        vec3 target = v3(lo.x + uniform(&seed) * (hi.x - lo.x), lo.y + uniform(&seed) * (hi.y - lo.y),
                         lo.z + uniform(&seed) * (hi.z - lo.z));
        rays[i] = (ray3){o, v3_norm(v3_sub(target, o))};
    }
}

/* A pinhole camera a little above the object, framing its bounding sphere. */
static void camera_rays(vec3 lo, vec3 hi, ray3 *rays, int side)
{
    vec3 c = v3_scale(v3_add(lo, hi), 0.5);
    double radius = 0.5 * v3_len(v3_sub(hi, lo)), fov = 40.0 * M_PI / 180.0;
    vec3 back = v3_norm(v3(0.15, 0.35, 1.0));
    vec3 eye = v3_add(c, v3_scale(back, radius / sin(0.5 * fov)));
    vec3 fwd = v3_neg(back), right = v3_norm(v3_cross(fwd, v3(0, 1, 0))), up = v3_cross(right, fwd);
    double half = tan(0.5 * fov);
    for (int y = 0; y < side; y++) {
        for (int x = 0; x < side; x++) {
            double sx = (2.0 * (x + 0.5) / side - 1.0) * half, sy = (1.0 - 2.0 * (y + 0.5) / side) * half;
            rays[y * side + x] = (ray3){eye, v3_norm(v3_add(fwd, v3_add(v3_scale(right, sx), v3_scale(up, sy))))};
        }
    }
}

/* The curvature tolerance giving about `target` domains (bisection on log tol;
 * the count falls as the tolerance grows). Returns the rings, malloc'd. */
static double *rings_near(const bspline_t *c, int target, int *n, double *tol_out)
{
    double lo = log(1e-12), hi = log(1.0), *best = NULL;
    int nbest = 0;
    double tbest = 0;
    for (int it = 0; it < 40; it++) {
        double mid = 0.5 * (lo + hi), *u = NULL;
        int k = 0;
        if (curve_domains_by_curvature(c, exp(mid), &u, &k) != 0) {
            fprintf(stderr, "bench_sor: curve_domains_by_curvature failed at tol %g\n", exp(mid));
            exit(1);
        }
        if (!best || abs(k - target) < abs(nbest - target)) {
            free(best);
            best = u, nbest = k, tbest = exp(mid);
        } else {
            free(u);
        }
        if (k == target)
            break;
        if (k > target)
            lo = mid;
        else
            hi = mid;
    }
    *n = nbest;
    *tol_out = tbest;
    return best;
}

static accel_t *scene_of(const bspline_t *c, const accel_sor_mode *mode, double *build_s)
{
    char err[256];
    double t0 = now_seconds();
    accel_t *acc = accel_create(ACCEL_BUILD_BEST, err, sizeof err);
    if (!acc || accel_add_sor(acc, c, HEIGHT, SOR_CAPS_ALL, NULL, mode, err, sizeof err) == ACCEL_INVALID_ID ||
        accel_commit(acc, err, sizeof err) != 0) {
        fprintf(stderr, "bench_sor: %s\n", err);
        exit(1);
    }
    *build_s = now_seconds() - t0;
    return acc;
}

static RTCScene raw_scene_of(RTCDevice device, const bspline_t *c, const double *rings, int n_rings, int segments)
{
    mesh_t m;
    if (mesh_revolve(c, rings, n_rings, HEIGHT, segments, MESH_CAP_BASE | MESH_CAP_MOUTH, &m) != 0) {
        fprintf(stderr, "bench_sor: mesh_revolve failed\n");
        exit(1);
    }
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *pos = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                         (size_t)m.n_verts);
    uint32_t *tri = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                            (size_t)m.n_tris);
    memcpy(pos, m.pos, 3 * sizeof(float) * (size_t)m.n_verts);
    memcpy(tri, m.tri, 3 * sizeof(uint32_t) * (size_t)m.n_tris);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    mesh_free(&m);
    return scene;
}

/* Largest distance of the mesh's hit points from the exact surface. */
static double mesh_error(const accel_t *acc, const bspline_t *c, const ray3 *rays, int n)
{
    double worst = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : worst)
    for (int i = 0; i < n; i++) {
        accel_hit h;
        if (accel_intersect(acc, &rays[i], 0, INFINITY, &h))
            worst = fmax(worst, accel_sor_distance(c, HEIGHT, SOR_CAPS_ALL, h.p));
    }
    return worst;
}

typedef struct {
    const char *label;
    const ray3 *rays;
    int n;
} ray_set;

/* Times m on one and on all threads, prints the row, returns the one-thread timing. */
static timing row(const char *profile, const ray_set *set, const char *name, const method *m, int cores,
                  const char *extra)
{
    timing one = time_method(m, set->rays, set->n, 1), all = time_method(m, set->rays, set->n, cores);
    printf("%-8s %-10s %-16s %12.0f %12.0f %6.1f%%  %s\n", profile, set->label, name, one.rays_per_s, all.rays_per_s,
           100.0 * (double)one.hits / set->n, extra);
    return one;
}

static int find_profile(const char *name)
{
    for (int p = 0; p < sor_test_profile_count(); p++)
        if (strcmp(sor_test_profile_name(p), name) == 0)
            return p;
    fprintf(stderr, "bench_sor: no test profile named '%s'\n", name);
    exit(2);
}

static sor_t *make_sor(const bspline_t *c)
{
    char err[256];
    sor_t *s = sor_create(c, HEIGHT, SOR_CAPS_ALL, err, sizeof err);
    if (!s) {
        fprintf(stderr, "bench_sor: %s\n", err);
        exit(1);
    }
    return s;
}

/* One method on one profile's incoherent rays, one thread, for a profiler:
 * direct, embree-user, naive, mesh:N or raw:N (N angular segments). */
static int only(const char *what, const char *name, double seconds)
{
    bspline_t c;
    sor_test_profile(find_profile(name), &c);
    sor_t *s = make_sor(&c);
    vec3 lo, hi;
    sor_bounds(s, &lo, &hi);
    ray3 *rays = malloc(sizeof *rays * N_INCOHERENT);
    incoherent_rays(lo, hi, 1, rays, N_INCOHERENT);
    method m = {.kind = M_DIRECT, .sor = s};
    double *rings = NULL, tol, build;
    int n_rings, segments = 0;
    RTCDevice device = rtcNewDevice(NULL);
    if (strcmp(what, "naive") == 0) {
        m.kind = M_NAIVE;
    } else if (strcmp(what, "embree-user") == 0) {
        accel_sor_mode analytic = {0};
        m = (method){.kind = M_EMBREE_USER, .acc = scene_of(&c, &analytic, &build)};
    } else if (sscanf(what, "mesh:%d", &segments) == 1) {
        rings = rings_near(&c, TARGET_RINGS, &n_rings, &tol);
        accel_sor_mode mode = {.segments = segments, .u_rings = rings, .n_rings = n_rings};
        m = (method){.kind = M_MESH, .acc = scene_of(&c, &mode, &build)};
    } else if (sscanf(what, "raw:%d", &segments) == 1) {
        rings = rings_near(&c, TARGET_RINGS, &n_rings, &tol);
        m = (method){.kind = M_RAW, .raw = raw_scene_of(device, &c, rings, n_rings, segments)};
    } else if (strcmp(what, "direct") != 0) {
        fprintf(stderr, "bench_sor: unknown method '%s' (direct, embree-user, naive, mesh:N, raw:N)\n", what);
        return 2;
    }
    long traced = 0, hits = 0;
    double t0 = thread_cpu_seconds();
    while (thread_cpu_seconds() - t0 < seconds) {
        for (int i = 0; i < N_INCOHERENT; i++) {
            double t;
            hits += trace(&m, &rays[i], &t);
        }
        traced += N_INCOHERENT;
    }
    printf("%s %s: %ld rays, %ld hits, %.0f rays/s (thread CPU time)\n", what, name, traced, hits,
           traced / (thread_cpu_seconds() - t0));
    accel_destroy(m.acc);
    if (m.raw)
        rtcReleaseScene(m.raw);
    rtcReleaseDevice(device);
    free(rings);
    free(rays);
    sor_destroy(s);
    bspline_free(&c);
    return 0;
}

/* Embree asks every tracing thread to flush denormals to zero (it warns of a
 * severe slowdown otherwise); set on the master and on OpenMP's pool, which
 * persists, so every method runs under the same mode. */
static void denormals_to_zero(void)
{
#pragma omp parallel
    {
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    }
}

int main(int argc, char **argv)
{
    denormals_to_zero();
    if (argc == 5 && strcmp(argv[1], "--only") == 0)
        return only(argv[2], argv[3], atof(argv[4]));
    if (argc != 1) {
        fprintf(stderr, "usage: bench_sor [--only METHOD PROFILE SECONDS]\n");
        return 2;
    }
    int cores = omp_get_max_threads();
    printf("bench_sor: %d incoherent rays, %dx%d camera rays, %d thread(s) for 'all'; >= %d passes and >= %.1f s "
           "per rate; 1T: fastest pass by thread CPU time; all: wall time over all passes\n",
           N_INCOHERENT, CAMERA_SIDE, CAMERA_SIDE, cores, MIN_PASSES, MIN_SECONDS);
    printf("%-8s %-10s %-16s %12s %12s %7s  %s\n", "profile", "rays", "method", "rays/s 1T", "rays/s all", "hits",
           "mesh: rings x segments, triangles, build s, max error, sagitta 4.9r/N^2");
    int n_cam = CAMERA_SIDE * CAMERA_SIDE;
    ray3 *inc = malloc(sizeof *inc * N_INCOHERENT), *cam = malloc(sizeof *cam * (size_t)n_cam);
    double ratio = NAN, ratio_user = NAN, ratio_raw = NAN;
    RTCDevice device = rtcNewDevice(NULL);
    for (int p = 0; p < sor_test_profile_count(); p++) {
        const char *name = sor_test_profile_name(p);
        bspline_t c;
        sor_test_profile(p, &c);
        sor_t *s = make_sor(&c);
        vec3 lo, hi;
        sor_bounds(s, &lo, &hi);
        double rmax = fmax(fmax(-lo.x, hi.x), fmax(-lo.z, hi.z));
        incoherent_rays(lo, hi, 1 + (uint64_t)p, inc, N_INCOHERENT);
        camera_rays(lo, hi, cam, CAMERA_SIDE);
        int n_rings;
        double tol, build;
        double *rings = rings_near(&c, TARGET_RINGS, &n_rings, &tol);
        accel_sor_mode analytic = {0};
        method direct = {.kind = M_DIRECT, .sor = s}, naive = {.kind = M_NAIVE, .sor = s},
               user = {.kind = M_EMBREE_USER, .acc = scene_of(&c, &analytic, &build)};
        method mesh[N_SEGMENTS], raw[N_SEGMENTS];
        char extra[N_SEGMENTS][160];
        for (int k = 0; k < N_SEGMENTS; k++) {
            accel_sor_mode mode = {.segments = SEGMENTS[k], .u_rings = rings, .n_rings = n_rings};
            mesh[k] = (method){.kind = M_MESH, .acc = scene_of(&c, &mode, &build)};
            raw[k] = (method){.kind = M_RAW, .raw = raw_scene_of(device, &c, rings, n_rings, SEGMENTS[k])};
            double err = mesh_error(mesh[k].acc, &c, inc, N_INCOHERENT);
            snprintf(extra[k], sizeof extra[k], "%d x %d, %d tris, %.2f s, %.2e, %.2e", n_rings, SEGMENTS[k],
                     accel_geometry_triangles(mesh[k].acc, 0), build, err,
                     4.9 * rmax / ((double)SEGMENTS[k] * SEGMENTS[k]));
        }
        const ray_set sets[2] = {{"incoherent", inc, N_INCOHERENT}, {"camera", cam, n_cam}};
        for (int r = 0; r < 2; r++) {
            timing d1 = row(name, &sets[r], "analytic direct", &direct, cores, "");
            timing u1 = row(name, &sets[r], "analytic embree", &user, cores, "");
            for (int k = 0; k < N_SEGMENTS; k++) {
                char label[32];
                snprintf(label, sizeof label, "mesh %d", SEGMENTS[k]);
                timing m1 = row(name, &sets[r], label, &mesh[k], cores, extra[k]);
                snprintf(label, sizeof label, "mesh %d raw", SEGMENTS[k]);
                timing r1 = row(name, &sets[r], label, &raw[k], cores, "");
                if (r == 0 && SEGMENTS[k] == 360 && strcmp(name, RECON_NAME) == 0) {
                    ratio = d1.rays_per_s / m1.rays_per_s;
                    ratio_user = u1.rays_per_s / m1.rays_per_s;
                    ratio_raw = d1.rays_per_s / r1.rays_per_s;
                }
            }
            row(name, &sets[r], "naive", &naive, cores, "");
        }
        printf("%-8s rings: %d curvature domains at tol %.3g (profile units); %d SOR primitives\n", name, n_rings, tol,
               sor_prim_count(s));
        for (int k = 0; k < N_SEGMENTS; k++) {
            accel_destroy(mesh[k].acc);
            rtcReleaseScene(raw[k].raw);
        }
        accel_destroy(user.acc);
        free(rings);
        sor_destroy(s);
        bspline_free(&c);
    }
    rtcReleaseDevice(device);
    free(inc);
    free(cam);
    printf("analytic (embree user geometry)/embree ratio: %.2f\n", ratio_user);
    printf("analytic/embree (raw rtcIntersect1, t only) ratio: %.2f\n", ratio_raw);
    printf("analytic/embree ratio: %.2f\n", ratio);
    return 0;
}
