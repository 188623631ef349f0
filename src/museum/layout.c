/* The museum's floor plan: a grid of exhibits in a room that grows with
 * them. See layout.h. */
#include "museum/layout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MIN_CLEARANCE 0.05     /* m: glass at least 5 cm from the vessel */
#define CLEARANCE_FRACTION 0.12 /* ... and 12% of the vessel's larger dimension */
#define DISPLAY_HEIGHT 1.1     /* m: the height the pedestals put the vessels' middles at */
#define MIN_PEDESTAL 0.3
#define MAX_PEDESTAL 0.9
#define MIN_ROOM_HEIGHT 3.0
#define CEILING_MARGIN 1.0     /* m: free height above the tallest case */
#define LABEL_ASPECT 1.5       /* width : height of the label plate */
#define MAX_LABEL_WIDTH 0.3
#define LABEL_DROP 0.06        /* m: the label's top edge below the pedestal's top */
#define LABEL_OFFSET 0.002     /* m: in front of the pedestal face, so the two never coincide */
#define SIGN_GAP 0.04           /* m: between the label and the sign */
#define SIGN_FLOOR 0.08         /* m: the sign's bottom at least this far above the floor */
#define LIGHT_DROP 0.03        /* m: the case light below the lid */
#define CAMERA_YFOV_DEG 60.0
#define PENDANT_DROP 0.6       /* m: ceiling lights hang this far under the ceiling */
#define CAMERA_ASPECT (16.0 / 9.0)

double layout_clearance(const layout_vessel *v)
{
    return fmax(MIN_CLEARANCE, CLEARANCE_FRACTION * fmax(v->height, 2.0 * v->radius));
}

static int vessels_valid(const layout_vessel *v, int n)
{
    if (!v || n < 1)
        return 0;
    for (int i = 0; i < n; i++)
        if (!(isfinite(v[i].height) && isfinite(v[i].radius) && v[i].height > 0 && v[i].radius > 0))
            return 0;
    return 1;
}

static layout_exhibit exhibit_for(const layout_vessel *v, vec3 centre)
{
    double clear = layout_clearance(v);
    layout_exhibit e = {.centre = centre};
    e.width = fmax(LAYOUT_MIN_FOOTPRINT, 2.0 * (v->radius + clear));
    e.pedestal_height = fmin(MAX_PEDESTAL, fmax(MIN_PEDESTAL, DISPLAY_HEIGHT - 0.5 * v->height));
    e.case_height = v->height + clear;
    e.vessel_base = v3(centre.x, e.pedestal_height, centre.z);
    e.light = v3(centre.x, e.pedestal_height + e.case_height - LIGHT_DROP, centre.z);
    e.label_width = fmin(MAX_LABEL_WIDTH, 0.9 * e.width);
    e.label_height = e.label_width / LABEL_ASPECT;
    e.label_centre = v3(centre.x, e.pedestal_height - LABEL_DROP - 0.5 * e.label_height,
                        centre.z + 0.5 * e.width + LABEL_OFFSET);
    /* The sign: as many lines as the face has room for under the label. */
    double room = e.label_centre.y - 0.5 * e.label_height - SIGN_GAP - SIGN_FLOOR;
    e.sign_lines = (int)floor((room / LAYOUT_SIGN_CAP - LAYOUT_SIGN_PAD) / LAYOUT_SIGN_PITCH);
    e.sign_lines = e.sign_lines < 0 ? 0 : e.sign_lines > LAYOUT_SIGN_LINES ? LAYOUT_SIGN_LINES : e.sign_lines;
    e.sign_width = 0.9 * e.width;
    e.sign_height = e.sign_lines ? LAYOUT_SIGN_CAP * (LAYOUT_SIGN_PAD + LAYOUT_SIGN_PITCH * e.sign_lines) : 0.0;
    e.sign_centre = v3(centre.x, e.label_centre.y - 0.5 * e.label_height - SIGN_GAP - 0.5 * e.sign_height,
                       e.label_centre.z);
    return e;
}

