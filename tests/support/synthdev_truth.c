/* synth-dev ground truth (synthdev_truth.h). */
#include "synthdev_truth.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

const char *const SYNTHDEV_CASES[SYNTHDEV_NCASES] = {
    "squat_jar_crane", "baluster_vase_e1.5_r1", "conical_tea_bowl_e5", "melon_vase_specular",
    "stem_cup_r2",     "pear_bottle_e3",        "brush_pot_lowcontrast_r1.5", "incense_bowl_sweep_e4",
};

int synthdev_dir(char *out, size_t len)
{
    const char *shared = getenv("CELADON_SHARED");
    snprintf(out, len, "%s/data/synth-dev", shared && *shared ? shared : "../shared");
    struct stat st;
    return stat(out, &st) == 0 && S_ISDIR(st.st_mode);
}

void synthdev_truth_free(synthdev_truth *t)
{
    free(t->z);
    free(t->r);
    memset(t, 0, sizeof *t);
}

int synthdev_truth_load(const char *dir, const char *name, synthdev_truth *t, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    char path[1024];
    snprintf(path, sizeof path, "%s/%s/camera.json", dir, name);
    json_error_t je;
    json_t *cam = json_load_file(path, 0, &je);
    if (!cam) {
        snprintf(err, errlen, "%s: %s", path, je.text);
        return -1;
    }
    t->elevation_deg = json_number_value(json_object_get(cam, "elevation_deg"));
    t->roll_deg = json_number_value(json_object_get(cam, "roll_deg"));
    t->focal_px = json_number_value(json_object_get(cam, "focal_px"));
    t->height = json_number_value(json_object_get(json_object_get(cam, "vessel"), "height"));
    json_decref(cam);
    snprintf(path, sizeof path, "%s/%s/profile.csv", dir, name);
    FILE *f = fopen(path, "r");
    if (!f || !(t->height > 0)) {
        if (f)
            fclose(f);
        snprintf(err, errlen, "%s: cannot read", path);
        return -1;
    }
    int cap = 4096;
    t->z = malloc(cap * sizeof *t->z);
    t->r = malloc(cap * sizeof *t->r);
    char line[256];
    double z, r;
    if (!fgets(line, sizeof line, f)) /* header */
        t->n = 0;
    while (t->z && t->r && fgets(line, sizeof line, f) && sscanf(line, "%lf,%lf", &z, &r) == 2) {
        if (t->n == cap) {
            cap *= 2;
            t->z = realloc(t->z, cap * sizeof *t->z);
            t->r = realloc(t->r, cap * sizeof *t->r);
            if (!t->z || !t->r)
                break;
        }
        /* The knot heights are listed again after the even samples: keep z increasing. */
        if (t->n > 0 && z <= t->z[t->n - 1])
            continue;
        t->z[t->n] = z;
        t->r[t->n++] = r;
    }
    fclose(f);
    if (t->n < 10) {
        synthdev_truth_free(t);
        snprintf(err, errlen, "%s: too few rows", path);
        return -1;
    }
    return 0;
}

/* Distance from (r, z) to the true profile polyline (r_i, z_i). */
static double distance_to_profile(const synthdev_truth *t, double r, double z)
{
    double best = INFINITY;
    for (int i = 0; i + 1 < t->n; i++) {
        double ax = t->r[i], ay = t->z[i], bx = t->r[i + 1] - ax, by = t->z[i + 1] - ay;
        double len2 = bx * bx + by * by, s = len2 > 0 ? ((r - ax) * bx + (z - ay) * by) / len2 : 0;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
        best = fmin(best, hypot(r - ax - s * bx, z - ay - s * by));
    }
    return best;
}

void synthdev_profile_error(const synthdev_truth *t, const bspline_t *curve, double lo, double hi, double *mean,
                            double *max)
{
    enum { CURVE_SAMPLES = 2000 };
    double u0 = curve->knots[0], u1 = curve->knots[curve->n_ctrl + curve->degree];
    double scale = t->height / bspline_eval(curve, u1).y, sum = 0, mx = 0;
    int m = 0;
    for (int i = 0; i < CURVE_SAMPLES; i++) {
        vec2 p = v2_scale(bspline_eval(curve, u0 + (u1 - u0) * i / (CURVE_SAMPLES - 1.0)), scale);
        if (p.y < lo * t->height || p.y > hi * t->height)
            continue;
        double e = distance_to_profile(t, p.x, p.y) / t->height;
        sum += e;
        mx = fmax(mx, e);
        m++;
    }
    *mean = m ? sum / m : INFINITY;
    *max = m ? mx : INFINITY;
}
