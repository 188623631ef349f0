/* The analytic-vs-meshed cross-check (include/celadon/crosscheck.h): the
 * renders, the image metrics, the deterministic primary-hit metrics and the
 * log-log fits. It reads the scenes through the public API only (scene.h,
 * render.h), probing primary rays with scene_first_hit so that the geometry
 * metrics see the exact first hits. */
#include <gsl/gsl_fit.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/crosscheck.h"
#include "celadon/render.h"

/* relMSE's epsilon (as in pbrt's and Mitsuba's image comparisons): keeps
 * black pixels from dominating. */
#define REL_MSE_EPS 0.01

static const char *const metric_names[CROSSCHECK_METRIC_COUNT] = {"rel_mse", "mean_abs_diff", "coverage_area",
                                                                  "depth_rel_err", "normal_err_deg"};

const char *crosscheck_metric_name(int metric) { return metric_names[metric]; }

double crosscheck_metric_value(const crosscheck_row *row, int metric)
{
    switch (metric) {
    case CROSSCHECK_REL_MSE: return row->rel_mse;
    case CROSSCHECK_MEAN_ABS_DIFF: return row->mean_abs_diff;
    case CROSSCHECK_COVERAGE_AREA: return row->coverage_area;
    case CROSSCHECK_DEPTH_REL_ERR: return row->depth_rel_err;
    default: return row->normal_err_deg;
    }
}

/* Loads the scene with SORs analytic (segments 0) or revolved. */
static scene_t *load(const crosscheck_params *p, int segments, char *err, size_t errlen)
{
    scene_options so = p->build;
    so.mesh_segments = segments;
    return scene_create_from_file(p->scene_path, p->defs, p->ndefs, &so, err, errlen);
}

/* Merges the parts of render `stem` from p->part_dirs (crosscheck_render_part's
 * folders) into film. */
static int merge_parts(const crosscheck_params *p, const scene_t *s, const char *stem, film_t *film, char *err,
                       size_t errlen)
{
    char(*paths)[4200] = malloc(sizeof *paths * (size_t)p->npart_dirs);
    const char **list = malloc(sizeof *list * (size_t)p->npart_dirs);
    if (!paths || !list)
        abort();
    for (int i = 0; i < p->npart_dirs; i++) {
        snprintf(paths[i], sizeof paths[i], "%s/%s.exr", p->part_dirs[i], stem);
        list[i] = paths[i];
    }
    int rc = render_parts_merge(list, p->npart_dirs, s, film, err, errlen);
    free(paths);
    free(list);
    return rc;
}

/* Renders s (or merges its parts), writes outdir/stem.exr and .png (unless
 * outdir is NULL), returns the RGB pixels; NULL with *rc -2 for refused parts, -1 otherwise. */
static float *render_and_write(const scene_t *s, const crosscheck_params *p, const char *outdir, const char *stem,
                               double *seconds, int *rc, char *err, size_t errlen)
{
    render_options ro = {.threads = p->threads};
    film_t film;
    render_stats st = {0};
    *rc = p->npart_dirs > 0 ? merge_parts(p, s, stem, &film, err, errlen) : render_scene(s, &ro, &film, &st, err, errlen);
    if (*rc != 0)
        return NULL;
    *rc = -1;
    *seconds = st.seconds;
    float *px = malloc(sizeof *px * 3 * (size_t)film.width * (size_t)film.height);
    char path[4200];
    int ok = px != NULL;
    for (int k = 0; k < 2 && ok && outdir; k++) {
        snprintf(path, sizeof path, "%s/%s.%s", outdir, stem, k ? "png" : "exr");
        ok = film_write(&film, path, err, errlen) == 0;
    }
    if (ok)
        film_develop(&film, px);
    else if (!px)
        snprintf(err, errlen, "out of memory");
    film_free(&film);
    if (!ok) {
        free(px);
        return NULL;
    }
    if (p->progress && p->npart_dirs > 0)
        fprintf(stderr, "crosscheck: %s: merged from %d parts\n", stem, p->npart_dirs);
    else if (p->progress)
        fprintf(stderr, "crosscheck: %s: %.2f s\n", stem, *seconds);
    return px;
}

