/* The analytic-vs-meshed cross-check: one scene rendered with its SORs
 * intersected exactly and revolved into N angular segments for several N,
 * with identical sampler seeds, and the differences measured against the
 * analytic image. A revolved mesh is inscribed in the surface, so its
 * distance to it, and every error it causes, should fall as N^-2.
 *
 * Metrics of one N (docs/crosscheck.md):
 *  - image: over every pixel and RGB channel of the rendered images,
 *      rel_mse       = mean (m - a)^2 / (a^2 + 0.01)   (a analytic, m meshed)
 *      mean_abs_diff = mean |m - a|
 *    Shared seeds make the two images' noise almost identical, but paths that
 *    cross a silhouette differently still add noise; these can floor.
 *  - geometry (deterministic, no noise): k x k primary rays per pixel at the
 *    centres of a regular subpixel grid, each traced to its first hit in both
 *    scenes (passing straight through thindielectric panes, which do not
 *    bend rays, so that vessels in glass cases count):
 *      coverage_rays   rays whose first-hit shape differs (one hits an SOR
 *                      where the other hits another shape or nothing),
 *      coverage_area   coverage_rays / k^2: the area in pixels between the two
 *                      silhouettes,
 *      coverage_pixels pixels with at least one such ray,
 *      depth_rel_err   mean |t_m - t_a| / t_a over rays whose first hit is the
 *                      same SOR in both scenes (t: distance along the ray),
 *      normal_err_deg  mean angle between the shading normals of those hits. */
#ifndef CELADON_CROSSCHECK_H
#define CELADON_CROSSCHECK_H

#include <stddef.h>

#include "celadon/parts.h"
#include "celadon/render_image.h"
#include "celadon/scene.h"

typedef struct {
    const char *scene_path;
    const scene_define *defs; /* -D overrides */
    int ndefs;
    scene_options build; /* size, spp, seed; mesh_segments is ignored */
    int threads;               /* 0: OpenMP's default */
    const int *segments;       /* N values, >= 3, strictly increasing, at least 2 */
    int nsegments;
    int geo_grid;              /* k: primary rays per pixel side of the geometry metrics */
    int fit_from;              /* the fits use the N >= fit_from (0: every N); at least two must be */
    int progress;              /* 1: one line per render on stderr */
    const char *const *part_dirs; /* npart_dirs > 0: crosscheck_run merges each render from the parts in */
    int npart_dirs;               /* these folders (crosscheck_render_part's) instead of rendering it */
} crosscheck_params;

typedef struct {
    int segments;
    double seconds; /* render time of the meshed image */
    double rel_mse, mean_abs_diff;
    long long coverage_rays, coverage_pixels;
    double coverage_area, depth_rel_err, normal_err_deg;
} crosscheck_row;

/* Least-squares fit log10(error) = slope log10(N) + intercept over the rows
 * with N >= fit_from where the error is positive; n_used < 2 means no fit
 * (slope NaN). */
typedef struct {
    double slope, intercept;
    int n_used;
} crosscheck_fit;

enum {
    CROSSCHECK_REL_MSE,
    CROSSCHECK_MEAN_ABS_DIFF,
    CROSSCHECK_COVERAGE_AREA,
    CROSSCHECK_DEPTH_REL_ERR,
    CROSSCHECK_NORMAL_ERR,
    CROSSCHECK_METRIC_COUNT
};

/* The metric of report.json's fitted_slope: the image error itself. */
#define CROSSCHECK_PRIMARY_METRIC CROSSCHECK_MEAN_ABS_DIFF

/* A stall: over the finest factor of four in N (from the largest N at most
 * a quarter of the last, or the first N, to the last) the image error
 * (mean_abs_diff) fell more slowly than N^-1 while the depth error fell
 * faster than N^-1.5. Something no segment count changes is then left in
 * the images: coincident surfaces (a vessel standing exactly in another
 * surface z-fights with it; docs/crosscheck.md), or the Monte Carlo noise
 * of the few samples that changed course (more spp or pixels). */
