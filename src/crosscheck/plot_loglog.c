/* Log-log plots with cairo (plot_loglog.h). */
#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/core.h"
#include "crosscheck/plot_loglog.h"

typedef struct {
    double lo, hi; /* log10 range */
} axis_range;

/* The plot area in pixels and the data ranges it shows. */
typedef struct {
    double x0, y0, x1, y1; /* left, top, right, bottom */
    axis_range ax, ay;
} frame;

static int drawable(double x, double y) { return isfinite(x) && isfinite(y) && x > 0.0 && y > 0.0; }

static double px_x(const frame *f, double x) { return f->x0 + (log10(x) - f->ax.lo) / (f->ax.hi - f->ax.lo) * (f->x1 - f->x0); }
static double px_y(const frame *f, double y) { return f->y1 - (log10(y) - f->ay.lo) / (f->ay.hi - f->ay.lo) * (f->y1 - f->y0); }

static void pad(axis_range *r)
{
    double m = fmax(0.06 * (r->hi - r->lo), 0.1);
    r->lo -= m, r->hi += m;
}

/* "10", "100", "1e-3", ... for 10^k; "2", "0.05", "3e-4" for the minors. */
static void tick_label(double v, char *buf, size_t n)
{
    double a = fabs(log10(v));
    if (a < 4.0 - 1e-9)
        snprintf(buf, n, "%g", v);
    else
        snprintf(buf, n, "%.0e", v);
}

static void text_at(cairo_t *cr, const char *s, double x, double y, double align_x, double align_y)
{
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
    cairo_show_text(cr, s);
}

/* Ticks, grid and labels of one axis (vertical: the y axis). */
static void draw_axis(cairo_t *cr, const frame *f, int vertical)
{
    const axis_range *r = vertical ? &f->ay : &f->ax;
    int label_minors = r->hi - r->lo < 1.0;
    char buf[32];
    for (int k = (int)floor(r->lo); k <= (int)ceil(r->hi); k++)
        for (int m = 1; m <= 9; m++) {
            double v = m * pow(10.0, k), lv = log10(v);
            if (lv < r->lo || lv > r->hi)
                continue;
            double p = vertical ? px_y(f, v) : px_x(f, v), len = m == 1 ? 7.0 : 4.0;
            cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
            cairo_set_line_width(cr, m == 1 ? 1.0 : 0.5);
            if (vertical)
                cairo_move_to(cr, f->x0, p), cairo_line_to(cr, f->x1, p);
            else
                cairo_move_to(cr, p, f->y0), cairo_line_to(cr, p, f->y1);
            cairo_stroke(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_set_line_width(cr, 1.0);
            if (vertical)
                cairo_move_to(cr, f->x0, p), cairo_line_to(cr, f->x0 + len, p);
            else
                cairo_move_to(cr, p, f->y1), cairo_line_to(cr, p, f->y1 - len);
            cairo_stroke(cr);
            if (m == 1 || label_minors) {
                tick_label(v, buf, sizeof buf);
                if (vertical)
                    text_at(cr, buf, f->x0 - 6, p, 1.0, 0.5);
                else
                    text_at(cr, buf, p, f->y1 + 6, 0.5, 0.0);
            }
        }
}

static void set_series_line(cairo_t *cr, const plot_series *s)
{
    cairo_set_source_rgb(cr, s->rgb[0], s->rgb[1], s->rgb[2]);
    cairo_set_line_width(cr, 1.8);
    double dash[2] = {7.0, 4.0};
    cairo_set_dash(cr, dash, s->style & PLOT_DASHED ? 2 : 0, 0.0);
}

static void draw_series(cairo_t *cr, const frame *f, const plot_series *s)
{
    if (s->style & PLOT_LINE) {
        set_series_line(cr, s);
        int started = 0;
        for (int i = 0; i < s->n; i++)
            if (drawable(s->x[i], s->y[i])) {
                (started ? cairo_line_to : cairo_move_to)(cr, px_x(f, s->x[i]), px_y(f, s->y[i]));
                started = 1;
            }
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0.0);
    }
    if (s->style & PLOT_POINTS) {
        cairo_set_source_rgb(cr, s->rgb[0], s->rgb[1], s->rgb[2]);
        for (int i = 0; i < s->n; i++)
            if (drawable(s->x[i], s->y[i])) {
                cairo_arc(cr, px_x(f, s->x[i]), px_y(f, s->y[i]), 4.0, 0.0, 2.0 * M_PI);
                cairo_fill(cr);
            }
    }
}