/* Renders part `part` of s into outdir/stem.exr. */
static int render_part_into(const scene_t *s, const crosscheck_params *p, render_part part, const char *outdir,
                            const char *stem, char *err, size_t errlen)
{
    render_options ro = {.threads = p->threads};
    if (render_part_samples(part, scene_spp(s), &ro.sample_begin, &ro.sample_end) != 0) {
        snprintf(err, errlen, "%s: part %d/%d of a render of %d spp gets no samples: use at most %d parts",
                 p->scene_path, part.k, part.n, scene_spp(s), scene_spp(s));
        return -2;
    }
    film_t film;
    render_stats st;
    if (render_scene(s, &ro, &film, &st, err, errlen) != 0)
        return -1;
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.exr", outdir, stem);
    int rc = render_part_write(&film, s, part, !st.interrupted, path, err, errlen);
    film_free(&film);
    if (rc == 0 && p->progress)
        fprintf(stderr, "crosscheck: %s part %d/%d: %.2f s\n", stem, part.k, part.n, st.seconds);
    return rc;
}

static void image_metrics(const float *a, const float *m, size_t n, crosscheck_row *row)
{
    double se = 0.0, ae = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)m[i] - (double)a[i];
        se += d * d / ((double)a[i] * a[i] + REL_MSE_EPS);
        ae += fabs(d);
    }
    row->rel_mse = se / (double)n;
    row->mean_abs_diff = ae / (double)n;
}

/* The first hit along r that is not a thin sheet (thindielectric): those let
 * the transmitted ray through unbent, so a vessel in a glass case is still
 * the first thing a primary ray meets. Returns the shape index or -1. */
static int first_opaque_hit(const scene_t *s, const ray3 *r, double tmin, double tmax, scene_hit *hit)
{
    for (int pane = 0; pane < 64; pane++) {
        if (!scene_first_hit(s, r, tmin, tmax, hit))
            return -1;
        if (!hit->sheet)
            return hit->shape;
        tmin = hit->t + hit->eps;
    }
    return -1;
}

static int is_sor(const scene_hit *h) { return strcmp(h->shape_type, "sor") == 0; }

/* The primary-hit metrics of the header, over k x k rays per pixel. */
static void geometry_metrics(const scene_t *an, const scene_t *me, const crosscheck_params *p, crosscheck_row *row,
                             long long *sor_rays)
{
    int width, height, k = p->geo_grid;
    scene_film_size(an, &width, &height);
    long long cov_rays = 0, cov_px = 0, same = 0, on_sor = 0;
    double depth = 0.0, angle = 0.0;
#pragma omp parallel for schedule(dynamic, 4) num_threads(p->threads > 0 ? p->threads : omp_get_max_threads()) \
    reduction(+ : cov_rays, cov_px, same, on_sor, depth, angle)
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            int differs = 0;
            for (int j = 0; j < k; j++)
                for (int i = 0; i < k; i++) {
                    double tmin, tmax;
                    ray3 r = scene_camera_ray(an, x, y, (i + 0.5) / k, (j + 0.5) / k, &tmin, &tmax);
                    scene_hit ha, hm;
                    int fa = first_opaque_hit(an, &r, tmin, tmax, &ha), fm = first_opaque_hit(me, &r, tmin, tmax, &hm);
                    int sa = fa >= 0 && is_sor(&ha), sm = fm >= 0 && is_sor(&hm);
                    on_sor += sa;
                    if (fa != fm && (sa || sm)) {
                        cov_rays++;
                        differs = 1;
                    } else if (sa) {
                        same++;
                        depth += fabs(hm.t - ha.t) / ha.t;
                        double c = v3_dot(ha.n, hm.n);
                        angle += acos(c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c);
                    }
                }
            cov_px += differs;
        }
    row->coverage_rays = cov_rays;
    row->coverage_pixels = cov_px;
    row->coverage_area = (double)cov_rays / ((double)k * k);
    row->depth_rel_err = same ? depth / (double)same : 0.0;
    row->normal_err_deg = same ? angle / (double)same * 180.0 / M_PI : 0.0;
    *sor_rays = on_sor;
}

