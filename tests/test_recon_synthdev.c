/* recon_extract on the rendered synth-dev photographs (perspective POV-Ray
 * renders with exactly known outlines): the sub-pixel outline of the chosen
 * side against silhouette_<side>.csv, the axis against camera.json. Skips when
 * the data set is absent, fails then under $CELADON_REQUIRE_DATA (CI). Data:
 * $CELADON_SHARED/data/synth-dev, else ../shared/data/synth-dev relative to
 * the repository root (support/shared_data.h). */
#include <criterion/criterion.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "celadon/recon.h"
#include "support/shared_data.h"
#include "support/test_build.h"

/* Targets, every photo: outline mean <= 0.25 px and max <= 1.5 px on the
 * chosen side, 5 px or more from the corners; axis direction within 0.1 deg;
 * all four corners within 12 px (perspective rounds them into ellipse arcs). */
static const double MEAN_PX = 0.25, MAX_PX = 1.5, AXIS_DEG = 0.1, CORNER_PX = 12;

static const char *const CASES[] = {
    "squat_jar_crane", "baluster_vase_e1.5_r1", "conical_tea_bowl_e5", "melon_vase_specular",
    "stem_cup_r2",     "pear_bottle_e3",        "brush_pot_lowcontrast_r1.5", "incense_bowl_sweep_e4",
};
enum { NCASES = sizeof CASES / sizeof CASES[0] };


/* silhouette csv: y_px,x_px,z_source per row; returns the row count. */
static int read_outline(const char *path, double **ys, double **xs)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    int n = 0, cap = 2048;
    *ys = malloc(cap * sizeof **ys);
    *xs = malloc(cap * sizeof **xs);
    char line[256];
    if (!fgets(line, sizeof line, f))
        n = 0;
    double y, x, z;
    while (fgets(line, sizeof line, f) && sscanf(line, "%lf,%lf,%lf", &y, &x, &z) == 3) {
        if (n == cap) {
            cap *= 2;
            *ys = realloc(*ys, cap * sizeof **ys);
            *xs = realloc(*xs, cap * sizeof **xs);
        }
        (*ys)[n] = y;
        (*xs)[n++] = x;
    }
    fclose(f);
    return n;
}

static vec2 json_pt(json_t *obj, const char *a, const char *b)
{
    json_t *p = json_object_get(json_object_get(obj, a), b);
    return v2(json_real_value(json_array_get(p, 0)), json_real_value(json_array_get(p, 1)));
}

typedef struct {
    double mean_err, max_err, axis_deg, axis_offset, corner_err;
    int side, n;
    double ms;
} outcome;

