/* The rendered perspective grid of docs/algorithms-recon.md, "Perspective"
 * (13.8), as `make check-rendered-grid` prints it: vessels rendered by
 * POV-Ray (tests/support/pov_vessel.c: a thin-walled open lathe on a sweep,
 * soft light and shadow) through pinhole_vessel.h's camera, 600 x 800 px,
 * from 0 to 10 degrees above at focal lengths of 35 to 200 mm (35 mm
 * equivalent), each run through reconstruct_photo as `celadon reconstruct`
 * runs it by default (automatic segmenter, the focal length from the
 * ellipses: no EXIF; --force only so that a result over the quality gate's
 * limits is still measured, and the gate's verdict is a column). Per photo:
 * the camera found, the meridian against the true profile over 3-97% of the
 * height in % of the height, and the axis's angle from the true (vertical)
 * image axis. Arguments: shape names to run (vase, bowl, wide_mouth), WxH
 * for another frame size, keep=DIR to keep the photos there. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "celadon/reconstruct.h"
#include "support/drawn_silhouettes.h"
#include "support/pinhole_vessel.h"
#include "support/pov_vessel.h"

static void run(const char *dir, const char *shape, const pinhole_params *p, double e, double f35)
{
    char pov[1024], png[1024], err[512] = "";
    snprintf(pov, sizeof pov, "%s/%s_e%g_f%g.pov", dir, shape, e, f35);
    snprintf(png, sizeof png, "%s/%s_e%g_f%g.png", dir, shape, e, f35);
    int rendered = pov_vessel_render(p, 0, pov, png, 2, err, sizeof err);
    remove(pov); /* 16 MB of mesh */
    if (rendered != 0) {
        printf("| %s | %g | %g | %.0f | not rendered: %s |\n", shape, e, f35, p->focal_px, err);
        return;
    }
    reconstruct_options opt = reconstruct_options_default();
    opt.force = 1;
    reconstruction r;
    int rc = reconstruct_photo(png, &opt, &r, err, sizeof err);
    drawn_grid_print_row(shape, p, e, f35, rc, &r, err, 1);
    reconstruction_free(&r);
}

int main(int argc, char **argv)
{
    if (!pov_available()) {
        fprintf(stderr, "rendered_grid: povray not found (make deps installs it)\n");
        return 2;
    }
    const double elevations[] = {0, 3, 5, 8, 10}, focals[] = {35, 50, 85, 135, 200};
    int width = 600, height = 800;
    const char *keep = NULL;
    for (int a = 1; a < argc; a++) {
        if (!strncmp(argv[a], "keep=", 5))
            keep = argv[a] + 5;
        else
            sscanf(argv[a], "%dx%d", &width, &height);
    }
    char dir[64] = "/tmp/celadon-rendered-XXXXXX";
    if (!keep && !mkdtemp(dir)) {
        perror("rendered_grid: mkdtemp");
        return 1;
    }
    printf("| shape | elevation ° | focal mm | f px true | f px ours | elevation ours ° | camera | meridian mean / max "
           "%% | axis ° | gate | note |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < DRAWN_GRID_SHAPES; s++)
        for (int k = 0; k < 5 && drawn_grid_shape_wanted(argc, argv, s); k++)
            for (int i = 0; i < 5; i++) {
                pinhole_params p = drawn_grid_vessel(s, elevations[i], focals[k], width, height);
                const char *name = drawn_grid_shape_names[s];
                run(keep ? keep : dir, name, &p, elevations[i], focals[k]);
                if (!keep) {
                    char path[1024];
                    snprintf(path, sizeof path, "%s/%s_e%g_f%g.png", dir, name, elevations[i], focals[k]);
                    remove(path);
                }
            }
    if (!keep)
        rmdir(dir);
    return 0;
}
