/* One exhibit of the museum as the writers see it: the reconstructed vessel
 * at its real size, its levels of detail, its texture and label. */
#ifndef CELADON_MUSEUM_EXHIBIT_H
#define CELADON_MUSEUM_EXHIBIT_H

#include <stddef.h>
#include <stdint.h>

#include "celadon/bspline.h"
#include "museum/lod.h"
#include "museum/vessel_size.h"

/* The label's line for a vessel included with --force. */
#define MUSEUM_BELOW_GATE_NOTE "Shape uncertain: below the quality gate (shown with --force)"

typedef struct {
    const char *photo;        /* the photo as given */
    char slug[96];            /* unique file-name form of the title: vessels/SLUG/, labels/SLUG.png */
    char *title, *date, *description; /* owned; date and description may be NULL */
    double height_cm_given, diameter_cm_given; /* the catalogue's, 0 when not given */
    vessel_size_source size_source; /* which rule of vessel_size.h set height_m */
    int below_gate;           /* failed the quality gate, included with --force */
    double height_m;          /* real height: the vessel's top (bspline_largest; a rolled lip puts it above
                               * the rim) at y = height_m */
    double rim_height_m;      /* where that puts the curve's end, the rim (mesh_revolve's and sor's height) */
    double radius_m;          /* the curve's largest radius (bspline_largest) */
    bspline_t curve;          /* the shape (profile_shape): (r, h), px, or units of the height for a meridian */
    lod_level lods[LOD_MAX_LEVELS];
    int n_lods;
    uint8_t *texture_jpg, *label_png, *sign_png; /* the glb's images: the texture as JPEG, the label and the
                                                  * title sign as PNG (sign NULL: none); owned */
    size_t texture_len, label_len, sign_len;
} museum_exhibit;

void museum_exhibit_free(museum_exhibit *e);

#endif