typedef struct {
    int found;              /* 1: the image error stalls */
    int n_from, n_to;       /* the span of N it was measured over */
    double image_slope, depth_slope;
} crosscheck_stall;

typedef struct {
    int width, height, spp, geo_grid;
    int fit_from;         /* the smallest N the fits use */
    unsigned long long seed;
    int sor_shapes;
    long long sor_rays;   /* geometry rays whose analytic first hit is an SOR */
    double analytic_seconds;
    int nrows;
    crosscheck_row *rows;
    crosscheck_fit fits[CROSSCHECK_METRIC_COUNT];
    crosscheck_stall stall;
} crosscheck_result;

/* Name of a metric as in report.json ("rel_mse", ...), and its value in a row. */
const char *crosscheck_metric_name(int metric);
double crosscheck_metric_value(const crosscheck_row *row, int metric);

/* The observed order of convergence between rows i - 1 and i (i >= 1):
 * log(e_i / e_(i-1)) / log(N_i / N_(i-1)), the slope of the log-log plot's
 * segment; NaN unless both errors are positive. Where it settles near -2 the
 * meshes are in the asymptotic range, where every error is proportional to
 * the sagitta; coarser meshes can be outside it (docs/crosscheck.md). */
double crosscheck_local_slope(const crosscheck_row *rows, int i, int metric);

/* The stall of crosscheck_stall's definition over rows[0..nrows) (N
 * increasing); found is 0 with fewer than two rows. */
crosscheck_stall crosscheck_find_stall(const crosscheck_row *rows, int nrows);

/* Renders and compares. Writes into outdir (which must exist) analytic.exr,
 * analytic.png, mesh-N.exr and mesh-N.png per N; nothing when outdir is
 * NULL. Returns 0; -2 for bad input
 * (unreadable scene, a scene without an SOR, bad parameters) with one line
 * in err; -1 for other failures. */
int crosscheck_run(const crosscheck_params *p, const char *outdir, crosscheck_result *res, char *err,
                   size_t errlen);
void crosscheck_result_free(crosscheck_result *res);

/* The cross-check's renders shared out as parts (parts.h), for a job
 * scheduler: part `part` of the analytic render and of each meshed one,
 * written into outdir (which must exist) as analytic.exr and mesh-N.exr,
 * part EXRs. crosscheck_run with part_dirs naming every part's folder then
 * merges them and measures. Returns 0; -2 for bad input (as crosscheck_run,
 * or more parts than samples) with one line in err; -1 for other failures. */
int crosscheck_render_part(const crosscheck_params *p, render_part part, const char *outdir, char *err,
                           size_t errlen);

/* report.json at path, and the log-log plot of every metric with its fitted
 * line and an N^-2 reference (plot_width x plot_height PNG). Return 0 or -1
 * with a reason. */
int crosscheck_write_report(const crosscheck_result *res, const crosscheck_params *p, const char *path, char *err,
                            size_t errlen);
/* The text of report.json (the same JSON crosscheck_write_report writes),
 * malloc'd; NULL when the scene path is not UTF-8. */
char *crosscheck_report_text(const crosscheck_result *res, const crosscheck_params *p);

/* crosscheck_run for callers that keep no files (the Python package): the
 * scene with defs and `celadon render`'s overrides o (its mesh_segments and
 * aovs ignored) rendered at each N of segments, the fits over N >= fit_from
 * (0: all), the geometry metrics over k = 4 rays per pixel side; *report
 * receives crosscheck_report_text (free it). Returns 0; -2 for bad input,
 * -1 for other failures, with one line in err (the line `celadon crosscheck`
 * prints after "celadon: "). */
int crosscheck_measure(const char *scene_path, const scene_define *defs, int ndefs, const render_image_options *o,
                       const int *segments, int nsegments, int fit_from, char **report, char *err, size_t errlen);

int crosscheck_write_plot(const crosscheck_result *res, const char *path, int plot_width, int plot_height,
                          char *err, size_t errlen);

#endif
