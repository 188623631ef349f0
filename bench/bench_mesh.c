/* Mesh benchmark: mesh_revolve, then the PLY and OBJ exporters, for 90k to
 * 400k faces of a vase profile. Median wall time of repeated runs. Files go
 * to a temporary folder that is removed afterwards. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "celadon/mesh.h"
#include "core/core.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double file_mb(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? st.st_size / 1e6 : 0.0;
}

int main(void)
{
    bspline_t c;
    const double U[] = {0, 0, 0, 0, 0.1, 0.35, 0.35, 0.7, 1, 1, 1, 1};
    const vec2 P[] = {{30, 0}, {45, 10}, {60, 40}, {20, 70}, {15, 90}, {25, 110}, {35, 130}, {33, 140}};
    if (bspline_init(&c, 3, 8) != 0)
        return 1;
    memcpy(c.knots, U, sizeof U);
    memcpy(c.ctrl, P, sizeof P);

    char dir[] = "/tmp/celadon-bench-mesh-XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    char ply[256], obj[256], err[512];
    snprintf(ply, sizeof ply, "%s/m.ply", dir);
    snprintf(obj, sizeof obj, "%s/m.obj", dir);

    enum { RUNS_REVOLVE = 21, RUNS_PLY = 7, RUNS_OBJ = 3 };
    const int segments = 360, rings[] = {126, 251, 556};
    printf("%9s %9s %8s | %12s %10s %10s | %8s %8s\n", "faces", "verts", "segments", "revolve ms", "PLY ms",
           "OBJ ms", "PLY MB", "OBJ MB");
    for (size_t k = 0; k < sizeof rings / sizeof rings[0]; k++) {
        double t_rev[RUNS_REVOLVE], t_ply[RUNS_PLY], t_obj[RUNS_OBJ];
        mesh_t m;
        for (int r = 0; r < RUNS_REVOLVE; r++) {
            double t0 = now_seconds();
            if (mesh_revolve(&c, NULL, rings[k], 1.0, segments, MESH_CAP_BASE | MESH_CAP_MOUTH, &m) != 0)
                return 1;
            t_rev[r] = (now_seconds() - t0) * 1e3;
            if (r + 1 < RUNS_REVOLVE)
                mesh_free(&m);
        }
        for (int r = 0; r < RUNS_PLY; r++) {
            double t0 = now_seconds();
            if (mesh_write_ply(ply, &m, err, sizeof err) != 0)
                return fprintf(stderr, "%s\n", err), 1;
            t_ply[r] = (now_seconds() - t0) * 1e3;
        }
        for (int r = 0; r < RUNS_OBJ; r++) {
            double t0 = now_seconds();
            if (mesh_write_obj(obj, &m, NULL, err, sizeof err) != 0)
                return fprintf(stderr, "%s\n", err), 1;
            t_obj[r] = (now_seconds() - t0) * 1e3;
        }
        printf("%9d %9d %8d | %12.2f %10.1f %10.1f | %8.1f %8.1f\n", m.n_tris, m.n_verts, segments,
               median(t_rev, RUNS_REVOLVE), median(t_ply, RUNS_PLY), median(t_obj, RUNS_OBJ), file_mb(ply),
               file_mb(obj));
        mesh_free(&m);
    }
    remove(ply);
    remove(obj);
    rmdir(dir);
    bspline_free(&c);
    return 0;
}