/* Runs one photo and measures it against the truth. Returns 0 when recon_extract failed. */
static int evaluate(const char *dir, const char *name, const char *file, outcome *o)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/%s/%s", dir, name, file);
    image_t img;
    cr_assert_eq(image_read(path, &img, err, sizeof err), 0, "%s: %s", path, err);
    recon_options opt = {-1, RECON_SIDE_AUTO, NULL};
    recon_result res;
    recon_status st = recon_extract(&img, &opt, &res, err, sizeof err);
    image_free(&img);
    if (st != RECON_OK) {
        cr_expect_eq(st, RECON_OK, "%s: %s", path, err);
        return 0;
    }
    o->ms = res.ms_image_processing;

    snprintf(path, sizeof path, "%s/%s/camera.json", dir, name);
    json_error_t je;
    json_t *cam = json_load_file(path, 0, &je);
    cr_assert_not_null(cam, "%s: %s", path, je.text);
    vec2 base = json_pt(cam, "axis_px", "base_center"), rim = json_pt(cam, "axis_px", "rim_center");
    int s = res.side_used == RECON_SIDE_RIGHT;
    const char *sname = s ? "right" : "left";
    char key[32];
    snprintf(key, sizeof key, "rim_%s", sname);
    vec2 crim = json_pt(cam, "corners_px", key);
    snprintf(key, sizeof key, "base_%s", sname);
    vec2 cbase = json_pt(cam, "corners_px", key);
    /* Corners: the worst of the four. */
    const char *cn[CORNER_COUNT] = {"rim_left", "rim_right", "base_left", "base_right"};
    o->corner_err = 0;
    for (int q = 0; q < CORNER_COUNT; q++)
        o->corner_err = fmax(o->corner_err, v2_len(v2_sub(res.corners[q], json_pt(cam, "corners_px", cn[q]))));
    json_decref(cam);

    vec2 td = v2_norm(v2_sub(rim, base));
    o->axis_deg = acos(fmin(1.0, v2_dot(td, res.axis_direction))) * 180 / M_PI;
    vec2 rn = v2(-res.axis_direction.y, res.axis_direction.x);
    o->axis_offset = fabs(v2_dot(v2_sub(base, res.axis_origin), rn));

    snprintf(path, sizeof path, "%s/%s/silhouette_%s.csv", dir, name, sname);
    double *ys, *xs;
    int nr = read_outline(path, &ys, &xs);
    cr_assert_gt(nr, 10, "%s", path);
    /* Normal distance to the true outline, on rows 5 px or more from the corners. */
    const double margin = 5;
    double sum = 0, mx = 0;
    int cnt = 0;
    for (int k = 0; k < res.n_silhouette[s]; k++) {
        vec2 p = res.silhouette[s][k];
        if (p.y < crim.y + margin || p.y > cbase.y - margin)
            continue;
        int r = (int)floor(p.y - ys[0] + 0.5);
        if (r < 1 || r >= nr - 1 || fabs(ys[r] - p.y) > 1e-6)
            continue;
        double slope = 0.5 * (xs[r + 1] - xs[r - 1]);
        double e = fabs(p.x - xs[r]) / sqrt(1 + slope * slope);
        sum += e;
        mx = fmax(mx, e);
        cnt++;
    }
    free(ys);
    free(xs);
    o->side = s;
    o->n = cnt;
    o->mean_err = cnt ? sum / cnt : INFINITY;
    o->max_err = mx;
    recon_result_free(&res);
    return 1;
}

/* Every photo in the optimised build; the sanitized one takes every other
 * photo from `first`, its PNG and JPEG runs together each photo once
 * (support/test_build.h). */
static void run_all(const char *file, int first)
{
    char dir[900];
    shared_data_path(dir, sizeof dir, "data/synth-dev");
    shared_data_require(dir);
    int step = test_build_case_step(2);
    for (int c = step > 1 ? first : 0; c < NCASES; c += step) {
        const char *name = CASES[c];
        outcome o;
        if (!evaluate(dir, name, file, &o))
            continue;
        cr_log_info("%-28s %s side %-5s rows %4d  outline mean %.3f max %.3f px  axis %.3f deg off %.2f px  "
                    "corners <= %.2f px  %.1f ms",
                    name, file, o.side ? "right" : "left", o.n, o.mean_err, o.max_err, o.axis_deg, o.axis_offset,
                    o.corner_err, o.ms);
        cr_expect_gt(o.n, 100, "%s/%s: %d outline rows compared", name, file, o.n);
        cr_expect_leq(o.mean_err, MEAN_PX, "%s/%s: outline mean %.3f px", name, file, o.mean_err);
        cr_expect_leq(o.max_err, MAX_PX, "%s/%s: outline max %.3f px", name, file, o.max_err);
        cr_expect_leq(o.axis_deg, AXIS_DEG, "%s/%s: axis %.3f deg", name, file, o.axis_deg);
        cr_expect_leq(o.corner_err, CORNER_PX, "%s/%s: a corner %.1f px off", name, file, o.corner_err);
    }
}

Test(recon_synthdev, png_outline_and_axis, .timeout = 120) { run_all("photo.png", 0); }
Test(recon_synthdev, jpeg_outline_and_axis, .timeout = 120) { run_all("photo.jpg", 1); }
