/* Levels of detail by screen-space error. See lod.h. */
#include "museum/lod.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_domains.h"
#include "celadon/mesh_rings.h"

/* The profile's scale and its curve's largest radius. */
typedef struct {
    double m_per_px, r_max_px;
} lod_scale;

/* E(N) in metres: twice the angular sagitta of the widest ring. 1 - cos x =
 * 2 sin^2(x/2), without the cancellation at large N. */
static double level_error(const lod_scale *s, int segments)
{
    double h = sin(M_PI / (2.0 * segments));
    return 2.0 * s->r_max_px * s->m_per_px * 2.0 * h * h;
}

static double level_distance(double error) { return error / (LOD_MAX_PIXELS * LOD_PIXEL_ANGLE); }

/* The fewest segments whose error is invisible from distance d. */
static int segments_for(const lod_scale *s, double d)
{
    int n = LOD_MIN_SEGMENTS;
    while (n < LOD_MAX_SEGMENTS && level_distance(level_error(s, n)) > d)
        n++;
    return n;
}

static int descending(const void *a, const void *b) { return *(const int *)b - *(const int *)a; }

static int build_level(const bspline_t *profile, double height_m, const lod_scale *s, int segments, lod_level *l)
{
    double *u = NULL;
    int n_rings = 0;
    memset(l, 0, sizeof *l);
    l->segments = segments;
    l->error = level_error(s, segments);
    l->distance = level_distance(l->error);
    /* The rings' half of the budget; finer than a few float ulps of the
     * radius resolves nothing (MESH_RING_TOL_FLOOR). */
    double tol_px = fmax(0.5 * l->error / s->m_per_px, MESH_RING_TOL_FLOOR * s->r_max_px);
    if (curve_domains_by_curvature(profile, tol_px, &u, &n_rings) != 0)
        return -1;
    int rc = mesh_revolve(profile, u, n_rings, height_m, segments, MESH_CAP_BASE, &l->mesh);
    free(u);
    return rc;
}

int lod_make(const bspline_t *profile, double height_m, const int *segments, int n_segments, double nearest_m,
             lod_level *out)
{
    if (!profile || profile->n_ctrl < 2 || !(height_m > 0) || n_segments < 0 || n_segments > LOD_MAX_LEVELS)
        return -1;
    double rim_px = bspline_eval(profile, 1.0).y;
    if (!(rim_px > 0))
        return -1;
    lod_scale sc = {height_m / rim_px, bspline_largest(profile, 0)};
    if (!(sc.r_max_px > 0))
        return -1;
    int counts[LOD_MAX_LEVELS], n = 0;
    if (n_segments == 0) {
        int s = segments_for(&sc, nearest_m);
        for (; n < LOD_AUTO_LEVELS && (n == 0 || counts[n - 1] > LOD_MIN_SEGMENTS); n++, s /= 2)
            counts[n] = s < LOD_MIN_SEGMENTS ? LOD_MIN_SEGMENTS : s;
    } else {
        for (int i = 0; i < n_segments; i++)
            if (segments[i] < 3 || segments[i] > LOD_MAX_SEGMENTS)
                return -1;
        memcpy(counts, segments, (size_t)n_segments * sizeof *counts);
        qsort(counts, (size_t)n_segments, sizeof *counts, descending);
        for (int i = 0; i < n_segments; i++)
            if (n == 0 || counts[i] != counts[n - 1])
                counts[n++] = counts[i];
    }
    for (int k = 0; k < n; k++)
        if (build_level(profile, height_m, &sc, counts[k], &out[k]) != 0) {
            lod_free(out, k + 1);
            return -1;
        }
    out[0].distance = 0.0;
    return n;
}

void lod_free(lod_level *levels, int n)
{
    for (int k = 0; k < n; k++)
        mesh_free(&levels[k].mesh);
}
