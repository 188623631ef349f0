/* Flat silhouettes that are no surface of revolution; see
 * drawn_silhouettes.h. */
#include "drawn_silhouettes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "synth_profile.h"

static int in_box(double x, double y, double x0, double x1, double y0, double y1)
{
    return x >= x0 && x <= x1 && y >= y0 && y <= y1;
}

/* Inside the regular five-pointed star of unit height, one point up: the
 * ten-vertex polygon by the crossing rule. */
static int in_star(double x, double y)
{
    const double R = 1 / (1 + cos(M_PI / 5)), r = R * 0.381966, cy = R * cos(M_PI / 5);
    double px[10], py[10];
    for (int k = 0; k < 10; k++) {
        double a = M_PI / 2 + k * M_PI / 5, rad = k % 2 ? r : R;
        px[k] = rad * cos(a);
        py[k] = cy + rad * sin(a);
    }
    int inside = 0;
    for (int i = 0, j = 9; i < 10; j = i++)
        if ((py[i] > y) != (py[j] > y) && x < px[i] + (y - py[i]) * (px[j] - px[i]) / (py[j] - py[i]))
            inside = !inside;
    return inside;
}

/* A maebyeong of height hgt standing at (cx, 0). */
static int in_maebyeong(double x, double y, double cx, double hgt)
{
    return y >= 0 && y <= hgt && fabs(x - cx) < hgt * synth_profile_radius(SYNTH_PROFILE_MAEBYEONG, y / hgt);
}

/* rm: the maebyeong's largest radius; jx: where the jar beside it stands. */
static int inside(drawn_silhouette s, double x, double y, double rm, double jx)
{
    switch (s) {
    case DRAWN_STAR:
        return in_star(x, y);
    case DRAWN_L:
        return in_box(x, y, -0.1, 0.1, 0, 1) || in_box(x, y, -0.1, 0.5, 0, 0.2);
    case DRAWN_TWIN_VESSELS: /* overlapping by 2% of the height */
        return in_maebyeong(x, y, -(rm - 0.01), 1) || in_maebyeong(x, y, rm - 0.01, 1);
    case DRAWN_VESSEL_AND_JAR:
        return in_maebyeong(x, y, 0, 1) ||
               (y >= 0 && y <= 0.5 && fabs(x - jx) < 0.5 * synth_profile_radius(SYNTH_PROFILE_JAR, 2 * y));
    case DRAWN_PERSON:
        return hypot(x, y - 0.91) < 0.09 || in_box(x, y, -0.04, 0.04, 0.78, 0.84) ||
               in_box(x, y, -0.2, 0.2, 0.74, 0.8) || in_box(x, y, -0.13, 0.13, 0.46, 0.8) ||
               in_box(fabs(x), y, 0.15, 0.2, 0.4, 0.8) || in_box(fabs(x), y, 0.02, 0.11, 0, 0.48);
    case DRAWN_CHAIR_FRONT:
        return in_box(x, y, -0.28, 0.28, 0.52, 1) || in_box(x, y, -0.32, 0.32, 0.45, 0.53) ||
               in_box(fabs(x), y, 0.24, 0.3, 0, 0.46);
    case DRAWN_CHAIR_SIDE:
        return in_box(x, y, 0.2, 0.28, 0.45, 1) || in_box(x, y, -0.28, 0.28, 0.45, 0.53) ||
               in_box(fabs(x), y, 0.22, 0.28, 0, 0.46);
    default:
        return 0;
    }
}

const char *drawn_silhouette_name(drawn_silhouette s)
{
    static const char *const names[DRAWN_SILHOUETTE_COUNT] = {
        "star", "L", "two touching vessels", "vessel and jar touching", "person", "chair (front)", "chair (side)"};
    return s >= 0 && s < DRAWN_SILHOUETTE_COUNT ? names[s] : NULL;
}

