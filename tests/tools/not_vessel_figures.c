/* The figures of the "not a vessel" rule (docs/algorithms-recon.md, "Not a
 * vessel") on vessels and on shapes that are none, as `make check-not-vessel`
 * prints them: recon_extract's axis_gap and base_asymmetry (in % of the
 * object's height) and its verdict, for the synth-dev and real-dev photos
 * (under $CELADON_SHARED, else ../shared; skipped when absent), the drawn
 * hard cases of tests/support/synth_scene.c, vessels drawn through a
 * pinhole from 0 to 20 degrees above, and the drawn silhouettes that are no
 * vessel (tests/support/drawn_silhouettes.c). Arguments, optional: the
 * groups to run (dev, scenes, vessels, shapes). */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "celadon/recon.h"
#include "support/drawn_silhouettes.h"
#include "support/pinhole_vessel.h"
#include "support/synth_profile.h"
#include "support/synth_scene.h"

static void report(const char *group, const char *name, const image_t *img)
{
    recon_result r;
    char err[512] = "";
    recon_status st = recon_extract(img, NULL, &r, err, sizeof err);
    printf("| %s | %s | %.2f | %.2f | %s |\n", group, name, 100 * r.axis_gap, 100 * r.base_asymmetry,
           st == RECON_OK ? "accepted" : err);
    fflush(stdout);
    recon_result_free(&r);
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Every photo of dir/NAME/file (file non-NULL) or dir/NAME ending in .jpg. */
static void shared_photos(const char *dir, const char *file, const char *group)
{
    DIR *d = opendir(dir);
    if (!d) {
        printf("| %s | (%s not found: skipped) | | | |\n", group, dir);
        return;
    }
    char *names[256];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < 256) {
        size_t len = strlen(e->d_name);
        if (e->d_name[0] == '.' || (!file && (len < 4 || strcmp(e->d_name + len - 4, ".jpg"))))
            continue;
        names[n++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof *names, by_name);
    for (int i = 0; i < n; i++) {
        char path[2048], err[512];
        snprintf(path, sizeof path, "%s/%s%s%s", dir, names[i], file ? "/" : "", file ? file : "");
        image_t img;
        if (image_read(path, &img, err, sizeof err) == 0) {
            report(group, names[i], &img);
            image_free(&img);
        }
        free(names[i]);
    }
}

static double maebyeong(double t)
{
    return synth_profile_radius(SYNTH_PROFILE_MAEBYEONG, t);
}

static int g_argc;
static char **g_argv;

static int wanted(const char *group)
{
    int yes = g_argc < 2;
    for (int a = 1; a < g_argc; a++)
        yes |= !strcmp(g_argv[a], group);
    return yes;
}

int main(int argc, char **argv)
{
    g_argc = argc;
    g_argv = argv;
    const char *env = getenv("CELADON_SHARED");
    char dir[1024];
    printf("| group | case | axis gap %% | base asymmetry %% | verdict |\n|---|---|---|---|---|\n");
    if (wanted("dev")) {
        snprintf(dir, sizeof dir, "%s/data/synth-dev", env ? env : "../shared");
        shared_photos(dir, "photo.png", "synth-dev");
        snprintf(dir, sizeof dir, "%s/data/real-dev", env ? env : "../shared");
        shared_photos(dir, NULL, "real-dev");
    }

    for (int i = 0; wanted("scenes") && i < synth_scene_case_count(); i++) {
        synth_scene_params sp;
        image_t img;
        if (synth_scene_case(synth_scene_case_name(i), 600, 800, &sp) != 0 ||
            synth_scene_draw(&sp, &img, NULL, NULL) != 0)
            continue;
        report("drawn scene", synth_scene_case_name(i), &img);
        image_free(&img);
    }

    const char *shape_names[] = {"vase", "bowl", "bottle", "jar", "maebyeong", "moon jar"};
    for (int s = 0; wanted("vessels") && s < 6; s++)
        for (int e = 0; e <= 20; e += 10) {
            pinhole_params p = pinhole_defaults(s < 4 ? (synth_shape)s : SYNTH_VASE, e);
            if (s >= 4) {
                p.radius = s == 4 ? maebyeong : drawn_moon_jar_radius;
                pinhole_frame(&p);
            }
            image_t img;
            if (pinhole_draw(&p, &img, NULL) != 0)
                continue;
            char name[64];
            snprintf(name, sizeof name, "%s, %d deg above", shape_names[s], e);
            report("drawn vessel", name, &img);
            image_free(&img);
        }

    for (int s = 0; wanted("shapes") && s < DRAWN_SILHOUETTE_COUNT; s++) {
        image_t img;
        if (drawn_silhouette_draw((drawn_silhouette)s, 400, 400, &img) != 0)
            continue;
        report("no vessel", drawn_silhouette_name((drawn_silhouette)s), &img);
        image_free(&img);
    }
    return 0;
}
