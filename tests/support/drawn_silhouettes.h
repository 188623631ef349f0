/* Silhouettes drawn for the "not a vessel" rule (docs/algorithms-recon.md,
 * "Not a vessel"): flat shapes that are no surface of revolution (a star,
 * an L, two vessels touching, a person, a chair), and the profiles of a
 * moon jar and a wide-mouthed vase for pinhole_params.radius. Each shape is defined in a frame of unit
 * height (y up from its lowest point, x centred), drawn in a celadon green
 * on a near-white backdrop at 70% of the image's height, anti-aliased by 4 x 4 samples per
 * pixel. */
#ifndef CELADON_TESTS_DRAWN_SILHOUETTES_H
#define CELADON_TESTS_DRAWN_SILHOUETTES_H

#include "celadon/image.h"
#include "celadon/reconstruct.h"
#include "pinhole_vessel.h"

typedef enum {
    DRAWN_STAR,            /* five-pointed, one point up: mirror-symmetric, backdrop between its legs */
    DRAWN_L,               /* an upright bar with a foot to the right */
    DRAWN_TWIN_VESSELS,    /* two maebyeong touching at their bellies */
    DRAWN_VESSEL_AND_JAR,  /* a maebyeong and a jar half its height touching it, on one floor */
    DRAWN_PERSON,          /* standing, from the front: head, arms apart from the body, legs apart */
    DRAWN_CHAIR_FRONT,     /* back, seat and two legs */
    DRAWN_CHAIR_SIDE,      /* a back post over one end of the seat, a leg at each end */
    DRAWN_SILHOUETTE_COUNT
} drawn_silhouette;

/* A short lowercase name ("star"); NULL out of range. */
const char *drawn_silhouette_name(drawn_silhouette s);

/* Draws s into a fresh 3-channel w x h image. Returns 0, or -1 when out of
 * memory. */
int drawn_silhouette_draw(drawn_silhouette s, int w, int h, image_t *img);

/* A moon jar's radius at t in [0, 1] (units of its height): a near sphere
 * on a narrow foot under a short mouth (pinhole_params.radius). */
double drawn_moon_jar_radius(double t);

/* A vase whose mouth flares wider than its belly (a trumpet mouth):
 * synth_vessel's vase plus 0.25 t^6, radius 0.38 at the rim against 0.26 at
 * the belly (the perspective grid's wide-mouthed vase). */
double drawn_wide_mouth_vase_radius(double t);

/* The perspective grids' vessels (tests/tools/perspective_grid.c,
 * rendered_grid.c, test_recon_rendered.c), named "vase", "bowl",
 * "wide_mouth", and "moon_jar" (drawn_moon_jar_radius), which the grids
 * run only when it is named: its camera is issue 25's open failure
 * (docs/algorithms-recon.md 13.9), the grids' documented tables are the
 * other three. */
enum { DRAWN_GRID_VASE, DRAWN_GRID_BOWL, DRAWN_GRID_WIDE_MOUTH, DRAWN_GRID_MOON_JAR, DRAWN_GRID_SHAPES };
extern const char *const drawn_grid_shape_names[DRAWN_GRID_SHAPES];

/* Whether the grid runs shape s: every shape but the moon jar when no
 * argument names one, else the ones named. */
int drawn_grid_shape_wanted(int argc, char **argv, int s);

/* Grid shape s seen from elevation_deg above at focal_35mm (35 mm
 * equivalent) in a width x height frame, pinhole_defaults' framing. */
pinhole_params drawn_grid_vessel(int s, double elevation_deg, double focal_35mm, int width, int height);

/* Prints the grid's table row for a reconstruction of p's photo: rc and
 * err as reconstruct_image gave them; the camera, the meridian against the
 * truth (% of the height) and the axis; with gate, the quality gate's
 * verdict as one more column. */
void drawn_grid_print_row(const char *shape, const pinhole_params *p, double e, double f35, int rc,
                          const reconstruction *r, const char *err, int gate);

#endif
