/* See vessel_size.h. */
#include "museum/vessel_size.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double vessel_size_height_m(double height_cm, double diameter_cm, double shape_height, double shape_max_radius,
                            vessel_size_source *source)
{
    if (height_cm > 0) {
        *source = VESSEL_SIZE_HEIGHT;
        return height_cm / 100.0;
    }
    if (diameter_cm > 0 && shape_height > 0 && shape_max_radius > 0) {
        *source = VESSEL_SIZE_DIAMETER;
        return diameter_cm / 100.0 * shape_height / (2.0 * shape_max_radius);
    }
    *source = VESSEL_SIZE_DEFAULT;
    return MUSEUM_DEFAULT_HEIGHT_CM / 100.0;
}

void vessel_size_line(double height_cm, double diameter_cm, char *buf, size_t len)
{
    if (height_cm > 0 && diameter_cm > 0)
        snprintf(buf, len, "Height %.1f cm, diameter %.1f cm", height_cm, diameter_cm);
    else if (height_cm > 0)
        snprintf(buf, len, "Height %.1f cm", height_cm);
    else if (diameter_cm > 0)
        snprintf(buf, len, "Diameter %.1f cm; height not recorded", diameter_cm);
    else
        snprintf(buf, len, "Height not recorded");
}

const char *vessel_size_source_name(vessel_size_source s)
{
    return s == VESSEL_SIZE_HEIGHT ? "catalogue height" : s == VESSEL_SIZE_DIAMETER ? "catalogue diameter"
                                                                                    : "default (not recorded)";
}
