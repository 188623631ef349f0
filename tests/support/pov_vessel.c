/* Rendered vessel photographs by POV-Ray (pov_vessel.h). */
#include "pov_vessel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Profile samples per wall, azimuth steps, the area light's side and the
 * anti-aliasing's depth, fine and draft. 360 (180) steps put a chord at
 * most r (1 - cos(pi/360)) < 4e-5 (1.5e-4) heights inside the circle, and
 * 200 (100) samples the profile's chords 0.8e-5 (3.2e-5) heights off it at
 * the vase's curvature, far below the 0.3% the grid measures. */
typedef struct {
    int samples, azimuth, light, aa_depth;
} mesh_quality;
static const mesh_quality QUALITY[2] = {{200, 360, 5, 3}, {100, 180, 3, 2}};
enum { MAX_SAMPLES = 200 };
static const double WALL = 0.015, FLOOR = 0.03;
static const double PI = 3.14159265358979323846;

int pov_available(void)
{
    return system("command -v povray >/dev/null 2>&1") == 0;
}

/* A point of the cross-section (r, y) with its outward normal (nr, ny). */
typedef struct {
    double r, y, nr, ny;
} section_point;

/* The open vessel's cross-section as strips, each a run of points that one
 * smooth surface passes through (the normals jump between strips): the
 * outer wall, the rim's flat top, the inner wall (the outer one moved
 * inward by WALL, facing the axis), the inside floor and the foot. Returns
 * the number of points; strip_end[k] is one past strip k's last point. */
static int cross_section(const pinhole_params *p, int samples, section_point *pt, int strip_end[5])
{
    int n = 0;
    const double dt = 1e-5;
    for (int i = 0; i <= samples; i++) { /* outer wall (r(t), t): normal (1, -r') */
        double t = (double)i / samples, d = (pinhole_radius(p, fmin(1, t + dt)) - pinhole_radius(p, fmax(0, t - dt))) /
                                                  (fmin(1, t + dt) - fmax(0, t - dt));
        double len = sqrt(1 + d * d);
        pt[n++] = (section_point){pinhole_radius(p, t), t, 1 / len, -d / len};
    }
    strip_end[0] = n;
    double r1 = pinhole_radius(p, 1);
    pt[n++] = (section_point){r1, 1, 0, 1};
    pt[n++] = (section_point){r1 - WALL, 1, 0, 1};
    strip_end[1] = n;
    for (int i = samples; i >= 0; i--) { /* inner wall, facing the axis: normal (-1, r') */
        double t = FLOOR + (1 - FLOOR) * i / samples;
        double d = (pinhole_radius(p, t + dt) - pinhole_radius(p, t - dt)) / (2 * dt), len = sqrt(1 + d * d);
        pt[n++] = (section_point){pinhole_radius(p, t) - WALL, t, -1 / len, d / len};
    }
    strip_end[2] = n;
    pt[n++] = (section_point){pinhole_radius(p, FLOOR) - WALL, FLOOR, 0, 1};
    pt[n++] = (section_point){0, FLOOR, 0, 1};
    strip_end[3] = n;
    pt[n++] = (section_point){0, 0, 0, -1};
    pt[n++] = (section_point){pinhole_radius(p, 0), 0, 0, -1};
    strip_end[4] = n;
    return n;
}

/* The vessel as a smooth-shaded triangle mesh of its cross-section swept
 * about the y axis (POV-Ray's mesh2: its bounding hierarchy makes the soft
 * shadow's many rays cheap, where a lathe of this many segments is not). */
