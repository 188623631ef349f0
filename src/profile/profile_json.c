/* profile.json (its fields: docs/user-guide.md#profilejson; its frames:
 * docs/conventions.md) through jansson: writing, and reading with a one-line
 * reason for anything malformed. */
#include "celadon/profile.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/curve_domains.h"
#include "celadon/sor.h"
#include "core/core.h"

enum { PROFILE_VERSION = 1 };

static const char *const corner_names[CORNER_COUNT] = {"rim_left", "rim_right", "base_left", "base_right"};

/* ------------------------------------------------------------------ writing */

static json_t *pair(vec2 v) { return json_pack("[f, f]", v.x, v.y); }

static json_t *pairs(const vec2 *v, int n)
{
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++)
        if (json_array_append_new(a, pair(v[i])) != 0) { /* NULL from a non-finite value */
            json_decref(a);
            return NULL;
        }
    return a;
}

static json_t *reals(const double *v, int n)
{
    json_t *a = json_array();
    for (int i = 0; a && i < n; i++)
        if (json_array_append_new(a, json_real(v[i])) != 0) {
            json_decref(a);
            return NULL;
        }
    return a;
}

static json_t *corners_json(const profile_t *p)
{
    json_t *o = json_object();
    for (int k = 0; o && k < CORNER_COUNT; k++)
        if (json_object_set_new(o, corner_names[k], pair(p->corners[k])) != 0) {
            json_decref(o);
            return NULL;
        }
    return o;
}

/* "excluded" (always, possibly empty) and "quality" (when recorded). */
static int add_reconstruction_notes(json_t *root, const profile_t *p)
{
    json_t *ex = json_array();
    for (int i = 0; ex && i < p->n_excluded; i++) {
        const char *side = p->excluded[i].side < 0 ? "left" : (p->excluded[i].side > 0 ? "right" : "both");
        if (json_array_append_new(ex, json_pack("{s:s, s:[i, i], s:s, s:s}", "what", p->excluded[i].what, "rows",
                                                p->excluded[i].rows[0], p->excluded[i].rows[1], "side", side,
                                                "profile", p->excluded[i].profile)) != 0) {
            json_decref(ex);
            ex = NULL;
        }
    }
    if (!ex || json_object_set_new(root, "excluded", ex) != 0)
        return -1;
    if (!p->quality.present)
        return 0;
    json_t *border = json_array();
    static const char *edge[4] = {"top", "bottom", "left", "right"};
    for (int k = 0; border && k < 4; k++)
        if (p->quality.border_contact & (1u << k))
            json_array_append_new(border, json_string(edge[k]));
    json_t *q = json_pack("{s:b, s:f, s:f, s:f, s:o}", "passed", p->quality.passed, "hausdorff_px",
                          p->quality.hausdorff_px, "lr_disagreement", p->quality.lr_disagreement,
                          "excluded_fraction", p->quality.excluded_fraction, "border_contact", border);
    return q && json_object_set_new(root, "quality", q) == 0 ? 0 : -1;
}

static json_t *conic_json(const profile_conic *c)
{
    return json_pack("{s:o, s:[f, f], s:f, s:f, s:i, s:i}", "center_px", pair(c->center_px), "semi_axes_px",
                     c->semi_axes_px[0], c->semi_axes_px[1], "rms_px", c->rms_px, "max_px", c->max_px, "points",
                     c->points, "inliers", c->inliers);
}

static json_t *camera_json(const profile_camera *c)
{
    return json_pack("{s:s, s:f, s:f, s:f, s:o, s:s, s:{s:o, s:o}}", "method", c->method, "elevation_deg",
                     c->elevation_deg, "focal_px", c->focal_px, "roll_deg", c->roll_deg, "principal_point",
                     pair(c->principal_point), "note", c->note, "conics", "base", conic_json(&c->conics[0]), "rim",
                     conic_json(&c->conics[1]));
}

static json_t *meridian_json(const profile_t *p)
{
    return json_pack("{s:i, s:o, s:o, s:o}", "degree", p->meridian.degree, "knots",
                     reals(p->meridian.knots, bspline_n_knots(&p->meridian)), "control_points",
                     pairs(p->meridian.ctrl, p->meridian.n_ctrl), "domains",
                     reals(p->meridian_domains, p->n_meridian_domains));
}

