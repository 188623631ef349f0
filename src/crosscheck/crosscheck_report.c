/* The cross-check's outputs: report.json (jansson) and the convergence plot
 * (plot_loglog). Field meanings: include/celadon/crosscheck.h and
 * docs/crosscheck.md. */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "celadon/crosscheck.h"
#include "core/core.h"
#include "crosscheck/plot_loglog.h"

/* A real, or null for NaN/inf (JSON has neither). */
static json_t *real_or_null(double v) { return isfinite(v) ? json_real(v) : json_null(); }

static json_t *row_json(const crosscheck_row *r)
{
    char exr[32], png[32];
    snprintf(exr, sizeof exr, "mesh-%d.exr", r->segments);
    snprintf(png, sizeof png, "mesh-%d.png", r->segments);
    return json_pack("{s:i, s:s, s:s, s:f, s:o, s:o, s:I, s:I, s:o, s:o, s:o}", "n", r->segments, "image", exr,
                     "png", png, "seconds", r->seconds, "rel_mse", real_or_null(r->rel_mse), "mean_abs_diff",
                     real_or_null(r->mean_abs_diff), "coverage_pixels", (json_int_t)r->coverage_pixels,
                     "coverage_rays", (json_int_t)r->coverage_rays, "coverage_area_px", real_or_null(r->coverage_area),
                     "depth_rel_err", real_or_null(r->depth_rel_err), "normal_err_deg",
                     real_or_null(r->normal_err_deg));
}

/* report.json's root; NULL when the scene path is not UTF-8. */
static json_t *report_json(const crosscheck_result *res, const crosscheck_params *p)
{
    json_t *rows = json_array(), *fits = json_object();
    for (int i = 0; i < res->nrows; i++)
        json_array_append_new(rows, row_json(&res->rows[i]));
    for (int m = 0; m < CROSSCHECK_METRIC_COUNT; m++) {
        json_t *local = json_array();
        for (int i = 1; i < res->nrows; i++)
            json_array_append_new(local, real_or_null(crosscheck_local_slope(res->rows, i, m)));
        json_object_set_new(fits, crosscheck_metric_name(m),
                            json_pack("{s:o, s:o, s:i, s:o}", "slope", real_or_null(res->fits[m].slope), "intercept",
                                      real_or_null(res->fits[m].intercept), "points", res->fits[m].n_used,
                                      "local_slopes", local));
    }
    const crosscheck_stall *st = &res->stall;
    json_t *stall = st->found ? json_pack("{s:i, s:i, s:o, s:o}", "from", st->n_from, "to", st->n_to, "image_slope",
                                          real_or_null(st->image_slope), "depth_slope", real_or_null(st->depth_slope))
                              : json_null();
    return json_pack(
        "{s:i, s:s, s:i, s:i, s:i, s:I, s:i, s:i, s:I, s:{s:s, s:s, s:f}, s:s, s:o, s:i, s:o, s:o, s:o, s:s}",
        "version", 1, "scene", p->scene_path, "width", res->width, "height", res->height, "spp", res->spp, "seed",
        (json_int_t)res->seed, "geo_grid", res->geo_grid, "sor_shapes", res->sor_shapes, "sor_rays",
        (json_int_t)res->sor_rays, "analytic", "image", "analytic.exr", "png", "analytic.png", "seconds",
        res->analytic_seconds, "fitted_slope_metric", crosscheck_metric_name(CROSSCHECK_PRIMARY_METRIC),
        "fitted_slope", real_or_null(res->fits[CROSSCHECK_PRIMARY_METRIC].slope), "fit_from", res->fit_from, "fits",
        fits, "image_error_stall", stall, "segments", rows, "plot", "convergence.png");
}

enum { REPORT_FLAGS = JSON_INDENT(2) | JSON_REAL_PRECISION(10) };

char *crosscheck_report_text(const crosscheck_result *res, const crosscheck_params *p)
{
    json_t *root = report_json(res, p);
    char *text = root ? json_dumps(root, REPORT_FLAGS) : NULL;
    json_decref(root);
    return text;
}