/* The slope of a metric's log-log chord between rows i and j. */
static double chord_slope(const crosscheck_row *rows, int i, int j, int metric)
{
    double e0 = crosscheck_metric_value(&rows[i], metric), e1 = crosscheck_metric_value(&rows[j], metric);
    if (!(e0 > 0.0 && e1 > 0.0 && isfinite(e0) && isfinite(e1)))
        return NAN;
    return log(e1 / e0) / log((double)rows[j].segments / rows[i].segments);
}

double crosscheck_local_slope(const crosscheck_row *rows, int i, int metric)
{
    return chord_slope(rows, i - 1, i, metric);
}

crosscheck_stall crosscheck_find_stall(const crosscheck_row *rows, int nrows)
{
    crosscheck_stall st = {0, 0, 0, NAN, NAN};
    if (nrows < 2)
        return st;
    int last = nrows - 1, from = 0;
    for (int i = 0; i < last; i++)
        if (4 * rows[i].segments <= rows[last].segments)
            from = i;
    st.n_from = rows[from].segments, st.n_to = rows[last].segments;
    st.image_slope = chord_slope(rows, from, last, CROSSCHECK_MEAN_ABS_DIFF);
    st.depth_slope = chord_slope(rows, from, last, CROSSCHECK_DEPTH_REL_ERR);
    st.found = st.image_slope > -1.0 && st.depth_slope < -1.5;
    return st;
}

static crosscheck_fit fit_metric(const crosscheck_row *rows, int n, int metric, int fit_from)
{
    double lx[n > 0 ? n : 1], ly[n > 0 ? n : 1];
    int m = 0;
    for (int i = 0; i < n; i++) {
        double v = crosscheck_metric_value(&rows[i], metric);
        if (rows[i].segments >= fit_from && v > 0.0 && isfinite(v)) {
            lx[m] = log10((double)rows[i].segments);
            ly[m] = log10(v);
            m++;
        }
    }
    crosscheck_fit f = {NAN, NAN, m};
    if (m >= 2) {
        double cov00, cov01, cov11, sumsq;
        gsl_fit_linear(lx, 1, ly, 1, (size_t)m, &f.intercept, &f.slope, &cov00, &cov01, &cov11, &sumsq);
    }
    return f;
}

static int check_params(const crosscheck_params *p, char *err, size_t errlen)
{
    if (p->nsegments < 2) {
        snprintf(err, errlen, "at least two segment counts are needed for a convergence fit");
        return -1;
    }
    for (int i = 0; i < p->nsegments; i++)
        if (p->segments[i] < 3 || (i > 0 && p->segments[i] <= p->segments[i - 1])) {
            snprintf(err, errlen, "segment counts must be >= 3 and strictly increasing");
            return -1;
        }
    if (p->geo_grid < 1 || p->geo_grid > 64) {
        snprintf(err, errlen, "the geometry grid must be from 1 to 64 rays per pixel side");
        return -1;
    }
    int fitted = 0;
    for (int i = 0; i < p->nsegments; i++)
        fitted += p->segments[i] >= p->fit_from;
    if (fitted < 2) {
        snprintf(err, errlen, "fitting from N = %d leaves fewer than two segment counts to fit", p->fit_from);
        return -1;
    }
    return 0;
}

