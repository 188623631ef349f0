/* A vessel's size in the museum, and what its label may say about it
 * (docs/museum.md, "Sizes"). The catalogue is the only source of facts:
 *
 *   height_cm given          the vessel is that tall (its proportions, and so
 *                            its width, follow from the exact profile);
 *   only diameter_cm given   its widest diameter is that, and its height is
 *                            the one the profile's proportions imply;
 *   neither                  it is MUSEUM_DEFAULT_HEIGHT_CM tall, a
 *                            stand-in the label never states: it says
 *                            "Height not recorded".
 *
 * With both given, the height sets the size and the label states both. */
#ifndef CELADON_MUSEUM_VESSEL_SIZE_H
#define CELADON_MUSEUM_VESSEL_SIZE_H

#include <stddef.h>

#include "celadon/bspline.h"
#include "celadon/museum.h"

typedef enum { VESSEL_SIZE_HEIGHT, VESSEL_SIZE_DIAMETER, VESSEL_SIZE_DEFAULT } vessel_size_source;

/* The vessel's height in metres for the catalogue's height_cm and
 * diameter_cm (0: not given), its shape's height (top minus base, > 0) and
 * largest radius in the shape's own units; *source says which rule held. */
double vessel_size_height_m(double height_cm, double diameter_cm, double shape_height, double shape_max_radius,
                            vessel_size_source *source);

/* The label's line about the size: the catalogue's figures only, e.g.
 * "Height 31.5 cm, diameter 20.0 cm", "Diameter 12.0 cm; height not
 * recorded", "Height not recorded". */
void vessel_size_line(double height_cm, double diameter_cm, char *buf, size_t len);

/* "catalogue height", "catalogue diameter" or "default (not recorded)":
 * museum.json's and the glTF extras' name of the rule. */
const char *vessel_size_source_name(vessel_size_source s);

#endif