/* Adds the perspective blocks that p has. Returns 0, or -1 when a value
 * is not finite. */
static int add_perspective(json_t *root, const profile_t *p)
{
    if (p->has_camera && json_object_set_new(root, "camera", camera_json(&p->camera)) != 0)
        return -1;
    if (p->has_meridian && json_object_set_new(root, "meridian", meridian_json(p)) != 0)
        return -1;
    return 0;
}

enum { PROFILE_JSON_FLAGS = JSON_INDENT(1) | JSON_REAL_PRECISION(17) };

/* profile.json's root; NULL with err (naming what) on failure. */
static json_t *profile_json(const profile_t *p, const char *what, char *err, size_t errlen)
{
    const char *bad = bspline_validate(&p->curve);
    if (!bad && p->has_meridian)
        bad = bspline_validate(&p->meridian);
    if (bad) {
        snprintf(err, errlen, "invalid B-spline: %s", bad);
        return NULL;
    }
    /* "o" steals a reference and fails on NULL: a non-finite number anywhere
     * (json_real refuses them) makes the whole pack fail. */
    char source[4 * 4096];
    json_t *root = json_pack(
        "{s:i, s:{s:s, s:i, s:i}, s:{s:o, s:o, s:f}, s:o, s:s, s:o, s:{s:i, s:o, s:o}, s:o, s:{s:f, s:f},"
        " s:{s:i, s:i, s:i}, s:{s:f, s:f, s:f, s:f}}",
        "version", PROFILE_VERSION,
        "source", "path", json_text(p->source_path, source, sizeof source), "width", p->source_width, "height", p->source_height,
        "axis", "origin", pair(p->axis_origin), "direction", pair(p->axis_direction), "tilt_deg", p->tilt_deg,
        "corners", corners_json(p),
        "side", p->side,
        "polyline", pairs(p->polyline, p->n_polyline),
        "bspline", "degree", p->curve.degree, "knots", reals(p->curve.knots, bspline_n_knots(&p->curve)),
        "control_points", pairs(p->curve.ctrl, p->curve.n_ctrl),
        "domains", reals(p->domains, p->n_domains),
        "error_px", "curve_to_polyline", p->err_curve_to_polyline, "polyline_to_curve", p->err_polyline_to_curve,
        "stats", "contour_points", p->contour_points, "control_points", p->curve.n_ctrl, "domains", p->n_domains,
        "timings_ms", "image_processing", p->ms_image_processing, "bspline", p->ms_bspline, "texture",
        p->ms_texture, "mesh", p->ms_mesh);
    if (root && (add_reconstruction_notes(root, p) != 0 || add_perspective(root, p) != 0)) {
        json_decref(root);
        root = NULL;
    }
    if (!root)
        snprintf(err, errlen, "cannot write %s: a value is not finite or a string is not UTF-8", what);
    return root;
}

int profile_write_json(const char *path, const profile_t *p, char *err, size_t errlen)
{
    json_t *root = profile_json(p, path, err, errlen);
    if (!root)
        return -1;
    int rc = json_write_file_atomic(path, root, PROFILE_JSON_FLAGS, err, errlen);
    json_decref(root);
    return rc;
}

char *profile_json_text(const profile_t *p, char *err, size_t errlen)
{
    json_t *root = profile_json(p, "the profile", err, errlen);
    char *text = root ? json_dumps(root, PROFILE_JSON_FLAGS) : NULL;
    if (root && !text)
        snprintf(err, errlen, "out of memory");
    json_decref(root);
    return text;
}

/* ------------------------------------------------------------------ reading */

typedef struct {
    char *err;
    size_t errlen;
} reader;