int crosscheck_run(const crosscheck_params *p, const char *outdir, crosscheck_result *res, char *err,
                   size_t errlen)
{
    memset(res, 0, sizeof *res);
    if (check_params(p, err, errlen) != 0)
        return -2;
    scene_t *an = load(p, 0, err, errlen);
    if (!an)
        return -2;
    res->sor_shapes = scene_shapes_of_type(an, "sor");
    if (res->sor_shapes == 0) {
        snprintf(err, errlen, "%s: the scene has no sor shape: nothing to cross-check", p->scene_path);
        scene_destroy(an);
        return -2;
    }
    scene_film_size(an, &res->width, &res->height);
    res->spp = scene_spp(an), res->seed = scene_seed(an), res->geo_grid = p->geo_grid;
    for (int i = p->nsegments - 1; i >= 0 && p->segments[i] >= p->fit_from; i--)
        res->fit_from = p->segments[i];
    int rc = -1;
    float *img_a = NULL;
    res->rows = calloc((size_t)p->nsegments, sizeof *res->rows);
    if (!res->rows) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    img_a = render_and_write(an, p, outdir, "analytic", &res->analytic_seconds, &rc, err, errlen);
    if (!img_a)
        goto done;
    size_t nval = 3 * (size_t)res->width * (size_t)res->height;
    for (int i = 0; i < p->nsegments; i++) {
        crosscheck_row *row = &res->rows[i];
        row->segments = p->segments[i];
        scene_t *me = load(p, row->segments, err, errlen);
        if (!me) {
            rc = -2;
            goto done;
        }
        char stem[32];
        snprintf(stem, sizeof stem, "mesh-%d", row->segments);
        float *img_m = render_and_write(me, p, outdir, stem, &row->seconds, &rc, err, errlen);
        if (img_m) {
            image_metrics(img_a, img_m, nval, row);
            geometry_metrics(an, me, p, row, &res->sor_rays);
        }
        free(img_m);
        scene_destroy(me);
        if (!img_m)
            goto done;
        res->nrows = i + 1;
    }
    for (int m = 0; m < CROSSCHECK_METRIC_COUNT; m++)
        res->fits[m] = fit_metric(res->rows, res->nrows, m, res->fit_from);
    res->stall = crosscheck_find_stall(res->rows, res->nrows);
    rc = 0;
done:
    free(img_a);
    scene_destroy(an);
    return rc;
}

int crosscheck_render_part(const crosscheck_params *p, render_part part, const char *outdir, char *err,
                           size_t errlen)
{
    if (check_params(p, err, errlen) != 0)
        return -2;
    int rc = 0;
    for (int i = -1; i < p->nsegments && rc == 0; i++) {
        scene_t *s = load(p, i < 0 ? 0 : p->segments[i], err, errlen);
        if (!s)
            return -2;
        char stem[32] = "analytic";
        if (i >= 0)
            snprintf(stem, sizeof stem, "mesh-%d", p->segments[i]);
        rc = render_part_into(s, p, part, outdir, stem, err, errlen);
        scene_destroy(s);
    }
    return rc;
}

void crosscheck_result_free(crosscheck_result *res)
{
    free(res->rows);
    memset(res, 0, sizeof *res);
}

int crosscheck_measure(const char *scene_path, const scene_define *defs, int ndefs, const render_image_options *o,
                       const int *segments, int nsegments, int fit_from, char **report, char *err, size_t errlen)
{
    crosscheck_params p = {.scene_path = scene_path, .defs = defs, .ndefs = ndefs,
                           .build = render_image_scene_options(o), .threads = o->threads, .segments = segments,
                           .nsegments = nsegments, .geo_grid = 4, .fit_from = fit_from};
    crosscheck_result res;
    *report = NULL;
    int rc = crosscheck_run(&p, NULL, &res, err, errlen);
    if (rc == 0 && !(*report = crosscheck_report_text(&res, &p))) {
        snprintf(err, errlen, "%s: the scene path is not UTF-8", scene_path);
        rc = -2;
    }
    crosscheck_result_free(&res);
    return rc;
}