int drawn_silhouette_draw(drawn_silhouette s, int w, int h, image_t *img)
{
    *img = image_alloc(w, h, 3);
    if (!img->data)
        return -1;
    const double scale = 0.7 * h, y_base = 0.85 * h; /* image rows of the shape's y = 0 */
    const float fg[3] = {0.25f, 0.42f, 0.33f}, bg[3] = {0.94f, 0.94f, 0.93f};
    const double rm = synth_profile_max_radius(SYNTH_PROFILE_MAEBYEONG);
    /* the jar (half the height) overlaps the maebyeong by 1% of the height
     * where they come closest */
    double jx = 0;
    for (int k = 0; k <= 500; k++) {
        double y = 0.5 * k / 500;
        jx = fmax(jx, synth_profile_radius(SYNTH_PROFILE_MAEBYEONG, y) +
                          0.5 * synth_profile_radius(SYNTH_PROFILE_JAR, 2 * y));
    }
    jx -= 0.01;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int hits = 0;
            for (int sy = 0; sy < 4; sy++)
                for (int sx = 0; sx < 4; sx++) {
                    double x = (i + (sx + 0.5) / 4 - 0.5 * w) / scale, y = (y_base - j - (sy + 0.5) / 4) / scale;
                    hits += inside(s, x, y, rm, jx);
                }
            float c = hits / 16.0f;
            for (int k = 0; k < 3; k++)
                img->data[((size_t)j * w + i) * 3 + k] = (1 - c) * bg[k] + c * fg[k];
        }
    return 0;
}

double drawn_moon_jar_radius(double t)
{
    /* a sphere's 0.46 widest, a foot of 0.17 and a mouth of 0.2, smoothly */
    double s = sin(M_PI * fmin(fmax(t, 0), 1));
    return 0.17 + 0.03 * t + 0.29 * pow(s, 0.75);
}

double drawn_wide_mouth_vase_radius(double t)
{
    return 0.17 + 0.09 * sin(2 * M_PI * (0.85 * t + 0.08)) + 0.25 * pow(t, 6);
}

const char *const drawn_grid_shape_names[DRAWN_GRID_SHAPES] = {"vase", "bowl", "wide_mouth", "moon_jar"};

int drawn_grid_shape_wanted(int argc, char **argv, int s)
{
    int named = 0, wanted = 0;
    for (int a = 1; a < argc; a++)
        for (int k = 0; k < DRAWN_GRID_SHAPES; k++)
            if (!strcmp(argv[a], drawn_grid_shape_names[k]))
                named = 1, wanted |= k == s;
    return named ? wanted : s != DRAWN_GRID_MOON_JAR;
}

pinhole_params drawn_grid_vessel(int s, double elevation_deg, double focal_35mm, int width, int height)
{
    pinhole_params p = pinhole_defaults(s == DRAWN_GRID_BOWL ? SYNTH_BOWL : SYNTH_VASE, elevation_deg);
    if (s == DRAWN_GRID_WIDE_MOUTH)
        p.radius = drawn_wide_mouth_vase_radius;
    if (s == DRAWN_GRID_MOON_JAR)
        p.radius = drawn_moon_jar_radius;
    p.width = width;
    p.height = height;
    p.focal_px = recon_focal_from_35mm(width, height, focal_35mm);
    pinhole_frame(&p);
    return p;
}

void drawn_grid_print_row(const char *shape, const pinhole_params *p, double e, double f35, int rc,
                          const reconstruction *r, const char *err, int gate)
{
    static const char *const methods[] = {"ellipses", "exif", "flag", "orthographic"};
    if (rc != 0) {
        printf("| %s | %g | %g | %.0f | refused: %s |\n", shape, e, f35, p->focal_px, err);
    } else if (!r->has_camera) {
        printf("| %s | %g | %g | %.0f | no camera: %s |\n", shape, e, f35, p->focal_px, r->camera_note);
    } else {
        double mean, max;
        pinhole_profile_error(p, &r->meridian.curve, &mean, &max);
        double axis = fmax(fabs(r->extract.tilt_deg), fabs(r->camera.roll_deg));
        printf("| %s | %g | %g | %.0f | %.0f | %.2f | %s | %.3f / %.3f | %.3f | ", shape, e, f35, p->focal_px,
               r->camera.focal_px, r->camera.elevation_deg, methods[r->camera.method], 100 * mean, 100 * max, axis);
        if (gate)
            printf("%s%s | ", r->quality.passed ? "pass" : "over: ", r->quality.failed);
        printf("%s |\n", r->camera.note);
    }
    fflush(stdout);
}