static int fail(reader *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->err, r->errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* The member key of obj (named path in messages), which must exist. */
static json_t *member(reader *r, json_t *obj, const char *key, const char *path)
{
    json_t *v = json_object_get(obj, key);
    if (!v)
        fail(r, "missing field '%s'", path);
    return v;
}

static int as_number(reader *r, json_t *v, const char *path, double *out)
{
    if (!json_is_number(v))
        return fail(r, "'%s' must be a number", path);
    *out = json_number_value(v);
    if (!isfinite(*out))
        return fail(r, "'%s' is not finite", path);
    return 0;
}

static int get_number(reader *r, json_t *obj, const char *key, const char *path, double *out)
{
    json_t *v = member(r, obj, key, path);
    return v ? as_number(r, v, path, out) : -1;
}

static int get_count(reader *r, json_t *obj, const char *key, const char *path, int *out)
{
    json_t *v = member(r, obj, key, path);
    if (!v)
        return -1;
    if (!json_is_integer(v) || json_integer_value(v) < 0 || json_integer_value(v) > 2147483647)
        return fail(r, "'%s' must be a non-negative integer", path);
    *out = (int)json_integer_value(v);
    return 0;
}

static int as_pair(reader *r, json_t *v, const char *path, vec2 *out)
{
    if (!json_is_array(v) || json_array_size(v) != 2)
        return fail(r, "'%s' must be an array of 2 numbers", path);
    return as_number(r, json_array_get(v, 0), path, &out->x) || as_number(r, json_array_get(v, 1), path, &out->y)
               ? -1
               : 0;
}

static int get_pair(reader *r, json_t *obj, const char *key, const char *path, vec2 *out)
{
    json_t *v = member(r, obj, key, path);
    return v ? as_pair(r, v, path, out) : -1;
}

static json_t *get_object(reader *r, json_t *obj, const char *key)
{
    json_t *v = member(r, obj, key, key);
    if (v && !json_is_object(v)) {
        fail(r, "'%s' must be an object", key);
        return NULL;
    }
    return v;
}

/* An array of min_n to max_n elements; *n receives its size. */
static json_t *get_array(reader *r, json_t *obj, const char *key, const char *path, size_t min_n, size_t max_n,
                         int *n)
{
    json_t *v = member(r, obj, key, path);
    if (!v)
        return NULL;
    if (!json_is_array(v)) {
        fail(r, "'%s' must be an array", path);
        return NULL;
    }
    if (json_array_size(v) < min_n) {
        fail(r, "'%s' must have at least %zu elements", path, min_n);
        return NULL;
    }
    if (json_array_size(v) > max_n) {
        fail(r, "'%s' has %zu elements, more than the %zu a profile may have", path, json_array_size(v), max_n);
        return NULL;
    }
    *n = (int)json_array_size(v);
    return v;
}

static int read_pairs(reader *r, json_t *a, const char *path, vec2 *out)
{
    char elem[64];
    for (size_t i = 0; i < json_array_size(a); i++) {
        snprintf(elem, sizeof elem, "%s[%zu]", path, i);
        if (as_pair(r, json_array_get(a, i), elem, &out[i]) != 0)
            return -1;
    }
    return 0;
}

static int read_reals(reader *r, json_t *a, const char *path, double *out)
{
    char elem[64];
    for (size_t i = 0; i < json_array_size(a); i++) {
        snprintf(elem, sizeof elem, "%s[%zu]", path, i);
        if (as_number(r, json_array_get(a, i), elem, &out[i]) != 0)
            return -1;
    }
    return 0;
}

/* The photo and the frame the profile was measured in: optional (a
 * researcher's own profile has none of it), checked when present. */
static int read_header(reader *r, json_t *root, profile_t *p)
{
    json_t *v = member(r, root, "version", "version");
    if (!v)
        return -1;
    if (!json_is_integer(v) || json_integer_value(v) != PROFILE_VERSION)
        return fail(r, "unsupported version (this reader knows version %d)", PROFILE_VERSION);

    if (json_object_get(root, "source")) {
        json_t *src = get_object(r, root, "source");
        if (!src)
            return -1;
        json_t *path = member(r, src, "path", "source.path");
        if (!path)
            return -1;
        if (!json_is_string(path) || json_string_length(path) >= sizeof p->source_path)
            return fail(r, "'source.path' must be a string shorter than %zu bytes", sizeof p->source_path);
        snprintf(p->source_path, sizeof p->source_path, "%s", json_string_value(path));
        if (get_count(r, src, "width", "source.width", &p->source_width) ||
            get_count(r, src, "height", "source.height", &p->source_height))
            return -1;
    }

    p->axis_direction = v2(0, -1);
    if (json_object_get(root, "axis")) {
        json_t *axis = get_object(r, root, "axis");
        if (!axis || get_pair(r, axis, "origin", "axis.origin", &p->axis_origin) ||
            get_pair(r, axis, "direction", "axis.direction", &p->axis_direction) ||
            get_number(r, axis, "tilt_deg", "axis.tilt_deg", &p->tilt_deg))
            return -1;
        if (fabs(v2_len(p->axis_direction) - 1.0) > 1e-6)
            return fail(r, "'axis.direction' must be a unit vector");
    }

    if (json_object_get(root, "corners")) {
        json_t *corners = get_object(r, root, "corners");
        if (!corners)
            return -1;
        for (int k = 0; k < CORNER_COUNT; k++) {
            char name[32];
            snprintf(name, sizeof name, "corners.%s", corner_names[k]);
            if (get_pair(r, corners, corner_names[k], name, &p->corners[k]) != 0)
                return -1;
        }
    }

    snprintf(p->side, sizeof p->side, "right");
    json_t *side = json_object_get(root, "side");
    if (side) {
        if (!json_is_string(side) ||
            (strcmp(json_string_value(side), "left") && strcmp(json_string_value(side), "right")))
            return fail(r, "'side' must be \"left\" or \"right\"");
        snprintf(p->side, sizeof p->side, "%s", json_string_value(side));
    }
    return 0;
}

/* A clamped cubic from 0 to 1: obj's degree, knots and control_points
 * (named path.* in messages). */
static int read_cubic(reader *r, json_t *obj, const char *path, bspline_t *c)
{
    char key[64], key2[64];
    snprintf(key, sizeof key, "%s.degree", path);
    json_t *deg = member(r, obj, "degree", key);
    if (!deg)
        return -1;
    if (!json_is_integer(deg) || json_integer_value(deg) != 3)
        return fail(r, "'%s' must be 3", key);
    int nk, nc;
    snprintf(key, sizeof key, "%s.knots", path);
    snprintf(key2, sizeof key2, "%s.control_points", path);
    json_t *knots = get_array(r, obj, "knots", key, 8, PROFILE_MAX_POINTS + 4, &nk);
    json_t *ctrl = knots ? get_array(r, obj, "control_points", key2, 4, PROFILE_MAX_POINTS, &nc) : NULL;
    if (!ctrl)
        return -1;
    if (nk != nc + 4)
        return fail(r, "'%s' has %d values; %d control points need %d", key, nk, nc, nc + 4);
    if (bspline_init(c, 3, nc) != 0)
        return fail(r, "out of memory");
    if (read_reals(r, knots, key, c->knots) || read_pairs(r, ctrl, key2, c->ctrl))
        return -1;
    const char *bad = bspline_validate(c);
    if (bad)
        return fail(r, "invalid B-spline: %s", bad);
    if (c->knots[0] != 0.0 || c->knots[nk - 1] != 1.0)
        return fail(r, "invalid B-spline: the parameter must run from 0 to 1");
    bad = sor_profile_check(c);
    if (bad)
        return fail(r, "the %s cannot be revolved: %s", strcmp(path, "bspline") ? path : "profile", bad);
    return 0;
}

/* Curvature domains: increasing values from 0 to 1, obj's member key. */
static int read_domains(reader *r, json_t *obj, const char *key, const char *path, double **dom, int *n)
{
    json_t *a = get_array(r, obj, key, path, 2, PROFILE_MAX_POINTS, n);
    if (!a)
        return -1;
    *dom = malloc((size_t)*n * sizeof **dom);
    if (!*dom)
        return fail(r, "out of memory");
    if (read_reals(r, a, path, *dom) != 0)
        return -1;
    if ((*dom)[0] != 0.0 || (*dom)[*n - 1] != 1.0)
        return fail(r, "'%s' must start at 0 and end at 1", path);
    for (int i = 1; i < *n; i++)
        if (!((*dom)[i] > (*dom)[i - 1]))
            return fail(r, "'%s' must be strictly increasing (%s[%d] = %.17g)", path, path, i, (*dom)[i]);
    return 0;
}

static int read_curve(reader *r, json_t *root, profile_t *p)
{
    int n;
    if (json_object_get(root, "polyline")) { /* the measured profile: optional */
        json_t *poly = get_array(r, root, "polyline", "polyline", 2, PROFILE_MAX_POINTS, &n);
        if (!poly)
            return -1;
        p->polyline = malloc((size_t)n * sizeof *p->polyline);
        if (!p->polyline)
            return fail(r, "out of memory");
        p->n_polyline = n;
        if (read_pairs(r, poly, "polyline", p->polyline) != 0)
            return -1;
    }

    json_t *bs = get_object(r, root, "bspline");
    if (!bs || read_cubic(r, bs, "bspline", &p->curve) != 0)
        return -1;
    if (!json_object_get(root, "domains")) /* computed as the reconstruction computes them */
        return curve_domains_by_curvature_variation(&p->curve, PROFILE_DOMAIN_TOL_PX, PROFILE_DOMAIN_TOL_DEG,
                                                    &p->domains, &p->n_domains) != 0
                   ? fail(r, "cannot compute the curvature domains of the B-spline")
                   : 0;
    return read_domains(r, root, "domains", "domains", &p->domains, &p->n_domains);
}

/* The reconstruction's report: optional, checked when present; nothing
 * reads it back but the tests and people. */
static int read_report(reader *r, json_t *root, profile_t *p)
{
    if (json_object_get(root, "error_px")) {
        json_t *e = get_object(r, root, "error_px");
        if (!e ||
            get_number(r, e, "curve_to_polyline", "error_px.curve_to_polyline", &p->err_curve_to_polyline) ||
            get_number(r, e, "polyline_to_curve", "error_px.polyline_to_curve", &p->err_polyline_to_curve))
            return -1;
        if (p->err_curve_to_polyline < 0.0 || p->err_polyline_to_curve < 0.0)
            return fail(r, "'error_px' distances must not be negative");
    }
    if (json_object_get(root, "stats")) {
        json_t *st = get_object(r, root, "stats");
        int ctrl, dom;
        if (!st || get_count(r, st, "contour_points", "stats.contour_points", &p->contour_points) ||
            get_count(r, st, "control_points", "stats.control_points", &ctrl) ||
            get_count(r, st, "domains", "stats.domains", &dom))
            return -1;
    }
    if (json_object_get(root, "timings_ms")) {
        json_t *t = get_object(r, root, "timings_ms");
        if (!t || get_number(r, t, "image_processing", "timings_ms.image_processing", &p->ms_image_processing) ||
            get_number(r, t, "bspline", "timings_ms.bspline", &p->ms_bspline) ||
            get_number(r, t, "texture", "timings_ms.texture", &p->ms_texture) ||
            get_number(r, t, "mesh", "timings_ms.mesh", &p->ms_mesh))
            return -1;
    }
    return 0;
}

static int get_string(reader *r, json_t *obj, const char *key, const char *path, char *out, size_t len)
{
    json_t *v = member(r, obj, key, path);
    if (!v)
        return -1;
    if (!json_is_string(v) || json_string_length(v) >= len)
        return fail(r, "'%s' must be a string shorter than %zu bytes", path, len);
    snprintf(out, len, "%s", json_string_value(v));
    return 0;
}

static int read_conic(reader *r, json_t *conics, const char *name, profile_conic *c)
{
    char path[64], key[96];
    snprintf(path, sizeof path, "camera.conics.%s", name);
    json_t *o = member(r, conics, name, path);
    if (!o)
        return -1;
    if (!json_is_object(o))
        return fail(r, "'%s' must be an object", path);
    vec2 axes;
#define KEY(k) (snprintf(key, sizeof key, "%s.%s", path, k), key)
    if (get_pair(r, o, "center_px", KEY("center_px"), &c->center_px) ||
        get_pair(r, o, "semi_axes_px", KEY("semi_axes_px"), &axes) ||
        get_number(r, o, "rms_px", KEY("rms_px"), &c->rms_px) || get_number(r, o, "max_px", KEY("max_px"), &c->max_px) ||
        get_count(r, o, "points", KEY("points"), &c->points) || get_count(r, o, "inliers", KEY("inliers"), &c->inliers))
        return -1;
#undef KEY
    c->semi_axes_px[0] = axes.x, c->semi_axes_px[1] = axes.y;
    if (axes.x < 0 || axes.y < 0 || c->rms_px < 0 || c->max_px < 0 || c->inliers > c->points)
        return fail(r, "'%s' has a negative size or more inliers than points", path);
    return 0;
}

static int read_camera(reader *r, json_t *cam, profile_camera *c)
{
    if (!json_is_object(cam))
        return fail(r, "'camera' must be an object");
    static const char *const methods[] = {"ellipses", "exif", "flag", "orthographic"};
    if (get_string(r, cam, "method", "camera.method", c->method, sizeof c->method) ||
        get_number(r, cam, "elevation_deg", "camera.elevation_deg", &c->elevation_deg) ||
        get_number(r, cam, "focal_px", "camera.focal_px", &c->focal_px) ||
        get_number(r, cam, "roll_deg", "camera.roll_deg", &c->roll_deg) ||
        get_pair(r, cam, "principal_point", "camera.principal_point", &c->principal_point) ||
        get_string(r, cam, "note", "camera.note", c->note, sizeof c->note))
        return -1;
    int known = 0;
    for (int k = 0; k < 4; k++)
        known |= !strcmp(c->method, methods[k]);
    if (!known)
        return fail(r, "'camera.method' must be \"ellipses\", \"exif\", \"flag\" or \"orthographic\"");
    if (c->focal_px < 0 || (c->focal_px == 0) != !strcmp(c->method, "orthographic"))
        return fail(r, "'camera.focal_px' must be positive, and 0 exactly for the orthographic model");
    if (fabs(c->elevation_deg) > 90)
        return fail(r, "'camera.elevation_deg' must be within -90..90");
    json_t *conics = member(r, cam, "conics", "camera.conics");
    if (!conics)
        return -1;
    if (!json_is_object(conics))
        return fail(r, "'camera.conics' must be an object");
    return read_conic(r, conics, "base", &c->conics[0]) || read_conic(r, conics, "rim", &c->conics[1]) ? -1 : 0;
}

/* The meridian: a clamped cubic whose control polygon starts at h = 0 and
 * ends at h = 1 (both exact) with r >= 0, and its domains. */
static int read_meridian(reader *r, json_t *m, profile_t *p)
{
    if (!json_is_object(m))
        return fail(r, "'meridian' must be an object");
    if (read_cubic(r, m, "meridian", &p->meridian) != 0)
        return -1;
    const bspline_t *c = &p->meridian;
    if (c->ctrl[0].y != 0.0 || c->ctrl[c->n_ctrl - 1].y != 1.0)
        return fail(r, "'meridian' must run from h = 0 (the base) to h = 1 (the rim)");
    for (int i = 0; i < c->n_ctrl; i++)
        if (c->ctrl[i].x < 0)
            return fail(r, "'meridian.control_points[%d]' has a negative radius", i);
    return read_domains(r, m, "domains", "meridian.domains", &p->meridian_domains, &p->n_meridian_domains);
}

/* The optional blocks of a perspective reconstruction. */
static int read_perspective(reader *r, json_t *root, profile_t *p)
{
    json_t *cam = json_object_get(root, "camera"), *mer = json_object_get(root, "meridian");
    if (cam && read_camera(r, cam, &p->camera) != 0)
        return -1;
    p->has_camera = cam != NULL;
    if (mer && read_meridian(r, mer, p) != 0)
        return -1;
    p->has_meridian = mer != NULL;
    return 0;
}

const bspline_t *profile_shape(const profile_t *p, const double **domains, int *n_domains)
{
    *domains = p->has_meridian ? p->meridian_domains : p->domains;
    *n_domains = p->has_meridian ? p->n_meridian_domains : p->n_domains;
    return p->has_meridian ? &p->meridian : &p->curve;
}

int profile_read_json(const char *path, profile_t *p, char *err, size_t errlen)
{
    memset(p, 0, sizeof *p);
    reader r = {err, errlen};
    char *text;
    size_t len;
    if (input_read_all(path, INPUT_MAX_TEXT_BYTES, &text, &len, err, errlen) != 0)
        return -1;
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &jerr);
    free(text);
    if (!root)
        return fail(&r, "not valid JSON (line %d): %s", jerr.line, jerr.text);
    int rc = json_is_object(root) ? 0 : fail(&r, "the top level must be an object");
    if (rc == 0)
        rc = read_header(&r, root, p) || read_curve(&r, root, p) || read_report(&r, root, p) ||
                     read_perspective(&r, root, p)
                 ? -1
                 : 0;
    json_decref(root);
    if (rc != 0)
        profile_free(p);
    return rc;
}

void profile_free(profile_t *p)
{
    free(p->polyline);
    free(p->domains);
    free(p->meridian_domains);
    bspline_free(&p->curve);
    bspline_free(&p->meridian);
    p->polyline = NULL;
    p->domains = p->meridian_domains = NULL;
    p->n_polyline = p->n_domains = p->n_meridian_domains = 0;
    p->has_meridian = 0;
}