int crosscheck_write_report(const crosscheck_result *res, const crosscheck_params *p, const char *path, char *err,
                            size_t errlen)
{
    json_t *root = report_json(res, p);
    if (!root) {
        snprintf(err, errlen, "cannot write %s: the scene path is not UTF-8", path);
        return -1;
    }
    int rc = json_write_file_atomic(path, root, REPORT_FLAGS, err, errlen);
    json_decref(root);
    return rc;
}

int crosscheck_write_plot(const crosscheck_result *res, const char *path, int plot_width, int plot_height,
                          char *err, size_t errlen)
{
    static const double colors[CROSSCHECK_METRIC_COUNT][3] = {
        {0.84, 0.15, 0.16}, {0.12, 0.47, 0.71}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74}, {1.00, 0.50, 0.05}};
    int n = res->nrows;
    double x[n > 0 ? n : 1], y[CROSSCHECK_METRIC_COUNT][n > 0 ? n : 1];
    double fx[CROSSCHECK_METRIC_COUNT][2], fy[CROSSCHECK_METRIC_COUNT][2], rx[2], ry[2];
    char labels[CROSSCHECK_METRIC_COUNT][96];
    plot_series s[2 * CROSSCHECK_METRIC_COUNT + 1];
    int ns = 0;
    for (int i = 0; i < n; i++)
        x[i] = res->rows[i].segments;
    for (int m = 0; m < CROSSCHECK_METRIC_COUNT; m++) {
        const crosscheck_fit *f = &res->fits[m];
        for (int i = 0; i < n; i++)
            y[m][i] = crosscheck_metric_value(&res->rows[i], m);
        /* The fitted line spans the points it was fitted to (N >= fit_from,
         * error > 0). */
        int first = -1, last = -1, in_range = 0;
        for (int i = 0; i < n; i++) {
            in_range += x[i] >= res->fit_from;
            if (x[i] >= res->fit_from && y[m][i] > 0.0 && isfinite(y[m][i]))
                last = i, first = first < 0 ? i : first;
        }
        char *lab = labels[m];
        size_t room = sizeof labels[m];
        int k = snprintf(lab, room, "%s: ", crosscheck_metric_name(m));
        if (f->n_used < 2)
            k += snprintf(lab + k, room - (size_t)k, "no fit");
        else
            k += snprintf(lab + k, room - (size_t)k, "slope %.2f", f->slope);
        if (f->n_used >= 2 && in_range < n)
            k += snprintf(lab + k, room - (size_t)k, " (N >= %d)", res->fit_from);
        if (f->n_used >= 2 && f->n_used < in_range)
            snprintf(lab + k, room - (size_t)k, " (%d of %d points > 0)", f->n_used, in_range);
        s[ns++] = (plot_series){labels[m], x, y[m], n, PLOT_POINTS, {colors[m][0], colors[m][1], colors[m][2]}};
        if (f->n_used >= 2) {
            for (int k = 0; k < 2; k++) {
                fx[m][k] = x[k ? last : first];
                fy[m][k] = pow(10.0, f->intercept + f->slope * log10(fx[m][k]));
            }
            s[ns++] = (plot_series){NULL, fx[m], fy[m], 2, PLOT_LINE, {colors[m][0], colors[m][1], colors[m][2]}};
        }
    }
    /* N^-2 over every N, through the primary metric's fitted line at the
     * first N fitted. */
    const crosscheck_fit *pf = &res->fits[CROSSCHECK_PRIMARY_METRIC];
    if (n > 0 && pf->n_used >= 2) {
        double n0 = res->fit_from, y0 = pow(10.0, pf->intercept + pf->slope * log10(n0));
        rx[0] = x[0], rx[1] = x[n - 1];
        ry[0] = y0 * pow(rx[0] / n0, -2.0), ry[1] = y0 * pow(rx[1] / n0, -2.0);
        s[ns++] = (plot_series){"reference N^-2", rx, ry, 2, PLOT_LINE | PLOT_DASHED, {0.35, 0.35, 0.35}};
    }
    char title[160];
    snprintf(title, sizeof title, "analytic vs. meshed SOR: error against segments N (%dx%d, %d spp)", res->width,
             res->height, res->spp);
    plot_loglog pl = {title, "angular segments N", "error (each metric in its own unit)", plot_width, plot_height, s,
                      ns};
    return plot_loglog_write_png(&pl, path, err, errlen);
}