/* Ceiling lights on a regular grid, at most LAYOUT_CEILING_LIGHT_SPACING apart. */
static int place_ceiling_lights(layout_t *l)
{
    int nx = (int)ceil(l->width / LAYOUT_CEILING_LIGHT_SPACING);
    int nz = (int)ceil(l->depth / LAYOUT_CEILING_LIGHT_SPACING);
    l->ceiling_lights = malloc((size_t)(nx * nz) * sizeof *l->ceiling_lights);
    if (!l->ceiling_lights)
        return -1;
    for (int i = 0; i < nz; i++)
        for (int j = 0; j < nx; j++)
            l->ceiling_lights[l->n_ceiling_lights++] =
                v3(l->width * ((j + 0.5) / nx - 0.5), l->height - PENDANT_DROP, l->depth * ((i + 0.5) / nz - 0.5));
    return 0;
}

/* Row `row` of the grid: as long as its own footprints and the aisles
 * between them, as deep as its widest footprint. */
static void row_size(const layout_t *l, int row, double *length, double *depth)
{
    *length = -LAYOUT_AISLE, *depth = 0.0;
    for (int i = row * l->columns; i < l->n_exhibits && i < (row + 1) * l->columns; i++)
        *length += l->exhibits[i].width + LAYOUT_AISLE, *depth = fmax(*depth, l->exhibits[i].width);
}

int layout_make(const layout_vessel *vessels, int n, layout_t *out)
{
    memset(out, 0, sizeof *out);
    if (!vessels_valid(vessels, n))
        return -1;
    out->exhibits = calloc((size_t)n, sizeof *out->exhibits);
    if (!out->exhibits)
        return -1;
    out->n_exhibits = n;
    /* A near-square grid, wider than deep when it cannot be square. */
    out->columns = (int)ceil(sqrt((double)n));
    out->rows = (n + out->columns - 1) / out->columns;
    /* Each exhibit where it would stand at the origin, for its size. */
    double tallest = 0.0, widest_row = 0.0, rows_depth = 0.0;
    for (int i = 0; i < n; i++) {
        out->exhibits[i] = exhibit_for(&vessels[i], v3(0, 0, 0));
        tallest = fmax(tallest, out->exhibits[i].pedestal_height + out->exhibits[i].case_height);
    }
    for (int row = 0; row < out->rows; row++) {
        double length, depth;
        row_size(out, row, &length, &depth);
        widest_row = fmax(widest_row, length);
        rows_depth += depth + LAYOUT_AISLE;
    }
    out->width = widest_row + 2.0 * LAYOUT_AISLE;
    out->depth = rows_depth + LAYOUT_AISLE + LAYOUT_ENTRANCE;
    out->height = fmax(MIN_ROOM_HEIGHT, tallest + CEILING_MARGIN);
    /* Row by row from the entrance, each row centred on x = 0 and its
     * exhibits centred on its middle line. */
    double front = 0.5 * out->depth - LAYOUT_ENTRANCE - LAYOUT_AISLE; /* z of the first row's front edge */
    double z_front = front;
    for (int row = 0; row < out->rows; row++) {
        int first = row * out->columns, last = first + out->columns < n ? first + out->columns : n;
        double length, depth;
        row_size(out, row, &length, &depth);
        double x = -0.5 * length;
        for (int i = first; i < last; i++) {
            double w = out->exhibits[i].width;
            out->exhibits[i] = exhibit_for(&vessels[i], v3(x + 0.5 * w, 0, z_front - 0.5 * depth));
            x += w + LAYOUT_AISLE;
        }
        z_front -= depth + LAYOUT_AISLE;
    }
    if (place_ceiling_lights(out) != 0) {
        layout_free(out);
        return -1;
    }
    /* The camera stands in the entrance zone and looks at the middle of the
     * exhibits at display height. */
    double zc = 0.5 * (front + z_front + LAYOUT_AISLE);
    out->camera_position = v3(0, LAYOUT_EYE_HEIGHT, 0.5 * out->depth - 0.5 * LAYOUT_ENTRANCE);
    out->camera_target = v3(0, DISPLAY_HEIGHT, zc);
    out->camera_yfov_deg = CAMERA_YFOV_DEG;
    out->camera_aspect = CAMERA_ASPECT;
    return 0;
}

void layout_free(layout_t *l)
{
    free(l->exhibits);
    free(l->ceiling_lights);
    memset(l, 0, sizeof *l);
}