static void draw_legend(cairo_t *cr, const frame *f, const plot_loglog *p)
{
    int rows = 0;
    double wmax = 0.0;
    for (int i = 0; i < p->nseries; i++)
        if (p->series[i].label) {
            cairo_text_extents_t e;
            cairo_text_extents(cr, p->series[i].label, &e);
            wmax = fmax(wmax, e.x_advance);
            rows++;
        }
    if (!rows)
        return;
    const double line_h = 17.0, sw = 26.0;
    double w = wmax + sw + 18.0, h = rows * line_h + 8.0, x = f->x1 - w - 8.0, y = f->y0 + 8.0;
    cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
    cairo_rectangle(cr, x, y, w, h);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    int row = 0;
    for (int i = 0; i < p->nseries; i++) {
        const plot_series *s = &p->series[i];
        if (!s->label)
            continue;
        double cy = y + 4.0 + (row++ + 0.5) * line_h;
        if (s->style & PLOT_LINE) {
            set_series_line(cr, s);
            cairo_move_to(cr, x + 6.0, cy), cairo_line_to(cr, x + 6.0 + sw, cy);
            cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0.0);
        }
        if (s->style & PLOT_POINTS) {
            cairo_set_source_rgb(cr, s->rgb[0], s->rgb[1], s->rgb[2]);
            cairo_arc(cr, x + 6.0 + sw / 2, cy, 4.0, 0.0, 2.0 * M_PI);
            cairo_fill(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        text_at(cr, s->label, x + sw + 12.0, cy, 0.0, 0.5);
    }
}

/* Data ranges over every drawable point; 0 when there is none. */
static int data_ranges(const plot_loglog *p, axis_range *ax, axis_range *ay)
{
    ax->lo = ay->lo = INFINITY, ax->hi = ay->hi = -INFINITY;
    for (int i = 0; i < p->nseries; i++)
        for (int j = 0; j < p->series[i].n; j++) {
            double x = p->series[i].x[j], y = p->series[i].y[j];
            if (!drawable(x, y))
                continue;
            ax->lo = fmin(ax->lo, log10(x)), ax->hi = fmax(ax->hi, log10(x));
            ay->lo = fmin(ay->lo, log10(y)), ay->hi = fmax(ay->hi, log10(y));
        }
    if (!isfinite(ax->lo))
        return 0;
    pad(ax), pad(ay);
    return 1;
}

static void draw(cairo_t *cr, const plot_loglog *p, const frame *f)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12.0);
    draw_axis(cr, f, 0);
    draw_axis(cr, f, 1);
    cairo_save(cr);
    cairo_rectangle(cr, f->x0, f->y0, f->x1 - f->x0, f->y1 - f->y0);
    cairo_clip(cr);
    for (int i = 0; i < p->nseries; i++)
        draw_series(cr, f, &p->series[i]);
    cairo_restore(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_rectangle(cr, f->x0, f->y0, f->x1 - f->x0, f->y1 - f->y0);
    cairo_stroke(cr);
    draw_legend(cr, f, p);
    cairo_set_font_size(cr, 14.0);
    if (p->xlabel)
        text_at(cr, p->xlabel, 0.5 * (f->x0 + f->x1), f->y1 + 26.0, 0.5, 0.0);
    if (p->title)
        text_at(cr, p->title, 0.5 * (f->x0 + f->x1), f->y0 - 12.0, 0.5, 1.0);
    if (p->ylabel) {
        cairo_save(cr);
        cairo_translate(cr, 18.0, 0.5 * (f->y0 + f->y1));
        cairo_rotate(cr, -M_PI / 2);
        text_at(cr, p->ylabel, 0.0, 0.0, 0.5, 0.5);
        cairo_restore(cr);
    }
}

int plot_loglog_write_png(const plot_loglog *p, const char *path, char *err, size_t errlen)
{
    frame f = {78.0, 40.0, p->width - 20.0, p->height - 52.0, {0, 0}, {0, 0}};
    if (p->width < 200 || p->height < 150 || p->width > 8192 || p->height > 8192) {
        snprintf(err, errlen, "cannot write %s: plot size %dx%d outside 200x150 to 8192x8192", path, p->width,
                 p->height);
        return -1;
    }
    if (!data_ranges(p, &f.ax, &f.ay)) {
        snprintf(err, errlen, "cannot write %s: no positive finite point to plot", path);
        return -1;
    }
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, p->width, p->height);
    cairo_t *cr = cairo_create(surf);
    draw(cr, p, &f);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    char tmp[4200];
    atomic_temp_name(path, tmp, sizeof tmp);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_write_to_png(surf, tmp);
    cairo_surface_destroy(surf);
    if (st != CAIRO_STATUS_SUCCESS || rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        atomic_temp_done(tmp);
        snprintf(err, errlen, "cannot write %s: %s", path,
                 st != CAIRO_STATUS_SUCCESS ? cairo_status_to_string(st) : strerror(e));
        return -1;
    }
    atomic_temp_done(tmp);
    return 0;
}