static void write_vessel(FILE *f, const pinhole_params *p, const mesh_quality *q)
{
    section_point pt[2 * (MAX_SAMPLES + 1) + 6];
    int strip_end[5], n = cross_section(p, q->samples, pt, strip_end), M = q->azimuth;
    fprintf(f, "mesh2 {\n  vertex_vectors { %d", n * M);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < M; j++) {
            double a = 2 * PI * j / M;
            fprintf(f, ",\n<%.8f,%.8f,%.8f>", pt[i].r * cos(a), pt[i].y, pt[i].r * sin(a));
        }
    fprintf(f, " }\n  normal_vectors { %d", n * M);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < M; j++) {
            double a = 2 * PI * j / M;
            fprintf(f, ",\n<%.6f,%.6f,%.6f>", pt[i].nr * cos(a), pt[i].ny, pt[i].nr * sin(a));
        }
    int faces = 0;
    for (int k = 0, first = 0; k < 5; first = strip_end[k++])
        faces += 2 * M * (strip_end[k] - first - 1);
    fprintf(f, " }\n  face_indices { %d", faces);
    for (int k = 0, first = 0; k < 5; first = strip_end[k++])
        for (int i = first; i + 1 < strip_end[k]; i++)
            for (int j = 0; j < M; j++) {
                int a = i * M + j, b = i * M + (j + 1) % M, c = a + M, d = b + M;
                fprintf(f, ",\n<%d,%d,%d>,<%d,%d,%d>", a, b, c, b, d, c);
            }
    fprintf(f, " }\n  pigment { rgb <0.30, 0.50, 0.40> }\n"
               "  finish { ambient 0.12 diffuse 0.75 phong 0.35 phong_size 60 }\n}\n");
}

/* A white matte sweep: the floor (y = 0) runs back to z0, curves up along a
 * quarter cylinder of radius rc and goes on as a wall. */
static void write_sweep(FILE *f, double z0, double rc)
{
    fprintf(f,
            "union {\n"
            "  box { <-80, -1, -80>, <80, 0, %.6f> }\n"
            "  difference { box { <-80, -1, %.6f>, <80, %.6f, %.6f> }\n"
            "               cylinder { <-81, %.6f, %.6f>, <81, %.6f, %.6f>, %.6f } }\n"
            "  box { <-80, %.6f, %.6f>, <80, 80, %.6f> }\n"
            "  pigment { rgb <0.86, 0.86, 0.84> }\n"
            "  finish { ambient 0.25 diffuse 0.65 }\n}\n",
            z0, z0, rc, z0 + rc, rc, z0, rc, z0, rc, rc - 1e-4, z0 + rc, z0 + rc + 1);
}

static int write_scene(const pinhole_params *p, const mesh_quality *q, const char *pov_path, char *err, size_t errlen)
{
    FILE *f = fopen(pov_path, "w");
    if (!f) {
        snprintf(err, errlen, "%s: cannot write the scene", pov_path);
        return -1;
    }
    vec3 loc = pinhole_camera_location(p);
    double rmax = 0;
    for (int i = 0; i <= q->samples; i++)
        rmax = fmax(rmax, pinhole_radius(p, (double)i / q->samples));
    /* angle is the horizontal field of view; right and up give square pixels */
    double fov = 2 * atan(0.5 * p->width / p->focal_px) * 180 / PI;
    fprintf(f,
            "global_settings { assumed_gamma 1.0 }\n"
            "camera { perspective location <%.9f, %.9f, %.9f> look_at <0, %.9f, 0>\n"
            "         right x * %d / %d up y angle %.9f }\n"
            "light_source { <-3, 5, -5> rgb 0.95\n"
            "  area_light <1.6, 0, 0>, <0, 0, 1.6>, %d, %d adaptive 1 circular orient }\n"
            "light_source { <5, 2.5, -6> rgb 0.30 shadowless }\n",
            loc.x, loc.y, loc.z, p->look_at_height, p->width, p->height, fov, q->light, q->light);
    write_vessel(f, p, q);
    write_sweep(f, rmax + 0.8, 2.0);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        snprintf(err, errlen, "%s: cannot write the scene", pov_path);
        return -1;
    }
    return 0;
}

int pov_vessel_render(const pinhole_params *p, int draft, const char *pov_path, const char *png_path, int threads,
                      char *err, size_t errlen)
{
    const mesh_quality *q = &QUALITY[draft != 0];
    if (write_scene(p, q, pov_path, err, errlen) != 0)
        return -1;
    /* -GA: no text streams; +A0.05 +AM2 +R: adaptive anti-aliasing to
     * aa_depth levels; the I/O restriction of Debian's povray.conf allows
     * the paths given on the command line. */
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "povray -GA -D +I'%s' +O'%s' +W%d +H%d +FN8 +A0.05 +AM2 +R%d +WT%d File_Gamma=sRGB >/dev/null 2>&1",
             pov_path, png_path, p->width, p->height, q->aa_depth, threads > 0 ? threads : 1);
    if (system(cmd) != 0) {
        snprintf(err, errlen, "%s: povray failed", pov_path);
        return -1;
    }
    return 0;
}
