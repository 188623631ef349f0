/* Perspective reconstruction on the synth-dev photographs (exact cameras and
 * profiles): for each photo, recon_extract then recon_camera_meridian; the
 * recovered elevation and focal length against camera.json, and the
 * meridian, scaled to the true height, against profile.csv over 3-97% of
 * the height, beside today's profile (the image outline's B-spline, as
 * `reconstruct` writes it, scaled the same way). Run by `make bench`
 * (skipped without ../shared/data/synth-dev); the table is in
 * docs/algorithms-recon.md, "Perspective". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tests/support/synthdev_truth.h"
#include "celadon/curve_fit.h"
#include "celadon/recon.h"
#include "celadon/recon_camera.h"

static double thread_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * ts.tv_sec + 1e-6 * ts.tv_nsec;
}

static const char *method_name(recon_camera_method m)
{
    static const char *const names[] = {"ellipses", "exif", "flag", "orthographic"};
    return names[m];
}

static int run(const char *dir, const char *name, const char *file)
{
    char path[1024], err[512];
    synthdev_truth t;
    if (synthdev_truth_load(dir, name, &t, err, sizeof err) != 0) {
        fprintf(stderr, "bench_perspective: %s\n", err);
        return -1;
    }
    snprintf(path, sizeof path, "%s/%s/%s", dir, name, file);
    image_t img;
    recon_result res;
    if (image_read(path, &img, err, sizeof err) != 0 || recon_extract(&img, NULL, &res, err, sizeof err) != RECON_OK) {
        fprintf(stderr, "bench_perspective: %s: %s\n", path, err);
        synthdev_truth_free(&t);
        return -1;
    }
    bspline_t today;
    double t_mean = NAN, t_max = NAN;
    if (bspline_fit_profile(res.polyline, res.n_polyline, 1.0, &today, NULL) == 0) {
        synthdev_profile_error(&t, &today, 0.03, 0.97, &t_mean, &t_max);
        bspline_free(&today);
    }
    recon_camera cam;
    recon_meridian mer;
    double c0 = thread_cpu_ms();
    int rc = recon_camera_meridian(&img, &res, NULL, &cam, &mer, err, sizeof err);
    double ms = thread_cpu_ms() - c0;
    if (rc != 0) {
        printf("| %s | %s | failed: %s |\n", name, file, err);
    } else {
        double m_mean, m_max;
        synthdev_profile_error(&t, &mer.curve, 0.03, 0.97, &m_mean, &m_max);
        printf("| %-27s | %s | %4.1f | %6.2f | %5.0f | %5.0f | %-12s | %.3f / %.3f | **%.3f / %.3f** | %.1f |%s%s\n",
               name, strstr(file, "jpg") ? "JPEG" : "PNG", t.elevation_deg, cam.elevation_deg, t.focal_px,
               cam.focal_px, method_name(cam.method), 100 * t_mean, 100 * t_max, 100 * m_mean, 100 * m_max, ms,
               cam.note[0] ? " " : "", cam.note);
        recon_meridian_free(&mer);
    }
    recon_result_free(&res);
    image_free(&img);
    synthdev_truth_free(&t);
    return 0;
}

int main(void)
{
    char dir[900];
    if (!synthdev_dir(dir, sizeof dir)) {
        printf("bench_perspective: synth-dev data not found at %s (set CELADON_SHARED); skipped\n", dir);
        return 0;
    }
    printf("| case | file | elev. true | elev. ours | f true | f ours | camera from | today mean / max %% | meridian "
           "mean / max %% | CPU ms |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int f = 0; f < 2; f++)
        for (int c = 0; c < SYNTHDEV_NCASES; c++)
            run(dir, SYNTHDEV_CASES[c], f ? "photo.jpg" : "photo.png");
    return 0;
}
