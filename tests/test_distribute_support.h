/* Helpers of the distributed-render tests (test_distribute_mpi.c,
 * test_parts.c): a scene whose camera orbits with -D frame, the CLI run in a
 * fixture folder, and images compared within float rounding. */
#ifndef CELADON_TEST_DISTRIBUTE_SUPPORT_H
#define CELADON_TEST_DISTRIBUTE_SUPPORT_H

#include <math.h>

#include "celadon/image.h"
#include "support/cli_run.h"
#include "test_render_util.h"

/* 64x48 and 96 spp: 295 k camera samples, 18 units of the distribution plan
 * (distribute_plan.h) for any of 1 to 3 ranks. The camera orbits the
 * vessel by $frame degrees; an off-axis light and a floor make every frame
 * different. */
static const char *const orbit_xml =
    "<scene version=\"3.0.0\">\n"
    "  <default name=\"spp\" value=\"96\"/>\n"
    "  <default name=\"frame\" value=\"0\"/>\n"
    "  <sensor type=\"perspective\">\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0.8, 3\" target=\"0, 0.4, 0\" up=\"0, 1, 0\"/>\n"
    "      <rotate y=\"1\" angle=\"$frame\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"64\"/><integer name=\"height\" value=\"48\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sor\"><string name=\"filename\" value=\"profile.json\"/>\n"
    "    <bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.3\"/></bsdf></shape>\n"
    "  <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><scale value=\"3\"/></transform></shape>\n"
    "  <shape type=\"disk\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/><translate x=\"1.5\" y=\"2\"/></transform>\n"
    "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"6\"/></emitter></shape>\n"
    "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.1\"/></emitter>\n"
    "</scene>\n";

/* Runs celadon with args; exit code, stderr into err. */
static inline int run_celadon(const render_fixture *f, const char *const *args, char *err, size_t errlen)
{
    cli_result r = cli_run(f->dir, args);
    snprintf(err, errlen, "%s", r.err);
    cli_result_free(&r);
    return r.status;
}

/* dir/name into out. */
static inline const char *fixture_path(const render_fixture *f, const char *name, char *out, size_t outlen)
{
    snprintf(out, outlen, "%s/%s", f->dir, name);
    return out;
}

static inline image_t read_image(const char *path)
{
    image_t img;
    char why[512];
    cr_assert_eq(image_read(path, &img, why, sizeof why), 0, "%s: %s", path, why);
    return img;
}

/* Whether two float images agree within float rounding of their sums: the
 * largest difference relative to max(1, |a|), in *worst. */
static inline int same_within_rounding(const image_t *a, const image_t *b, double *worst)
{
    *worst = INFINITY;
    if (a->width != b->width || a->height != b->height || a->channels != b->channels)
        return 0;
    *worst = 0.0;
    size_t n = (size_t)a->width * a->height * a->channels;
    for (size_t i = 0; i < n; i++) {
        double d = fabs((double)a->data[i] - b->data[i]) / fmax(1.0, fabs((double)a->data[i]));
        *worst = d > *worst ? d : *worst;
    }
    return *worst <= 1e-6;
}

#endif
