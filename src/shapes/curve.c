/* What the curve shapes share (`linearcurve`, `bsplinecurve`): Mitsuba's
 * curve files, one control point "x y z radius" a line, an empty line
 * between curves; positions placed by to_world, radii as given (Mitsuba's
 * rule); traced by Embree's round curves (accel's ACCEL_KIND_CURVE_*). A
 * hit's normal points from the curve's centre at the hit's parameter to the
 * point (the swept sphere's normal); uv as Mitsuba's: u the angle around the
 * curve over 2 pi, v the segment's parameter plus its index, over the
 * number of segments. Curves do not emit light here. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "shapes/shape_impl.h"

typedef struct {
    accel_kind kind;
    float *points;      /* world x, y, z, radius */
    unsigned *segments; /* first control point of each */
    int n_points, n_segments;
} curve_data;

/* The centre of segment s at parameter u and its derivative by u. */
static void curve_centre(const curve_data *c, int s, double u, vec3 *p, vec3 *dp)
{
    const float *q = c->points + 4 * (size_t)c->segments[s];
    double w[4], dw[4];
    int n = 2;
    if (c->kind == ACCEL_KIND_CURVE_LINEAR) {
        w[0] = 1.0 - u, w[1] = u, dw[0] = -1.0, dw[1] = 1.0;
    } else { /* the uniform cubic B-spline basis */
        double v = 1.0 - u;
        w[0] = v * v * v / 6.0, w[1] = (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0;
        w[2] = (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, w[3] = u * u * u / 6.0;
        dw[0] = -v * v / 2.0, dw[1] = (3.0 * u * u - 4.0 * u) / 2.0;
        dw[2] = (-3.0 * u * u + 2.0 * u + 1.0) / 2.0, dw[3] = u * u / 2.0;
        n = 4;
    }
    *p = *dp = v3(0.0, 0.0, 0.0);
    for (int k = 0; k < n; k++) {
        vec3 x = v3(q[4 * k], q[4 * k + 1], q[4 * k + 2]);
        *p = v3_add(*p, v3_scale(x, w[k]));
        *dp = v3_add(*dp, v3_scale(x, dw[k]));
    }
}

static unsigned curve_add(const void *data, accel_t *acc, const transform4 *to_world, char *err, size_t errlen)
{
    (void)to_world; /* the points are in world space already */
    const curve_data *c = data;
    return accel_add_curves(acc, c->kind, c->points, c->n_points, c->segments, c->n_segments, err, errlen);
}

static void curve_local_hit(const void *data, const accel_hit *ah, shape_local_hit *h)
{
    const curve_data *c = data;
    int s = (int)ah->prim;
    double u = ah->param[0];
    vec3 centre, axis;
    curve_centre(c, s, u, &centre, &axis);
    vec3 r = v3_sub(ah->p, centre);
    h->t = ah->t;
    h->p = ah->p;
    h->n = v3_len(r) > 0.0 ? v3_norm(r) : ah->ng;
    frame3 f = frame3_from_normal(v3_len(axis) > 0.0 ? v3_norm(axis) : v3(0.0, 0.0, 1.0));
    double phi = atan2(v3_dot(f.t, h->n), v3_dot(f.s, h->n));
    h->uv = v2((phi < 0.0 ? phi + 2.0 * M_PI : phi) / (2.0 * M_PI), (u + s) / c->n_segments);
    h->part = 0;
    h->param[0] = u, h->param[1] = (double)s;
}

/* dp/du: around the curve, 2 pi times the distance from the centre; dp/dv:
 * along it, the centre's derivative times the segment count. */
static void curve_tangents(const void *data, const shape_local_hit *h, vec3 *dpdu, vec3 *dpdv)
{
    const curve_data *c = data;
    vec3 centre, axis;
    curve_centre(c, (int)h->param[1], h->param[0], &centre, &axis);
    vec3 r = v3_sub(h->p, centre);
    vec3 a = v3_len(axis) > 0.0 ? v3_norm(axis) : v3(0.0, 0.0, 1.0);
    *dpdu = v3_scale(v3_cross(a, r), 2.0 * M_PI);
    *dpdv = v3_scale(axis, c->n_segments);
}

static void curve_destroy(void *data)
{
    curve_data *c = data;
    free(c->points);
    free(c->segments);
    free(c);
}

static void curve_bounds(const void *data, vec3 *lo, vec3 *hi)
{
    const curve_data *c = data;
    *lo = v3(INFINITY, INFINITY, INFINITY), *hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int i = 0; i < c->n_points; i++) {
        const float *q = c->points + 4 * (size_t)i;
        double r = fabs(q[3]);
        *lo = v3(fmin(lo->x, q[0] - r), fmin(lo->y, q[1] - r), fmin(lo->z, q[2] - r));
        *hi = v3(fmax(hi->x, q[0] + r), fmax(hi->y, q[1] + r), fmax(hi->z, q[2] + r));
    }
}

static bool curve_flat_normal(const void *data, vec3 *n)
{
    (void)data, (void)n;
    return false;
}

/* Curves never emit (curve_shape_create refuses an area emitter), so they
 * are never sampled by area. */
static const shape_analytic_ops curve_ops = {curve_add,     curve_local_hit, NULL,         NULL,
                                             curve_destroy, curve_tangents,  curve_bounds, curve_flat_normal, NULL};

/* Appends the segments of the curve whose points are [first, end) (span: 2
 * or 4 points a segment): 0, or -1 when it has too few points. */
static int close_curve(curve_data *c, int first, int end, int span, int *cap)
{
    int n = end - first;
    if (n == 0)
        return 0;
    if (n < span)
        return -1;
    for (int i = first; i + span <= end; i++) {
        if (c->n_segments == *cap) {
            *cap = *cap ? 2 * *cap : 64;
            unsigned *s = realloc(c->segments, sizeof *s * (size_t)*cap);
            if (!s)
                return -1;
            c->segments = s;
        }
        c->segments[c->n_segments++] = (unsigned)i;
    }
    return 0;
}

/* Reads the curve file text into c, placing points by to_world: 0, or -1
 * with the problem in why. */
static int parse_curves(char *text, const transform4 *to_world, int span, curve_data *c, char *why, size_t whylen)
{
    int cap_pts = 0, cap_seg = 0, first = 0, line = 0;
    for (char *s = text, *next; s && *s; s = next) {
        next = strchr(s, '\n');
        if (next)
            *next++ = '\0';
        line++;
        double v[4];
        int got = sscanf(s, "%lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3]);
        if (got <= 0 && strspn(s, " \t\r") == strlen(s)) { /* an empty line ends a curve */
            if (close_curve(c, first, c->n_points, span, &cap_seg) != 0)
                goto short_curve;
            first = c->n_points;
            continue;
        }
        if (got != 4 || !isfinite(v[0] + v[1] + v[2] + v[3]) || v[3] < 0.0) {
            snprintf(why, whylen, "line %d is not four finite numbers x y z radius (radius >= 0)", line);
            return -1;
        }
        if (c->n_points == cap_pts) {
            cap_pts = cap_pts ? 2 * cap_pts : 256;
            float *p = realloc(c->points, 4 * sizeof *p * (size_t)cap_pts);
            if (!p) {
                snprintf(why, whylen, "out of memory");
                return -1;
            }
            c->points = p;
        }
        vec3 w = transform_point(to_world, v3(v[0], v[1], v[2]));
        float *q = c->points + 4 * (size_t)c->n_points++;
        q[0] = (float)w.x, q[1] = (float)w.y, q[2] = (float)w.z, q[3] = (float)v[3];
    }
    if (close_curve(c, first, c->n_points, span, &cap_seg) != 0)
        goto short_curve;
    if (c->n_segments == 0) {
        snprintf(why, whylen, "no curve in the file");
        return -1;
    }
    return 0;
short_curve:
    snprintf(why, whylen, "a curve ending before line %d has fewer than %d control points", line + 1, span);
    return -1;
}

int curve_shape_create(scene_obj *o, accel_kind kind, const transform4 *to_world, shape_t *sh, char *err,
                       size_t errlen)
{
    if (scene_obj_child(o, SCENE_EMITTER))
        return scene_obj_error(o, err, errlen, "a curve cannot emit light here (an area emitter needs a surface to sample)");
    const char *path = scene_obj_string(o, "filename", "");
    curve_data *c = calloc(1, sizeof *c);
    char *text = NULL, why[256];
    size_t len;
    if (!c)
        return scene_obj_error(o, err, errlen, "out of memory");
    c->kind = kind;
    if (input_read_all(path, INPUT_MAX_TEXT_BYTES, &text, &len, why, sizeof why) != 0 ||
        parse_curves(text, to_world, kind == ACCEL_KIND_CURVE_LINEAR ? 2 : 4, c, why, sizeof why) != 0) {
        free(text);
        curve_destroy(c);
        return scene_obj_error(o, err, errlen, "%s: %s", path, why);
    }
    free(text);
    sh->is_mesh = false;
    sh->ops = &curve_ops;
    sh->data = c;
    sh->to_world = transform_identity();
    return 0;
}
