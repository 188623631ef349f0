/* The museum's floor plan, made from the number and sizes of the vessels
 * alone (docs/museum.md, "Layout").
 *
 * World frame: metres, Y up, the floor at y = 0, the room centred on x = 0
 * and z = 0. The entrance is in the middle of the front wall (z = +depth/2);
 * the visitor enters looking toward -z. Every vessel faces the entrance: its
 * photographed side (texture u = 0.5, object +z) looks toward +z.
 *
 * Each exhibit is a pedestal with a closed glass case on it, both of the
 * same square footprint, the vessel standing on the pedestal in the middle of
 * the case. Exhibits stand in rows of `columns` (the last row may hold
 * fewer), each row as long as its own footprints and the aisles between them
 * and as deep as its widest footprint, so the room is as large as the
 * collection needs, not as its largest piece times the count; between any
 * two footprints, between a footprint and a wall, and in front of the first
 * row there is at least LAYOUT_AISLE metres of free floor (exactly that
 * along each row and between rows), and the entrance zone adds
 * LAYOUT_ENTRANCE in front of that. */
#ifndef CELADON_MUSEUM_LAYOUT_H
#define CELADON_MUSEUM_LAYOUT_H

#include "celadon/vecmath.h"

#define LAYOUT_AISLE 1.5        /* m: free width of every aisle (a wheelchair turns in 1.5 m) */
#define LAYOUT_ENTRANCE 1.5     /* m: free floor between the entrance wall and the first aisle */
#define LAYOUT_EYE_HEIGHT 1.6   /* m: the entrance camera */
#define LAYOUT_CEILING_LIGHT_SPACING 4.0 /* m: at most this far apart */
/* The entrance door: in the middle of the entrance wall, behind the entrance
 * camera, at most LAYOUT_ENTRANCE / 2 in front of it. */
#define LAYOUT_DOOR_WIDTH 1.0
#define LAYOUT_DOOR_HEIGHT 2.1
/* Every footprint is at least this wide (a plinth of a real museum; the
 * title sign needs the width). */
#define LAYOUT_MIN_FOOTPRINT 0.6
/* The title sign on each pedestal's front, under the label: the title in
 * capitals LAYOUT_SIGN_CAP tall (8 px and more at 960x540 from the
 * entrance for the first row, 60 degrees of field: f = 468 px over a
 * distance up to 3.2 m), on at most LAYOUT_SIGN_LINES lines; a line takes
 * LAYOUT_SIGN_PITCH capitals of height and the plate LAYOUT_SIGN_PAD more
 * (the first line's ascent and the last one's descent, margins). */
#define LAYOUT_SIGN_CAP 0.055
#define LAYOUT_SIGN_LINES 2
#define LAYOUT_SIGN_PITCH 1.8
#define LAYOUT_SIGN_PAD 1.2

typedef struct {
    double height, radius; /* m: the vessel's height and its largest radius (a bound) */
} layout_vessel;

typedef struct {
    vec3 centre;            /* footprint centre on the floor (y = 0) */
    double width;           /* side of the square footprint of pedestal and case, m */
    double pedestal_height; /* the vessel's base stands at centre + (0, pedestal_height, 0) */
    double case_height;     /* inner height of the glass case above the pedestal */
    vec3 vessel_base;       /* where the vessel's base centre stands */
    vec3 light;             /* the case light, under the case's lid */
    vec3 label_centre;      /* the label, on the pedestal's front face (+z), facing +z */
    double label_width, label_height;
    int sign_lines;         /* the title sign's lines (0: no room for one on the pedestal's face) */
    vec3 sign_centre;       /* under the label, on the same face */
    double sign_width, sign_height;
} layout_exhibit;

typedef struct {
    double width, depth, height; /* the room: x in [-width/2, width/2], z in [-depth/2, depth/2] */
    int columns, rows;           /* exhibits per row (the last may hold fewer), rows */
    int n_exhibits;
    layout_exhibit *exhibits;    /* in the order of the vessels given */
    int n_ceiling_lights;
    vec3 *ceiling_lights;
    vec3 camera_position, camera_target; /* the entrance camera */
    double camera_yfov_deg, camera_aspect;
} layout_t;

/* Lays out n >= 1 vessels (positive, finite sizes). Exhibits fill the rows
 * from the entrance, left to right, each row centred on x = 0 and each
 * exhibit on its row's middle line. Returns 0, or -1 for bad
 * arguments or out of memory. */
int layout_make(const layout_vessel *vessels, int n, layout_t *out);
void layout_free(layout_t *l);

/* The footprint gap every exhibit keeps around its vessel: the glass is
 * this far from the vessel's widest point and above its top. */
double layout_clearance(const layout_vessel *v);

#endif
